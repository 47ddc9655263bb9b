// SPDX-License-Identifier: AGPL-3.0-or-later
// CGAL 5.5's hole filling as a CGAL user runs it on a file: read the mesh
// (PMP::IO::read_polygon_mesh, which repairs a soup as CGAL's readers do),
// fill every border cycle with triangulate_refine_and_fair_hole (default
// parameters), write it. The peer of `dotctl fill-holes --local` in
// bench/scan_fill.sh: both timed as whole processes on the same files.
// Usage: cgal_fill_file IN.off OUT.ply
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <iostream>
#include <iterator>
#include <vector>

namespace PMP = CGAL::Polygon_mesh_processing;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: cgal_fill_file IN OUT\n";
    return 2;
  }
  Mesh mesh;
  if (!PMP::IO::read_polygon_mesh(argv[1], mesh)) {
    std::cerr << "cgal_fill_file: cannot read '" << argv[1] << "'\n";
    return 2;
  }
  std::vector<Mesh::Halfedge_index> borders;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(borders));
  int faired = 0;
  for (Mesh::Halfedge_index h : borders) {
    std::vector<Mesh::Face_index> faces;
    std::vector<Mesh::Vertex_index> vertices;
    faired += std::get<0>(PMP::triangulate_refine_and_fair_hole(
        mesh, h, std::back_inserter(faces), std::back_inserter(vertices)));
  }
  if (!CGAL::IO::write_polygon_mesh(argv[2], mesh,
                                    CGAL::parameters::stream_precision(17))) {
    std::cerr << "cgal_fill_file: cannot write '" << argv[2] << "'\n";
    return 1;
  }
  std::cout << borders.size() << " border cycles, " << faired << " faired\n";
  return 0;
}
