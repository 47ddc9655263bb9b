// SPDX-License-Identifier: AGPL-3.0-or-later
// A patch against itself and the mesh faces near it (those whose bounding
// boxes meet the patch's), with the exact predicates of the validator.
#include "fill/patch_check.h"

#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <limits>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "dot/fill_holes.h"
#include "dot/validate.h"
#include "mesh/edge_index.h"
#include "mesh/topology.h"
#include "util/run_control.h"

namespace dot {

namespace {

// The positions `faces` use, and `faces` renumbered over them.
std::vector<Vec3> LocalPoints(const std::function<const Vec3&(int32_t)>& point,
                              std::vector<Triangle>* faces) {
  std::unordered_map<int32_t, int32_t> local;
  std::vector<Vec3> points;
  for (Triangle& t : *faces) {
    for (int32_t& v : t) {
      auto [it, added] = local.emplace(v, static_cast<int32_t>(points.size()));
      if (added) points.push_back(point(v));
      v = it->second;
    }
  }
  return points;
}

}  // namespace

Status CountPairsAmong(const std::function<const Vec3&(int32_t)>& point,
                       std::vector<Triangle> faces, size_t checked,
                       const Control& control, int64_t* pairs) {
  const std::vector<Vec3> points = LocalPoints(point, &faces);
  return CountIntersectingPairs(points, faces, checked, control, pairs);
}

namespace {

// A patch id's position: mesh ids, then the patch's new vertices.
std::function<const Vec3&(int32_t)> PatchPoints(const MeshData& mesh,
                                                int32_t first_new_id,
                                                const HolePatch& patch) {
  return [&mesh, &patch, first_new_id](int32_t id) -> const Vec3& {
    return id < first_new_id ? mesh.vertices[id]
                             : patch.new_vertices[id - first_new_id];
  };
}

// The patch faces first, then its split faces' pieces, then the mesh faces
// (other than those split) whose boxes meet the patch's; returns how many
// faces the first two make.
size_t PatchAndNearFaces(const MeshData& mesh, const MeshTopology& topology,
                         const std::function<const Vec3&(int32_t)>& point,
                         const HolePatch& patch, std::vector<Triangle>* faces,
                         std::vector<int32_t>* mesh_ids = nullptr) {
  *faces = patch.faces;
  for (const auto& pieces : patch.pieces) {
    faces->insert(faces->end(), pieces.begin(), pieces.end());
  }
  const size_t own = faces->size();
  Box3 box;
  for (const Triangle& t : patch.faces) {
    for (int32_t v : t) box.Add(point(v));
  }
  std::vector<int32_t> near;
  topology.face_tree->FacesMeeting(box, &near);
  const std::unordered_set<int32_t> split(patch.split_faces.begin(),
                                          patch.split_faces.end());
  for (int32_t f : near) {
    if (split.count(f)) continue;
    faces->push_back(mesh.triangles[f]);
    if (mesh_ids) mesh_ids->push_back(f);
  }
  return own;
}

// The per-patch checks query the face tree, which BuildMeshAdjacency omits.
Status NeedFaceTree(const MeshTopology& topology, const char* who) {
  if (topology.face_tree) return OkStatus();
  return MakeStatus(StatusCode::kInternal,
                    std::string(who) + " needs BuildMeshTopology's face tree");
}

}  // namespace

Status PatchIntersections(const MeshData& mesh, const MeshTopology& topology,
                          int32_t first_new_id, const HolePatch& patch,
                          const Control& control, int64_t* pairs) {
  if (Status s = NeedFaceTree(topology, "PatchIntersections"); !s.ok())
    return s;
  const auto point = PatchPoints(mesh, first_new_id, patch);
  std::vector<Triangle> faces;
  PatchAndNearFaces(mesh, topology, point, patch, &faces);
  return CountPairsAmong(point, std::move(faces), patch.faces.size(), control,
                         pairs);
}

Status InputCrossingsNear(const MeshData& mesh, const MeshTopology& topology,
                          int32_t first_new_id, const HolePatch& patch,
                          const Control& control, InputCrossings* out) {
  *out = {};
  if (Status s = NeedFaceTree(topology, "InputCrossingsNear"); !s.ok())
    return s;
  const auto point = PatchPoints(mesh, first_new_id, patch);
  std::vector<Triangle> faces;
  std::vector<int32_t> ids;  // mesh face of faces[own + k]
  const size_t own =
      PatchAndNearFaces(mesh, topology, point, patch, &faces, &ids);
  const std::vector<Vec3> points = LocalPoints(point, &faces);
  std::vector<std::pair<int32_t, int32_t>> pairs;
  Status s =
      ListIntersectingPairs(points, faces, faces.size(), control, &pairs);
  if (!s.ok()) return s;
  // Mesh faces the input's own crossings touch, grown by rings of faces
  // around their vertices; and the mesh faces the patch crosses.
  std::unordered_set<int32_t> near_crossing, crossed;
  for (auto [a, b] : pairs) {  // a < b: the patch's faces come first
    if (static_cast<size_t>(b) < own) {
      ++out->own_pairs;
    } else if (static_cast<size_t>(a) < own) {
      ++out->patch_pairs;
      crossed.insert(ids[b - own]);
    } else {
      ++out->input_pairs;
      near_crossing.insert(ids[a - own]);
      near_crossing.insert(ids[b - own]);
    }
  }
  std::vector<int32_t> frontier(near_crossing.begin(), near_crossing.end());
  for (int ring = 0; ring < kCrossingRings && !frontier.empty(); ++ring) {
    std::vector<int32_t> next;
    for (int32_t f : frontier) {
      for (int32_t v : mesh.triangles[f]) {
        for (int32_t k = topology.face_begin[v]; k < topology.face_begin[v + 1];
             ++k) {
          if (near_crossing.insert(topology.faces[k]).second) {
            next.push_back(topology.faces[k]);
          }
        }
      }
    }
    frontier = std::move(next);
  }
  for (auto [a, b] : pairs) {
    if (static_cast<size_t>(a) < own && static_cast<size_t>(b) >= own &&
        !near_crossing.count(ids[b - own])) {
      ++out->away_pairs;
    }
  }
  return OkStatus();
}

Status IntersectingChords(const MeshData& mesh, const MeshTopology& topology,
                          int32_t first_new_id, const HolePatch& patch,
                          const Control& control,
                          std::vector<std::pair<int32_t, int32_t>>* chords,
                          bool own_only) {
  chords->clear();
  if (Status s = NeedFaceTree(topology, "IntersectingChords"); !s.ok())
    return s;
  RunTicker ticker(control, "the intersection check");
  const auto point = PatchPoints(mesh, first_new_id, patch);
  std::vector<Triangle> faces;  // as PatchIntersections sees them
  const size_t own = PatchAndNearFaces(mesh, topology, point, patch, &faces);
  if (own_only) faces.resize(own);
  // Each patch face with the faces whose boxes meet its own (one box
  // intersection pass), then the exact test on that small set.
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int32_t>;
  std::vector<Box> boxes;
  for (size_t f = 0; f < faces.size(); ++f) {
    Box3 b;
    for (int32_t v : faces[f]) b.Add(point(v));
    boxes.emplace_back(
        CGAL::Bbox_3(b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z),
        static_cast<int32_t>(f));
  }
  const size_t checked = patch.faces.size();
  std::vector<std::vector<int32_t>> meets(checked);
  struct Stop {};
  try {
    CGAL::box_self_intersection_d(
        boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
          if (!ticker.Tick()) throw Stop{};
          const auto a = static_cast<size_t>(x.info()),
                     b = static_cast<size_t>(y.info());
          if (a < checked) meets[a].push_back(y.info());
          if (b < checked) meets[b].push_back(x.info());
        });
  } catch (const Stop&) {
    return ticker.status();
  }
  std::unordered_map<uint64_t, int> uses;
  for (const Triangle& t : patch.faces) {
    for (int k = 0; k < 3; ++k) ++uses[UndirectedEdgeKey(t[k], t[(k + 1) % 3])];
  }
  std::unordered_set<uint64_t> seen;
  for (size_t f = 0; f < checked; ++f) {
    if (meets[f].empty()) continue;
    std::vector<Triangle> set = {faces[f]};
    for (int32_t g : meets[f]) set.push_back(faces[g]);
    int64_t pairs = 0;
    Status s = CountPairsAmong(point, std::move(set), 1, control, &pairs);
    if (!s.ok()) return s;
    if (pairs == 0) continue;
    const Triangle& t = patch.faces[f];
    for (int k = 0; k < 3; ++k) {
      const int32_t a = t[k], b = t[(k + 1) % 3];
      const uint64_t key = UndirectedEdgeKey(a, b);
      if (a < first_new_id && b < first_new_id && uses[key] == 2 &&
          seen.insert(key).second) {
        chords->emplace_back(a, b);
      }
    }
  }
  return OkStatus();
}

}  // namespace dot
