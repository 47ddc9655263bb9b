// SPDX-License-Identifier: AGPL-3.0-or-later
// Curve networks into surfaces (issue 20): closed libcgal-demo meshes cut
// into disk-shaped patches (CutIntoPatches), the patch rims taken as the
// network (every rim vertex, and every third), surfaced by SurfaceNetwork
// with its defaults, and compared with the mesh they were cut from: valid
// (edge-manifold, oriented, no intersecting pair, exact), closed, every
// curve edge present, the symmetric Hausdorff distance to the original
// relative to its bounding-box diagonal. The baseline is CGAL 5.5 per
// cycle (the same cycles): triangulate_hole_polyline, refine, fair with the
// rim fixed, the patches welded at the network's vertices.
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/fair.h>
#include <CGAL/Polygon_mesh_processing/refine.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <map>

#include "fill_bench/fill_bench.h"
#include "measure.h"
#include "suite.h"

namespace dot::bench {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMeshK = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

// CGAL's hole filling of one cycle alone: its triangles oriented along the
// loop, then refined and faired with the loop fixed; new vertices appended
// to `mesh`.
bool CgalPatch(const std::vector<int32_t>& loop, MeshData* mesh) {
  std::vector<K::Point_3> points;
  for (int32_t v : loop) {
    const Vec3& p = mesh->vertices[v];
    points.emplace_back(p.x, p.y, p.z);
  }
  std::vector<CGAL::Triple<int, int, int>> tris;
  PMP::triangulate_hole_polyline(points, std::back_inserter(tris));
  if (tris.empty()) return false;
  SurfaceMeshK sm;
  for (const auto& p : points) sm.add_vertex(p);
  // Orient along the loop: the face on edge (0, 1) must run 0 -> 1.
  bool flip = false;
  for (const auto& t : tris) {
    const int c[3] = {t.first, t.second, t.third};
    for (int k = 0; k < 3; ++k) {
      if (c[k] == 1 && c[(k + 1) % 3] == 0) flip = true;
    }
  }
  std::vector<SurfaceMeshK::Face_index> faces;
  for (const auto& t : tris) {
    using V = SurfaceMeshK::Vertex_index;
    const auto f = flip ? sm.add_face(V(t.first), V(t.third), V(t.second))
                        : sm.add_face(V(t.first), V(t.second), V(t.third));
    if (f == SurfaceMeshK::null_face()) return false;
    faces.push_back(f);
  }
  std::vector<SurfaceMeshK::Face_index> new_faces;
  std::vector<SurfaceMeshK::Vertex_index> new_vertices;
  PMP::refine(sm, faces, std::back_inserter(new_faces),
              std::back_inserter(new_vertices),
              CGAL::parameters::density_control_factor(std::sqrt(2.0)));
  if (!new_vertices.empty()) PMP::fair(sm, new_vertices);
  std::vector<int32_t> id(sm.number_of_vertices());
  for (auto v : sm.vertices()) {
    if (v.idx() < loop.size()) {
      id[v.idx()] = loop[v.idx()];
    } else {
      id[v.idx()] = static_cast<int32_t>(mesh->vertices.size());
      const auto& p = sm.point(v);
      mesh->vertices.push_back({p.x(), p.y(), p.z()});
    }
  }
  for (auto f : sm.faces()) {
    Triangle t;
    int k = 0;
    for (auto v : sm.vertices_around_face(sm.halfedge(f))) t[k++] = id[v.idx()];
    mesh->triangles.push_back(t);
  }
  return true;
}

// The largest distance from samples of `from` (its vertices on faces, and
// each face's centroid and the midpoints between centroid and corners) to
// the triangles of `to`, through CGAL's AABB tree: works on any triangle
// set (the welded baseline is not always a manifold, which CGAL's
// Hausdorff functions need).
double OneSidedDistance(const MeshData& from, const MeshData& to) {
  using Tri = K::Triangle_3;
  using Iterator = std::vector<Tri>::const_iterator;
  using Primitive = CGAL::AABB_triangle_primitive<K, Iterator>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
  auto point = [](const Vec3& p) { return K::Point_3(p.x, p.y, p.z); };
  std::vector<Tri> triangles;
  for (const Triangle& t : to.triangles) {
    triangles.emplace_back(point(to.vertices[t[0]]), point(to.vertices[t[1]]),
                           point(to.vertices[t[2]]));
  }
  Tree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  double worst = 0;
  for (const Triangle& t : from.triangles) {
    const Vec3 c = (1.0 / 3) * (from.vertices[t[0]] + from.vertices[t[1]] +
                                from.vertices[t[2]]);
    std::vector<Vec3> samples = {c};
    for (int32_t v : t) {
      samples.push_back(from.vertices[v]);
      samples.push_back(0.5 * (c + from.vertices[v]));
    }
    for (const Vec3& q : samples) {
      worst = std::max(worst, std::sqrt(tree.squared_distance(point(q))));
    }
  }
  return worst;
}

double SampledHausdorff(const MeshData& a, const MeshData& b) {
  if (a.triangles.empty() || b.triangles.empty()) return NAN;
  return std::max(OneSidedDistance(a, b), OneSidedDistance(b, a));
}

struct Row {
  std::string name;
  int keep = 1, curves = 0, patches = 0, surfaced = 0, cgal_patches = 0;
  int true_patches = 0, rims_found = 0;
  double ours_ms = NAN, cgal_ms = NAN, ours_d = NAN, cgal_d = NAN;
  bool closed = false, valid = false;
  int64_t cgal_pairs = -1;
};

double Diagonal(const MeshData& m) {
  Vec3 lo = m.vertices[0], hi = lo;
  for (const Vec3& p : m.vertices) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  return Distance(lo, hi);
}

}  // namespace

