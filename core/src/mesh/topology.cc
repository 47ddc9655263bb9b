// SPDX-License-Identifier: AGPL-3.0-or-later
#include "mesh/topology.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <memory>

namespace dot {

namespace {

void BuildRows(const MeshData& mesh, MeshTopology* topo) {
  const size_t nv = mesh.vertices.size();
  topo->face_begin.assign(nv + 1, 0);
  for (const Triangle& t : mesh.triangles) {
    for (int32_t v : t) ++topo->face_begin[v + 1];
  }
  for (size_t v = 0; v < nv; ++v)
    topo->face_begin[v + 1] += topo->face_begin[v];
  topo->faces.resize(topo->face_begin[nv]);
  std::vector<int32_t> fill(topo->face_begin.begin(),
                            topo->face_begin.end() - 1);
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    for (int32_t v : mesh.triangles[f]) {
      topo->faces[fill[v]++] = static_cast<int32_t>(f);
    }
  }
}

}  // namespace

std::shared_ptr<const MeshTopology> BuildMeshAdjacency(const MeshData& mesh) {
  auto topo = std::make_shared<MeshTopology>();
  BuildRows(mesh, topo.get());
  return topo;
}

std::shared_ptr<const MeshTopology> BuildMeshTopology(const MeshData& mesh) {
  auto topo = std::make_shared<MeshTopology>();
  tbb::parallel_invoke(
      [&] { BuildRows(mesh, topo.get()); },
      [&] { topo->face_tree = std::make_shared<const FaceTree>(mesh); });
  return topo;
}

}  // namespace dot
