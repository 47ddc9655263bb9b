// SPDX-License-Identifier: AGPL-3.0-or-later
// CGAL 5.5's polygon triangulation as a CGAL user runs it on a file: read
// "x y z" lines (further columns, such as normals, are ignored), run
// triangulate_hole_polyline over the Delaunay triangles only (as dot-bench's
// in-process peer: no cubic fallback), write the patch as OBJ. The
// whole-process peer of `dotctl triangulate --local` in
// bench/polygon_process.sh. Prints the compute time of the call alone.
// Usage: cgal_polyline_file IN.xyz OUT.obj
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: cgal_polyline_file IN OUT\n";
    return 2;
  }
  std::ifstream in(argv[1]);
  if (!in) {
    std::cerr << "cgal_polyline_file: cannot read '" << argv[1] << "'\n";
    return 2;
  }
  std::vector<K::Point_3> points;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos ||
        line[line.find_first_not_of(" \t\r")] == '#') {
      continue;
    }
    std::istringstream fields(line);
    double x, y, z;
    if (!(fields >> x >> y >> z)) {
      std::cerr << argv[1] << ":" << number << ": expected x y z\n";
      return 2;
    }
    points.emplace_back(x, y, z);
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<CGAL::Triple<int, int, int>> patch;
  CGAL::Polygon_mesh_processing::triangulate_hole_polyline(
      points, std::back_inserter(patch),
      CGAL::parameters::use_delaunay_triangulation(true)
          .do_not_use_cubic_algorithm(true));
  const double ms = std::chrono::duration<double, std::milli>(
                        std::chrono::steady_clock::now() - t0)
                        .count();
  std::ofstream out(argv[2]);
  char buffer[128];
  for (const K::Point_3& p : points) {
    std::snprintf(buffer, sizeof buffer, "v %.17g %.17g %.17g\n", p.x(), p.y(),
                  p.z());
    out << buffer;
  }
  for (const auto& t : patch) {
    out << "f " << t.first + 1 << ' ' << t.second + 1 << ' ' << t.third + 1
        << '\n';
  }
  if (!out) {
    std::cerr << "cgal_polyline_file: cannot write '" << argv[2] << "'\n";
    return 1;
  }
  std::cout << "compute_ms " << ms << " triangles " << patch.size() << '\n';
  return patch.empty() ? 1 : 0;
}