int RunNetwork(const Config& config, std::ostream& report) {
  const std::vector<std::string> meshes =
      config.quick ? std::vector<std::string>{"homer"}
                   : std::vector<std::string>{"homer", "bunny00", "elephant",
                                              "armadillo"};
  const std::vector<int> sizes =
      config.quick ? std::vector<int>{4, 40} : std::vector<int>{4, 12, 40, 140};
  std::vector<Row> rows;
  int invalid = 0;
  for (const std::string& name : meshes) {
    MeshData original;
    if (!fill::LoadMesh(config, name, &original)) continue;
    const double diagonal = Diagonal(original);
    for (int patches : sizes) {
      for (int keep : {1, 3}) {
        CutNetwork cut;
        if (!CutIntoPatches(original, patches, keep, 1, &cut).ok()) {
          std::cerr << "network: " << name << " " << patches << ": no cut\n";
          continue;
        }
        Row row;
        row.name = name + "/p" + std::to_string(cut.patches);
        row.keep = keep;
        std::cerr << "network: " << row.name << " keep " << keep << "\n";
        SurfaceResult r;
        const Sample s = Measure(config.reps, config.long_run_s, config.cap_s,
                                 [&] { r = SurfaceNetwork(cut.network); });
        if (!r.status.ok()) {
          std::cerr << "network: " << row.name << ": " << r.status.message
                    << "\n";
          ++invalid;
          continue;
        }
        row.ours_ms = s.ms;
        row.curves = r.report.curves;
        row.patches = static_cast<int>(r.report.patches.size());
        row.surfaced = r.report.surfaced;
        row.closed = r.report.closed;
        std::vector<std::vector<int32_t>> cycles;
        for (const PatchReport& p : r.report.patches) {
          cycles.emplace_back();
          for (const auto& loop : p.loop_vertices) {
            cycles.back().insert(cycles.back().end(), loop.begin(), loop.end());
          }
        }
        row.true_patches = cut.patches;
        row.rims_found = CountRimsFound(cut, cycles);
        const int64_t pairs =
            CountIntersectingPairs(r.mesh.vertices, r.mesh.triangles);
        row.valid = pairs == 0 && r.report.intersecting_pairs == 0;
        if (!row.valid) {
          std::cerr << "network: DEFECT " << row.name << ": " << pairs
                    << " intersecting pairs\n";
          ++invalid;
        }
        row.ours_d = SampledHausdorff(r.mesh, original) / diagonal;
        // The baseline over the same cycles.
        MeshData cgal;
        const auto t0 = std::chrono::steady_clock::now();
        cgal.vertices = cut.network.vertices;
        for (const PatchReport& p : r.report.patches) {
          if (p.loop_vertices.size() != 1) continue;
          row.cgal_patches += CgalPatch(p.loop_vertices[0], &cgal);
        }
        row.cgal_ms = MsSince(t0);
        row.cgal_pairs = CountIntersectingPairs(cgal.vertices, cgal.triangles);
        row.cgal_d = SampledHausdorff(cgal, original) / diagonal;
        rows.push_back(row);
      }
    }
  }
  std::ofstream csv(config.Path("network.csv"));
  csv << "network,keep_every,curves,true_patches,rims_found,patches,surfaced,"
         "closed,valid,ours_ms,ours_hausdorff,cgal_ms,cgal_patches,cgal_pairs,"
         "cgal_hausdorff\n";
  for (const Row& r : rows) {
    csv << r.name << "," << r.keep << "," << r.curves << "," << r.true_patches
        << "," << r.rims_found << "," << r.patches << "," << r.surfaced << ","
        << r.closed << "," << r.valid << "," << r.ours_ms << "," << r.ours_d
        << "," << r.cgal_ms << "," << r.cgal_patches << "," << r.cgal_pairs
        << "," << r.cgal_d << "\n";
  }
  int better = 0, compared = 0;
  for (const Row& r : rows) {
    if (std::isnan(r.ours_d) || std::isnan(r.cgal_d)) continue;
    ++compared;
    better += r.ours_d < r.cgal_d;
  }
  report << "## Curve networks into surfaces\n\n"
         << "Closed meshes cut into disk-shaped patches (`CutIntoPatches`), "
            "the patch rims as the network (every rim vertex, or every "
            "third: `keep`), surfaced by `SurfaceNetwork` with its defaults "
            "(all cores), median of "
         << config.reps
         << " runs. Hausdorff: symmetric, to the original mesh, relative to "
            "its bounding-box diagonal, sampled (every vertex, face centroid "
            "and centroid-corner midpoint against the other's triangles, "
            "CGAL's AABB tree). "
            "Rims found: how many of the cut's patches have their rim among "
            "the cycles found. "
            "Baseline: CGAL 5.5 per cycle (the same cycles, one thread): "
            "`triangulate_hole_polyline`, `refine`, `fair` with the rim "
            "fixed, welded.\n\n"
         << "| network | keep | curves | rims found | patches | surfaced | "
            "closed | valid | dot ms | dot Hausdorff | CGAL ms | CGAL pairs | "
            "CGAL "
            "Hausdorff |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|"
            "\n";
  for (const Row& r : rows) {
    report << "| " << r.name << " | " << r.keep << " | " << r.curves << " | "
           << r.rims_found << " of " << r.true_patches << " | " << r.patches
           << " | " << r.surfaced << " | " << (r.closed ? "yes" : "no") << " | "
           << (r.valid ? "yes" : "NO") << " | " << Fixed(r.ours_ms) << " | "
           << Fixed(r.ours_d, 4) << " | " << Fixed(r.cgal_ms) << " | "
           << r.cgal_pairs << " | " << Fixed(r.cgal_d, 4) << " |\n";
  }
  report << "\ndot nearer the original than the CGAL baseline on " << better
         << " of " << compared << " networks.\n\n";
  return invalid;
}

}  // namespace dot::bench
