// SPDX-License-Identifier: AGPL-3.0-or-later
// A patch against itself and the mesh faces near it (those whose bounding
// boxes meet the patch's), with the exact predicates of the validator.
#include "fill/patch_check.h"

#include <algorithm>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "dot/fill_holes.h"
#include "dot/validate.h"
#include "mesh/topology.h"
#include "util/run_control.h"

namespace dot {

Status CountPairsAmong(const std::function<const Vec3&(int32_t)>& point,
                       std::vector<Triangle> faces, size_t checked,
                       const Control& control, int64_t* pairs) {
  std::unordered_map<int32_t, int32_t> local;
  std::vector<Vec3> points;
  for (Triangle& t : faces) {
    for (int32_t& v : t) {
      auto [it, added] = local.emplace(v, static_cast<int32_t>(points.size()));
      if (added) points.push_back(point(v));
      v = it->second;
    }
  }
  return CountIntersectingPairs(points, faces, checked, control, pairs);
}

Status PatchIntersections(const MeshData& mesh, const MeshTopology& topology,
                          int32_t first_new_id, const HolePatch& patch,
                          const Control& control, int64_t* pairs) {
  if (!topology.face_tree) {
    return MakeStatus(StatusCode::kInternal,
                      "PatchIntersections needs BuildMeshTopology's face tree");
  }
  auto point = [&](int32_t id) -> const Vec3& {
    return id < first_new_id ? mesh.vertices[id]
                             : patch.new_vertices[id - first_new_id];
  };
  Box3 box;
  for (const Triangle& t : patch.faces) {
    for (int32_t v : t) box.Add(point(v));
  }
  std::vector<Triangle> faces = patch.faces;
  for (const auto& pieces : patch.pieces) {
    faces.insert(faces.end(), pieces.begin(), pieces.end());
  }
  std::vector<int32_t> near;
  topology.face_tree->FacesMeeting(box, &near);
  const std::unordered_set<int32_t> split(patch.split_faces.begin(),
                                          patch.split_faces.end());
  for (int32_t f : near) {
    if (!split.count(f)) faces.push_back(mesh.triangles[f]);
  }
  return CountPairsAmong(point, std::move(faces), patch.faces.size(), control,
                         pairs);
}

}  // namespace dot
