// SPDX-License-Identifier: AGPL-3.0-or-later
#include "search_space/delaunay3d.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "mesh/edge_index.h"
#include "search_space/delaunay_cgal.h"
#include "search_space/faces_of_tetrahedra.h"
#include "util/run_control.h"

namespace dot {
namespace {

// Positions i whose polygon edge (i, next[i]) is on no face.
std::vector<int32_t> MissingPolygonEdges(const std::vector<int32_t>& next,
                                         const std::vector<Triangle>& faces) {
  const EdgeIndex index = BuildEdgeIndex(faces);
  std::vector<int32_t> missing;
  for (int32_t i = 0; i < static_cast<int32_t>(next.size()); ++i) {
    if (!HasEdge(index, i, next[i])) missing.push_back(i);
  }
  return missing;
}

// TetGen decides with Shewchuk's predicates, which are exact only while no
// product of up to five coordinate differences underflows: on the work
// coordinates (largest in [0.5, 1)), every non-zero one must be at least
// 2^-150 (products then stay above 2^-1022). Below that it can return a
// wrong tetrahedralization, hence a self-intersecting "Delaunay" patch.
Status CheckTetgenRange(const std::vector<Vec3>& points) {
  for (size_t i = 0; i < points.size(); ++i) {
    for (double c : {points[i].x, points[i].y, points[i].z}) {
      if (c != 0 && std::abs(c) < 0x1p-150) {
        return InvalidArgument(
            "vertex " + std::to_string(i) +
            " has a coordinate more than 2^150 times smaller than the "
            "polygon's largest (but not zero), on which TetGen's predicates "
            "are not exact; use the cgal backend, or round it to zero");
      }
    }
  }
  return OkStatus();
}

Status Faces(const Options& options, const Control& control,
             const std::vector<Vec3>& points, std::vector<Triangle>* faces,
             int64_t* tetrahedra) {
  if (options.delaunay == DelaunayBackend::kCgal) {
    return CgalDelaunayFaces(points, options, control, faces, tetrahedra);
  }
  if (Status s = CheckTetgenRange(points); !s.ok()) return s;
  Tetrahedralization tets;
  Status s = control.tetrahedralize ? control.tetrahedralize(points, &tets)
                                    : TetgenTetrahedralize(points, &tets);
  if (!s.ok()) return s;
  *tetrahedra = static_cast<int64_t>(tets.tets.size());
  return FacesOfTetrahedra(tets, faces);
}

}  // namespace

bool TetgenAvailable() { return DOT_WITH_TETGEN; }

#if !DOT_WITH_TETGEN
Status TetgenTetrahedralize(const std::vector<Vec3>&, Tetrahedralization*) {
  return InvalidArgument(kNoTetgenMessage);
}
#endif

Status Delaunay3dFaces(const Options& options, const Control& control,
                       PolygonLoop* loop, std::vector<Triangle>* faces,
                       Stats* stats) {
  const int32_t input_size = loop->size();
  const int max_inserted = options.max_inserted_vertices;
  RunTicker ticker(control, Stage::kDelaunay);
  for (;;) {
    Status s =
        Faces(options, control, loop->Points(), faces, &stats->tetrahedra);
    if (!s.ok()) return s;
    if (!options.protect_edges) break;
    const std::vector<int32_t> next = loop->Successors();
    const std::vector<int32_t> missing = MissingPolygonEdges(next, *faces);
    if (missing.empty()) break;
    if (loop->size() - input_size + static_cast<int32_t>(missing.size()) >
        max_inserted) {
      return MakeStatus(StatusCode::kResourceExhausted,
                        "edge protection would insert more than " +
                            std::to_string(max_inserted) + " vertices");
    }
    if (!ticker.Poll()) return ticker.status();
    // Split every missing edge at its midpoint, walking the loop(s) once.
    std::vector<int32_t> ids;
    std::vector<int32_t> loop_of;  // position -> loop, for the new sizes
    for (int32_t l = 0; l < loop->LoopCount(); ++l) {
      loop_of.insert(loop_of.end(),
                     loop->sizes.empty() ? loop->size() : loop->sizes[l], l);
    }
    ids.reserve(loop->ids.size() + missing.size());
    size_t next_missing = 0;
    for (int32_t i = 0; i < loop->size(); ++i) {
      ids.push_back(loop->ids[i]);
      if (next_missing < missing.size() && missing[next_missing] == i) {
        ++next_missing;
        const int32_t a = loop->ids[i], b = loop->ids[next[i]];
        if (!loop->sizes.empty()) ++loop->sizes[loop_of[i]];
        const Vec3 mid = 0.5 * (loop->vertices[a] + loop->vertices[b]);
        if (mid == loop->vertices[a] || mid == loop->vertices[b]) {
          return InvalidArgument("edge protection cannot make edge " +
                                 std::to_string(a) + "-" + std::to_string(b) +
                                 " Delaunay: it is too short to halve (the "
                                 "polygon may touch itself there)");
        }
        ids.push_back(static_cast<int32_t>(loop->vertices.size()));
        loop->vertices.push_back(mid);
        if (!loop->normals.empty()) {
          const Vec3 n = loop->normals[a] + loop->normals[b];
          loop->normals.push_back(Norm(n) > 0 ? Normalized(n)
                                              : loop->normals[a]);
        }
        // Both halves lie on the face across the split edge.
        if (!loop->edge_normals.empty()) {
          loop->edge_normals.push_back(loop->edge_normals[a]);
        }
      }
    }
    loop->ids = std::move(ids);
  }
  stats->delaunay_triangles = static_cast<int64_t>(faces->size());
  return OkStatus();
}

}  // namespace dot
