// SPDX-License-Identifier: AGPL-3.0-or-later
// CGAL's side: a Surface_mesh built from the same repaired mesh, every
// border cycle filled by triangulate_hole, triangulate_and_refine_hole or
// triangulate_refine_and_fair_hole (default parameters), in a forked
// child so that a run can be stopped at a time cap.
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "fill_bench/cgal_types.h"
#include "fill_bench/fill_bench.h"
#include "heap_meter.h"

namespace dot::bench::fill {
namespace {

using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
using Halfedge = SurfaceMesh::Halfedge_index;
namespace PMP = CGAL::Polygon_mesh_processing;

struct CgalVisitor : PMP::Hole_filling::Default_visitor {
  bool* cubic;
  explicit CgalVisitor(bool* c) : cubic(c) {}
  void start_cubic_phase(int) const { *cubic = true; }
};

// What the child sends back.
struct CgalCycle {
  int32_t first = 0;  // a vertex of the cycle (Surface_mesh index)
  int32_t filled = 0, cubic = 0, fair_ok = 1;
  double ms = 0;
};

struct CgalOnce {
  std::string status = "ok";
  double ms = NAN, build_ms = NAN, heap = NAN;
  std::vector<CgalCycle> cycles;
  std::vector<Vec3> vertices;  // Surface_mesh vertices, by index
  std::vector<Triangle> faces;
};

template <typename T>
void Put(std::string* out, const T& v) {
  out->append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <typename T>
bool Get(const std::string& in, size_t* at, T* v) {
  if (*at + sizeof *v > in.size()) return false;
  std::memcpy(v, in.data() + *at, sizeof *v);
  *at += sizeof *v;
  return true;
}

// The Surface_mesh CGAL fills, built from the repaired mesh: face by face
// (add_face), or, when the mesh has non-manifold vertices (pinched
// borders; `soup` is then true), as CGAL's readers do: orient_polygon_soup
// duplicates those vertices and polygon_soup_to_polygon_mesh builds it, so
// a pinched border is one cycle through two copies of a point.
bool BuildSurfaceMesh(const MeshData& m, bool soup, SurfaceMesh* sm) {
  if (!soup) {
    sm->reserve(m.vertices.size(), 3 * m.triangles.size() / 2,
                m.triangles.size());
    for (const Vec3& v : m.vertices) sm->add_vertex(P(v));
    for (const Triangle& t : m.triangles) {
      const auto f = sm->add_face(SurfaceMesh::Vertex_index(t[0]),
                                  SurfaceMesh::Vertex_index(t[1]),
                                  SurfaceMesh::Vertex_index(t[2]));
      if (f == SurfaceMesh::null_face()) return false;
    }
    return true;
  }
  std::vector<K::Point_3> points;
  for (const Vec3& v : m.vertices) points.push_back(P(v));
  std::vector<std::array<std::size_t, 3>> faces;
  for (const Triangle& t : m.triangles) {
    faces.push_back({static_cast<std::size_t>(t[0]),
                     static_cast<std::size_t>(t[1]),
                     static_cast<std::size_t>(t[2])});
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(faces)) {
    PMP::orient_polygon_soup(points, faces);
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(faces)) return false;
  PMP::polygon_soup_to_polygon_mesh(points, faces, *sm);
  return true;
}

// The child's work: build the Surface_mesh (timed apart), fill every
// border cycle (timed), send the result. Peak heap covers both.
std::string CgalChild(const MeshData& mesh, bool soup, FillStage stage) {
  ResetHeapPeak();
  const auto tb = Clock::now();
  SurfaceMesh sm;
  if (!BuildSurfaceMesh(mesh, soup, &sm)) _exit(5);
  const double build_ms = MsSince(tb);
  std::vector<CgalCycle> cycles;
  const auto t0 = Clock::now();
  std::vector<Halfedge> borders;
  PMP::extract_boundary_cycles(sm, std::back_inserter(borders));
  for (Halfedge h : borders) {
    CgalCycle cy;
    cy.first = static_cast<int32_t>(sm.target(h).idx());
    bool cubic = false;
    CgalVisitor visitor(&cubic);
    std::vector<SurfaceMesh::Face_index> faces;
    std::vector<SurfaceMesh::Vertex_index> vertices;
    const auto t = Clock::now();
    switch (stage) {
      case FillStage::kTriangulate:
        PMP::triangulate_hole(sm, h, std::back_inserter(faces),
                              CGAL::parameters::visitor(visitor));
        break;
      case FillStage::kRefine:
        PMP::triangulate_and_refine_hole(sm, h, std::back_inserter(faces),
                                         std::back_inserter(vertices),
                                         CGAL::parameters::visitor(visitor));
        break;
      case FillStage::kFair:
        cy.fair_ok = std::get<0>(PMP::triangulate_refine_and_fair_hole(
            sm, h, std::back_inserter(faces), std::back_inserter(vertices),
            CGAL::parameters::visitor(visitor)));
        break;
    }
    cy.ms = MsSince(t);
    cy.filled = !faces.empty();
    cy.cubic = cubic;
    cycles.push_back(cy);
  }
  const double ms = MsSince(t0);
  const auto heap = static_cast<double>(HeapPeakBytes());
  if (sm.has_garbage()) sm.collect_garbage();  // contiguous indices
  std::string out;
  Put(&out, ms);
  Put(&out, build_ms);
  Put(&out, heap);
  Put(&out, static_cast<int64_t>(cycles.size()));
  for (const CgalCycle& cy : cycles) Put(&out, cy);
  Put(&out, static_cast<int64_t>(sm.number_of_vertices()));
  for (auto v : sm.vertices()) {
    const K::Point_3& p = sm.point(v);
    Put(&out, Vec3{p.x(), p.y(), p.z()});
  }
  Put(&out, static_cast<int64_t>(sm.number_of_faces()));
  for (auto f : sm.faces()) {
    Triangle t{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (k < 3) t[k] = static_cast<int32_t>(v.idx());
      ++k;
    }
    Put(&out, t);
  }
  return out;
}

CgalOnce RunCgalOnce(const MeshData& mesh, bool soup, FillStage stage,
                     double cap_s) {
  CgalOnce r;
  int fds[2];
  if (pipe(fds) != 0) {
    r.status = "error: pipe";
    return r;
  }
  std::cout.flush();
  std::cerr.flush();
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    r.status = "error: fork";
    return r;
  }
  if (pid == 0) {
    close(fds[0]);
    std::string out;
    int code = 0;
    try {
      out = CgalChild(mesh, soup, stage);
    } catch (const std::exception& e) {
      out.clear();
      code = 3;
    }
    size_t at = 0;
    while (at < out.size()) {
      const ssize_t w = write(fds[1], out.data() + at, out.size() - at);
      if (w <= 0) _exit(4);
      at += static_cast<size_t>(w);
    }
    close(fds[1]);
    _exit(code);
  }
  close(fds[1]);
  const auto deadline =
      Clock::now() + std::chrono::milliseconds(static_cast<int>(cap_s * 1000));
  std::string data;
  char buf[1 << 16];
  bool timed_out = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          deadline - Clock::now())
                          .count();
    if (left <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = poll(&p, 1, static_cast<int>(left));
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) {
      timed_out = true;
      break;
    }
    const ssize_t n = read(fds[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    data.append(buf, static_cast<size_t>(n));
  }
  close(fds[0]);
  if (timed_out) kill(pid, SIGKILL);
  int wstatus = 0;
  waitpid(pid, &wstatus, 0);
  if (timed_out) {
    r.status = "timeout";
    return r;
  }
  if (!WIFEXITED(wstatus) || WEXITSTATUS(wstatus) != 0) {
    r.status = WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 5
                   ? "error: no Surface_mesh"
               : WIFSIGNALED(wstatus)
                   ? "error: crashed (signal " +
                         std::to_string(WTERMSIG(wstatus)) + ")"
                   : "error: exception (exit " +
                         std::to_string(WEXITSTATUS(wstatus)) + ")";
    return r;
  }
  size_t at = 0;
  int64_t n = 0;
  bool ok = Get(data, &at, &r.ms) && Get(data, &at, &r.build_ms) &&
            Get(data, &at, &r.heap) && Get(data, &at, &n);
  for (int64_t i = 0; ok && i < n; ++i) {
    CgalCycle cy;
    ok = Get(data, &at, &cy);
    r.cycles.push_back(cy);
  }
  ok = ok && Get(data, &at, &n);
  r.vertices.resize(ok ? n : 0);
  for (int64_t i = 0; ok && i < n; ++i) ok = Get(data, &at, &r.vertices[i]);
  ok = ok && Get(data, &at, &n);
  r.faces.resize(ok ? n : 0);
  for (int64_t i = 0; ok && i < n; ++i) ok = Get(data, &at, &r.faces[i]);
  if (!ok) r.status = "error: truncated answer";
  return r;
}

}  // namespace

// True when CGAL needs the soup route for `m` (non-manifold vertices).
bool NeedsSoup(const MeshData& m) {
  std::vector<std::array<std::size_t, 3>> faces;
  for (const Triangle& t : m.triangles) {
    faces.push_back({static_cast<std::size_t>(t[0]),
                     static_cast<std::size_t>(t[1]),
                     static_cast<std::size_t>(t[2])});
  }
  return !PMP::is_polygon_soup_a_polygon_mesh(faces);
}

Run RunCgal(const Config& config, const Case& c, const Holes& holes, bool soup,
            const std::unordered_map<Vec3, int32_t, ByPoint>& input_ids,
            FillStage stage, MeshData* out) {
  Run run;
  CgalOnce last;
  // The hole of a cycle: its vertex's input id (copies of a point map to
  // the input vertex).
  auto hole_of = [&](const CgalOnce& once, const CgalCycle& cy) {
    if (cy.first < 0 ||
        cy.first >= static_cast<int32_t>(once.vertices.size())) {
      return -1;
    }
    auto v = input_ids.find(once.vertices[cy.first]);
    if (v == input_ids.end()) return -1;
    auto h = holes.vertex.find(v->second);
    return h == holes.vertex.end() ? -1 : h->second;
  };
  std::vector<std::vector<double>> hole_ms(holes.count);
  std::vector<double> build_ms;
  run.time = Repeat(config, [&](double* ms, double* heap) {
    CgalOnce once = RunCgalOnce(c.mesh, soup, stage, kCgalCapS);
    if (once.status != "ok") {
      if (last.status == "ok" && last.vertices.empty()) last = once;
      return false;
    }
    *ms = once.ms;
    *heap = once.heap;
    build_ms.push_back(once.build_ms);
    std::vector<double> per(holes.count, 0);
    for (const CgalCycle& cy : once.cycles) {
      const int h = hole_of(once, cy);
      if (h >= 0) per[h] += cy.ms;
    }
    for (int k = 0; k < holes.count; ++k) hole_ms[k].push_back(per[k]);
    last = std::move(once);
    return true;
  });
  if (run.time.runs == 0) {
    run.status = last.status;
    return run;
  }
  run.build_ms = Median(build_ms);
  std::vector<int32_t> id(last.vertices.size());
  out->vertices = c.mesh.vertices;
  for (size_t i = 0; i < last.vertices.size(); ++i) {
    auto it = input_ids.find(last.vertices[i]);
    if (it != input_ids.end()) {
      id[i] = it->second;
    } else {
      id[i] = static_cast<int32_t>(out->vertices.size());
      out->vertices.push_back(last.vertices[i]);
    }
  }
  out->triangles.clear();
  for (Triangle t : last.faces) {
    for (int32_t& v : t) v = id[v];
    out->triangles.push_back(t);
  }
  std::vector<int> open(holes.count, 0), cycles(holes.count, 0);
  run.hole_cubic.assign(holes.count, false);
  for (int k = 0; k < holes.count; ++k) {
    run.hole_ms.push_back(Median(hole_ms[k]));
  }
  run.loops = static_cast<int>(last.cycles.size());
  for (const CgalCycle& cy : last.cycles) {
    run.loops_filled += cy.filled;
    run.fair_failed += stage == FillStage::kFair && cy.filled && !cy.fair_ok;
    const int h = hole_of(last, cy);
    if (h < 0) {
      run.note = "a border cycle outside every hole";
      continue;
    }
    ++cycles[h];
    open[h] += !cy.filled;
    run.hole_cubic[h] = run.hole_cubic[h] || cy.cubic;
  }
  for (int k = 0; k < holes.count; ++k) {
    const bool filled = cycles[k] > 0 && open[k] == 0;
    run.hole_filled.push_back(filled);
    run.holes_filled += filled;
  }
  return run;
}

bool CgalCanBuild(const MeshData& mesh, bool soup) {
  SurfaceMesh sm;
  return BuildSurfaceMesh(mesh, soup, &sm);
}

}  // namespace dot::bench::fill
