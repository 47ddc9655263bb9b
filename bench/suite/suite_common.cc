// SPDX-License-Identifier: AGPL-3.0-or-later
#include <cmath>
#include <cstdio>
#include <iostream>

#include "suite.h"

namespace dot::bench {

std::string Fixed(double v, int digits) {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

std::string Mib(double bytes) {
  return std::isnan(bytes) ? "-" : Fixed(bytes / (1 << 20), 1) + " MiB";
}

Result SolveWith(const Problem& problem, const MetricWeights& weights,
                 const Options& options, const Control& control) {
  Problem p = problem;
  p.weights = weights;
  return Triangulate(p, options, control);
}

int InvalidOutput(const Result& r, const std::string& what) {
  if (!r.status.ok()) return 0;
  const MeshReport report = ValidateMesh(r.vertices, r.polygon, r.triangles);
  if (report.valid()) return 0;
  std::cerr << "dot-bench: INVALID output for " << what << ": "
            << report.first_problem << "\n";
  return 1;
}

MetricWeights OneMetric(Metric m) {
  MetricWeights w;
  w[m] = 1;
  return w;
}

std::vector<HoleCase> MakeHoles(const Config& config, int count,
                                int min_triangles, int max_triangles) {
  std::vector<HoleCase> holes;
  std::vector<std::pair<std::string, MeshData>> meshes;
  for (const char* name : {"armadillo", "refined_elephant", "bunny00"}) {
    MeshData m;
    const std::string path = config.mesh_dir + "/" + name + ".off";
    if (ReadMeshFile(path, &m).ok()) {
      meshes.emplace_back(name, std::move(m));
    } else {
      std::cerr << "dot-bench: cannot read " << path << "\n";
    }
  }
  if (meshes.empty()) return holes;
  const double lo = std::log(min_triangles), hi = std::log(max_triangles);
  uint64_t seed = 1;
  for (int i = 0; i < count && seed < 20ULL * count; ++i) {
    const auto& [name, mesh] = meshes[i % meshes.size()];
    const double u = count > 1 ? static_cast<double>(i) / (count - 1) : 0;
    const int size =
        static_cast<int>(std::lround(std::exp(lo + u * (hi - lo))));
    Hole hole;
    // A seed whose neighbourhood has no room for the hole: try the next.
    while (!GrowHole(mesh, size, seed++, &hole).ok()) {
      if (seed >= 20ULL * count) return holes;
    }
    holes.push_back({name, hole.triangles, std::move(hole.boundary)});
  }
  return holes;
}

}  // namespace dot::bench
