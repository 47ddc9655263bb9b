// SPDX-License-Identifier: AGPL-3.0-or-later
// SurfaceNetwork: graph -> cycles -> DOT per patch (twice: the second time
// with the boundary normals the first patches give the curves, shared by
// the patches on each curve) -> re-solves of patches that meet others ->
// refinement per patch -> fairing of the whole network -> exact checks.
// Every step that could break the contract is checked with exact
// predicates and undone patch by patch where it does.
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <mutex>
#include <new>
#include <numeric>
#include <set>
#include <stdexcept>
#include <thread>
#include <unordered_map>

#include "dot/validate.h"
#include "fill/refine_limits.h"
#include "network/seam.h"
#include "network/surface_steps.h"
#include "util/run_control.h"

namespace dot {
namespace {

using Clock = std::chrono::steady_clock;
using Chord = std::pair<int32_t, int32_t>;

constexpr int kResolveRounds = 4;

Chord Key(int32_t a, int32_t b) { return {std::min(a, b), std::max(a, b)}; }

// Adds `why` to a patch's reason (a fan's reason stays when its refinement
// is undone).
void Note(PatchReport* r, const std::string& why) {
  r->reason += (r->reason.empty() ? "" : "; ") + why;
}

struct Work {
  std::vector<std::vector<int32_t>> loops;  // graph vertex ids
  std::map<Chord, int> boundary;            // its loops' edges, times run
  std::vector<Chord> forbidden;             // network edges, chords to avoid
  PatchMesh dot;                            // the DOT patch
  PatchMesh mesh;                           // as it stands (refined)
  bool live = false;                        // has a patch in the surface
  SeamSplit seam;                           // pieces empty: no seam
};

// Patches whose faces meet others' wrongly along an edge: a chord of a
// patch (an edge not on its loops) that is a curve's edge or an edge of
// another patch (refinement's flips can make one), more faces of a patch on
// an edge of its loops than they run it, or an edge that is no curve's
// with more than two faces or two that run it the same way.
std::set<int32_t> SharedEdgePatches(const MeshData& m,
                                    const std::vector<int32_t>& owner,
                                    const std::vector<Work>& work,
                                    const std::set<Chord>& curve_edges,
                                    std::string* what = nullptr) {
  std::map<Chord, std::vector<size_t>> faces_on;
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    const Triangle& t = m.triangles[f];
    for (int k = 0; k < 3; ++k)
      faces_on[Key(t[k], t[(k + 1) % 3])].push_back(f);
  }
  std::set<int32_t> out;
  for (const auto& [edge, faces] : faces_on) {
    const bool curve = curve_edges.count(edge) > 0;
    bool several = false;
    for (size_t f : faces) several = several || owner[f] != owner[faces[0]];
    // A patch has a face on an edge of its loops once per time they run
    // it (a flip inside a seam patch can add one where its loop runs the
    // edge elsewhere).
    std::map<int32_t, int> faces_of;
    for (size_t f : faces) ++faces_of[owner[f]];
    for (const auto& [p, n] : faces_of) {
      const auto run = work[p].boundary.find(edge);
      if (run != work[p].boundary.end() && n > run->second) {
        out.insert(p);
        if (what != nullptr && what->empty()) {
          *what = "patch " + std::to_string(p) + " has " + std::to_string(n) +
                  " faces on an edge its loops run " +
                  std::to_string(run->second) + " times (graph vertices " +
                  std::to_string(edge.first) + " and " +
                  std::to_string(edge.second) + ")";
        }
      }
    }
    for (size_t f : faces) {
      const bool chord = !work[owner[f]].boundary.count(edge);
      if (chord && (curve || several)) {
        out.insert(owner[f]);
        if (what != nullptr && what->empty()) {
          *what = "patch " + std::to_string(owner[f]) + " has a chord on " +
                  (curve ? "a curve's edge" : "another patch's edge") +
                  " (graph vertices " + std::to_string(edge.first) + " and " +
                  std::to_string(edge.second) + ")";
        }
      }
    }
    if (faces.size() < 2 || curve) continue;
    bool same_way = false;
    if (faces.size() == 2) {
      const Chord e = edge;  // (C++17 lambdas cannot capture a binding)
      auto runs = [&m, e](size_t f) {
        const Triangle& t = m.triangles[f];
        for (int k = 0; k < 3; ++k) {
          if (t[k] == e.first && t[(k + 1) % 3] == e.second) return true;
        }
        return false;
      };
      same_way = runs(faces[0]) == runs(faces[1]);
    }
    if (faces.size() > 2 || same_way) {
      for (size_t f : faces) out.insert(owner[f]);
    }
  }
  return out;
}

// The graph's vertices, then a seam patch's new path.
std::vector<Vec3> PiecesVertices(const NetworkGraph& g, const Work& w) {
  std::vector<Vec3> out = g.vertices;
  out.insert(out.end(), w.seam.new_vertices.begin(), w.seam.new_vertices.end());
  return out;
}

// TriangulatePatch of a patch, a seam patch piece by piece: the second
// never takes an edge of the first (the surface would pinch there), the
// new path's normals blended from its ends'.
Status SolvePatch(const NetworkGraph& g, const Work& w,
                  const std::vector<Vec3>& normals,
                  const SurfaceOptions& options, const Control& control,
                  PatchMesh* out, PatchReport* report) {
  if (w.seam.pieces.empty()) {
    return TriangulatePatch(g.vertices, w.loops, normals, w.forbidden, options,
                            control, out, report);
  }
  const std::vector<Vec3> vertices = PiecesVertices(g, w);
  std::vector<Vec3> piece_normals = normals;
  const size_t points = w.seam.new_vertices.size();
  for (size_t t = 0; t < points && !normals.empty(); ++t) {
    const double f =
        static_cast<double>(t + 1) / static_cast<double>(points + 1);
    const Vec3 n = (1 - f) * normals[w.seam.from] + f * normals[w.seam.to];
    piece_normals.push_back(Norm(n) > 0 ? Normalized(n) : Vec3{});
  }
  std::vector<Chord> forbidden = w.forbidden;
  PatchMesh both;
  both.new_vertices = w.seam.new_vertices;
  double cost = 0, ms = 0;
  for (size_t i = 0; i < w.seam.pieces.size(); ++i) {
    PatchMesh one;
    const Status s =
        TriangulatePatch(vertices, {w.seam.pieces[i]}, piece_normals, forbidden,
                         options, control, &one, report);
    ms += report->triangulate_ms;
    report->triangulate_ms = ms;
    if (!s.ok()) return s;
    cost += report->cost;
    for (const Triangle& t : one.faces) {
      both.faces.push_back(t);
      both.piece.push_back(static_cast<char>(i));
      for (int k = 0; k < 3; ++k)
        forbidden.push_back(Key(t[k], t[(k + 1) % 3]));
    }
  }
  report->cost = cost;
  *out = std::move(both);
  return OkStatus();
}

// FanPatch of a patch, a seam patch a fan per piece.
Status FanWork(const NetworkGraph& g, const Work& w, PatchMesh* out) {
  const auto first_new = static_cast<int32_t>(g.vertices.size());
  if (w.seam.pieces.empty())
    return FanPatch(g.vertices, w.loops, first_new, out);
  const std::vector<Vec3> vertices = PiecesVertices(g, w);
  PatchMesh both;
  both.new_vertices = w.seam.new_vertices;
  for (size_t i = 0; i < w.seam.pieces.size(); ++i) {
    PatchMesh one;
    const auto centre =
        first_new + static_cast<int32_t>(both.new_vertices.size());
    const Status s = FanPatch(vertices, {w.seam.pieces[i]}, centre, &one);
    if (!s.ok()) return s;
    both.new_vertices.push_back(one.new_vertices[0]);
    for (const Triangle& t : one.faces) {
      both.faces.push_back(t);
      both.piece.push_back(static_cast<char>(i));
    }
  }
  *out = std::move(both);
  return OkStatus();
}

template <typename F>
Status ForEachPatch(const SurfaceOptions& options, const std::vector<int>& ids,
                    const F& f) {
  const int threads =
      options.threads > 0
          ? options.threads
          : static_cast<int>(std::thread::hardware_concurrency());
  std::vector<Status> status(ids.size());
  tbb::task_arena arena(std::max(1, threads));
  arena.execute([&] {
    tbb::parallel_for(size_t{0}, ids.size(), size_t{1},
                      [&](size_t k) { status[k] = f(ids[k]); });
  });
  for (const Status& s : status) {
    if (!s.ok()) return s;
  }
  return OkStatus();
}

// The live patches as one mesh over graph ids then new vertices; `owner`
// receives each face's patch and `first_vertex` each patch's offset.
MeshData Assemble(const NetworkGraph& g, const std::vector<Work>& work,
                  bool refined, std::vector<int32_t>* owner,
                  std::vector<int32_t>* first_vertex) {
  MeshData m;
  m.vertices = g.vertices;
  const auto first_new = static_cast<int32_t>(g.vertices.size());
  owner->clear();
  first_vertex->assign(work.size(), 0);
  for (size_t p = 0; p < work.size(); ++p) {
    if (!work[p].live) continue;
    const PatchMesh& pm = refined ? work[p].mesh : work[p].dot;
    const auto offset = static_cast<int32_t>(m.vertices.size()) - first_new;
    (*first_vertex)[p] = static_cast<int32_t>(m.vertices.size());
    m.vertices.insert(m.vertices.end(), pm.new_vertices.begin(),
                      pm.new_vertices.end());
    for (Triangle t : pm.faces) {
      for (int32_t& v : t) {
        if (v >= first_new) v += offset;
      }
      m.triangles.push_back(t);
      owner->push_back(static_cast<int32_t>(p));
    }
  }
  return m;
}

// Patches that meet others wrongly: a chord on more than two faces (or
// twice the same way), or faces that cross. For each, the chords of its
// faces in the conflict are added to `more` (patch -> chords), the later
// patch of a pair giving way when it can.
Status FindConflicts(const NetworkGraph& g, const std::vector<Work>& work,
                     const std::vector<char>& stubborn, bool earlier_first,
                     const Control& control,
                     std::map<int32_t, std::set<Chord>>* more,
                     std::map<int32_t, std::string>* why) {
  more->clear();
  why->clear();
  std::vector<int32_t> owner, first;
  const MeshData m = Assemble(g, work, false, &owner, &first);
  // In the patch's own numbering (its new vertices from first_new).
  const auto first_new = static_cast<int32_t>(g.vertices.size());
  auto chords_of = [&](size_t f) {
    std::vector<Chord> out;
    const Triangle& t = m.triangles[f];
    auto own = [&](int32_t v) {
      return v < first_new ? v : v - first[owner[f]] + first_new;
    };
    for (int k = 0; k < 3; ++k) {
      const Chord c = Key(t[k], t[(k + 1) % 3]);
      if (!work[owner[f]].boundary.count(c)) {
        out.push_back(Key(own(c.first), own(c.second)));
      }
    }
    return out;
  };
  // The later patch (`earlier_first`: the earlier) gives way when it has a
  // chord there and has not failed to give way before (`stubborn`); else
  // the other one.
  auto blame = [&](size_t f1, size_t f2, const std::string& what) {
    size_t a = f1, b = f2;
    if ((owner[a] < owner[b]) != earlier_first) std::swap(a, b);
    if (chords_of(a).empty() || stubborn[owner[a]]) std::swap(a, b);
    if (chords_of(a).empty() || stubborn[owner[a]]) {
      if (owner[a] < owner[b]) std::swap(a, b);  // neither can: the later
    }
    const std::vector<Chord> chords = chords_of(a);
    const int32_t p = owner[a];
    (*more)[p].insert(chords.begin(), chords.end());
    if (stubborn[p]) (*more)[p].clear();  // cannot give way: it fails
    if (!why->count(p)) (*why)[p] = what + " patch " + std::to_string(owner[b]);
  };
  std::map<Chord, std::vector<size_t>> faces_on;
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    const Triangle& t = m.triangles[f];
    for (int k = 0; k < 3; ++k)
      faces_on[Key(t[k], t[(k + 1) % 3])].push_back(f);
  }
  for (const auto& [edge, faces] : faces_on) {
    if (faces.size() < 2) continue;
    for (size_t i = 0; i < faces.size(); ++i) {
      for (size_t j = i + 1; j < faces.size(); ++j) {
        if (owner[faces[i]] == owner[faces[j]]) continue;
        const bool chord_i = !work[owner[faces[i]]].boundary.count(edge);
        const bool chord_j = !work[owner[faces[j]]].boundary.count(edge);
        if (chord_i || chord_j)
          blame(faces[i], faces[j], "shares an edge with");
      }
    }
  }
  std::vector<std::pair<int32_t, int32_t>> pairs;
  const Status s =
      ListIntersectingPairs(m.vertices, m.triangles, SIZE_MAX, control, &pairs);
  if (!s.ok()) return s;
  for (const auto& [f1, f2] : pairs) {
    if (owner[f1] == owner[f2]) {
      (*more)[owner[f1]];
      (*why)[owner[f1]] = "crosses itself";
      continue;
    }
    blame(static_cast<size_t>(f1), static_cast<size_t>(f2), "crosses");
  }
  return OkStatus();
}

// Patches of faces in intersecting pairs of `m` (owner per face). With
// `moved` (may be null: all), only pairs with a face of those patches
// count: the rest were checked before and have not changed.
Status CrossingPatches(const MeshData& m, const std::vector<int32_t>& owner,
                       const std::set<int32_t>* moved, const Control& control,
                       std::set<int32_t>* patches, int64_t* count) {
  // The moved patches' faces first: the check takes pairs with one of them.
  std::vector<int32_t> order;
  std::vector<Triangle> faces;
  size_t checked = SIZE_MAX;
  if (moved != nullptr) {
    order.resize(m.triangles.size());
    std::iota(order.begin(), order.end(), 0);
    const auto mid = std::stable_partition(
        order.begin(), order.end(),
        [&](int32_t f) { return moved->count(owner[f]) > 0; });
    checked = static_cast<size_t>(mid - order.begin());
    faces.reserve(order.size());
    for (int32_t f : order) faces.push_back(m.triangles[f]);
  }
  std::vector<std::pair<int32_t, int32_t>> pairs;
  const Status s =
      ListIntersectingPairs(m.vertices, moved != nullptr ? faces : m.triangles,
                            checked, control, &pairs);
  if (!s.ok()) return s;
  auto face = [&](int32_t f) { return moved != nullptr ? order[f] : f; };
  patches->clear();
  for (const auto& [a, b] : pairs) {
    patches->insert(owner[face(a)]);
    patches->insert(owner[face(b)]);
  }
  *count = static_cast<int64_t>(pairs.size());
  return OkStatus();
}

// Puts a patch back to its DOT surface (or fan); false if it was there.
bool PutBackOne(Work* w, PatchReport* r, const std::string& why) {
  if (w->mesh.faces == w->dot.faces &&
      w->mesh.new_vertices == w->dot.new_vertices) {
    return false;
  }
  w->mesh = w->dot;
  r->refined_vertices = 0;
  r->faired = false;
  Note(r, why);
  return true;
}

// Puts patches back to their DOT surfaces while any makes a chord on an
// edge another face has, or (`crossings`) crosses another. kInternal if
// the DOT surfaces themselves do (they were checked apart).
Status PutBack(const NetworkGraph& g, const Control& control,
               const std::set<Chord>& curve_edges, bool crossings,
               std::vector<Work>* work, std::vector<PatchReport>* reports) {
  for (;;) {
    std::vector<int32_t> owner, first;
    const MeshData m = Assemble(g, *work, true, &owner, &first);
    std::set<int32_t> bad = SharedEdgePatches(m, owner, *work, curve_edges);
    if (crossings) {
      std::set<int32_t> crossing;
      int64_t pairs = 0;
      const Status s =
          CrossingPatches(m, owner, nullptr, control, &crossing, &pairs);
      if (!s.ok()) return s;
      bad.insert(crossing.begin(), crossing.end());
    }
    if (bad.empty()) return OkStatus();
    bool changed = false;
    for (int32_t p : bad) {
      changed |=
          PutBackOne(&(*work)[p], &(*reports)[p],
                     "refinement undone: it made faces cross or share an edge");
    }
    if (!changed) {
      return MakeStatus(StatusCode::kInternal,
                        "DOT patches that were checked apart cross after "
                        "refinement was undone");
    }
  }
}

struct RescueTry {
  PatchMesh mesh;
  PatchReport report;  // as DOT (or the fan) left it
};

// Tries a failed patch `p` again in the finished surface: each of `tries`
// (triangulations of its cycle) refined and faired with every other vertex
// fixed. Where it crosses neighbours, it is faired again together with them
// (they were faired around a hole where `p` is), at most `kRescueGrowth`
// times. Kept (*rescued) if it then crosses nothing and shares no chord;
// the neighbours faired with it keep their new places.
Status RescuePatch(const NetworkGraph& g, const SurfaceOptions& options,
                   const Control& control, const std::set<Chord>& curve_edges,
                   int p, const std::vector<RescueTry>& tries, size_t cap,
                   std::vector<Work>* work, std::vector<PatchReport>* reports,
                   bool* rescued) {
  constexpr int kRescueGrowth = 2;
  const auto first_new = static_cast<int32_t>(g.vertices.size());
  Work& w = (*work)[p];
  *rescued = false;
  for (const RescueTry& t : tries) {
    w.dot = t.mesh;
    w.mesh = t.mesh;
    w.live = true;
    PatchReport r = t.report;
    r.reason = (*reports)[p].reason;
    r.refined_vertices = 0;
    Status s = RefinePatch(g, options, control, first_new, cap, &w.mesh, &r);
    if (!s.ok()) return s;
    auto own = [&](int32_t q) {
      return static_cast<std::ptrdiff_t>((*work)[q].mesh.new_vertices.size());
    };
    std::set<int32_t> freed = {p};
    for (int growth = 0; growth <= kRescueGrowth; ++growth) {
      std::vector<int32_t> owner, first;
      MeshData m = Assemble(g, *work, true, &owner, &first);
      std::vector<char> fixed(m.vertices.size(), 1);
      for (int32_t q : freed) {
        std::fill_n(fixed.begin() + first[q], own(q), 0);
      }
      bool faired = false;
      std::string why;
      s = FairMesh(&m, first_new, fixed, options.fairing_continuity, control,
                   &faired, &why);
      if (!s.ok()) return s;
      std::set<int32_t> crossing;
      int64_t pairs = 0;
      s = CrossingPatches(m, owner, &freed, control, &crossing, &pairs);
      if (!s.ok()) return s;
      if (pairs == 0 &&
          SharedEdgePatches(m, owner, *work, curve_edges).empty()) {
        for (int32_t q : freed) {
          std::copy_n(m.vertices.begin() + first[q], own(q),
                      (*work)[q].mesh.new_vertices.begin());
          if (q == p || !faired) continue;
          PatchReport& neighbour = (*reports)[q];
          neighbour.faired = own(q) > 0;
          Note(&neighbour, "faired again with patch " + std::to_string(p) +
                               " once that was surfaced");
        }
        r.status = PatchStatus::kSurfaced;
        r.faired = faired && own(p) > 0;
        Note(&r, std::string("surfaced after the fairing, ") +
                     (faired ? "faired" : "refined") +
                     (faired && freed.size() > 1 ? " with its neighbours"
                                                 : " alone") +
                     " in the finished surface (its coarse " +
                     (r.fan ? "fan" : "DOT surface") + " met a neighbour)");
        (*reports)[p] = std::move(r);
        *rescued = true;
        return OkStatus();
      }
      // The patches in crossing pairs with it (or with a neighbour freed
      // before) are freed too, if they have vertices of their own to move,
      // and it is faired again; not if nothing new was freed or the fairing
      // failed.
      const size_t before = freed.size();
      for (int32_t q : crossing) {
        if (own(q) > 0) freed.insert(q);
      }
      if (!faired || freed.size() == before) break;
    }
  }
  w.live = false;
  w.dot = {};
  w.mesh = {};
  return OkStatus();
}

// Fair each live patch alone, its boundary fixed (when the patches do not
// form one manifold surface); a patch whose fairing crosses anything keeps
// its refined vertices.
Status FairEachPatch(const NetworkGraph& g, const SurfaceOptions& options,
                     const Control& control, std::vector<Work>* work,
                     std::vector<PatchReport>* reports) {
  const auto first_new = static_cast<int32_t>(g.vertices.size());
  for (size_t p = 0; p < work->size(); ++p) {
    Work& w = (*work)[p];
    if (!w.live || w.mesh.new_vertices.empty()) continue;
    // Boundary vertices first (fixed), then the patch's own.
    MeshData m;
    std::map<int32_t, int32_t> local;
    for (const Triangle& t : w.mesh.faces) {
      for (int32_t v : t) {
        if (v < first_new && local.emplace(v, m.vertices.size()).second) {
          m.vertices.push_back(g.vertices[v]);
        }
      }
    }
    const auto fixed_count = static_cast<int32_t>(m.vertices.size());
    m.vertices.insert(m.vertices.end(), w.mesh.new_vertices.begin(),
                      w.mesh.new_vertices.end());
    for (Triangle t : w.mesh.faces) {
      for (int32_t& v : t) {
        v = v < first_new ? local[v] : fixed_count + (v - first_new);
      }
      m.triangles.push_back(t);
    }
    bool faired = false;
    std::string why;
    Status s = FairMesh(&m, fixed_count, {}, options.fairing_continuity,
                        control, &faired, &why);
    if (!s.ok()) return s;
    if (!faired) {
      Note(&(*reports)[p], "not faired: " + why);
      continue;
    }
    PatchMesh faired_patch = w.mesh;
    std::copy(m.vertices.begin() + fixed_count, m.vertices.end(),
              faired_patch.new_vertices.begin());
    std::swap(w.mesh, faired_patch);
    std::vector<int32_t> owner, first;
    const MeshData all = Assemble(g, *work, true, &owner, &first);
    std::set<int32_t> crossing;
    int64_t pairs = 0;
    s = CrossingPatches(all, owner, nullptr, control, &crossing, &pairs);
    if (!s.ok()) return s;
    if (pairs > 0) {
      std::swap(w.mesh, faired_patch);
      Note(&(*reports)[p], "fairing undone: it made faces cross");
    } else {
      (*reports)[p].faired = true;
    }
  }
  return OkStatus();
}

}  // namespace

MetricWeights SurfaceOptions::DefaultSurfaceWeights() {
  MetricWeights w;
  w[Metric::kSquaredDihedral] = 1;
  w[Metric::kNormalDeviation] = 0.25;
  w[Metric::kArea] = 0.01;
  return w;
}

Status CheckSurfaceOptions(const SurfaceOptions& options) {
  FillOptions fill;
  fill.weights = options.weights;
  fill.density = options.density;
  fill.fairing_continuity = options.fairing_continuity;
  fill.threads = options.threads;
  const Status weld = CheckWeldDistance(options.weld_distance);
  if (!weld.ok()) return weld;
  return CheckFillOptions(fill);
}

std::string_view PatchStatusName(PatchStatus s) {
  switch (s) {
    case PatchStatus::kSurfaced:
      return "surfaced";
    case PatchStatus::kFailed:
      return "failed";
    case PatchStatus::kSkipped:
      return "skipped";
  }
  return "unknown";
}

namespace {

SurfaceResult Surface(const CurveNetwork& network,
                      const SurfaceOptions& options, const Control& control,
                      const SurfaceProgressFn& on_progress) {
  const auto t_start = Clock::now();
  SurfaceResult out;
  SurfaceReport& report = out.report;
  auto fail = [&](Status s) {
    out.status = std::move(s);
    out.mesh = {};
    report.total_ms = MsSince(t_start);
    return std::move(out);
  };
  Status s = CheckSurfaceOptions(options);
  if (!s.ok()) return fail(s);
  NetworkGraph g;
  s = BuildNetworkGraph(network, &g, control, options.weld_distance);
  if (!s.ok()) return fail(s);
  for (int32_t v : g.vertex_of_input) {
    out.vertex_of_input.push_back(v < 0 ? -1 : g.input_of_vertex[v]);
  }
  if (g.welded_edges > 0) {
    report.notes.push_back(std::to_string(g.welded_edges) +
                           " edges dropped: the weld joined their ends");
  }
  report.curves = static_cast<int32_t>(g.curves.size());
  for (const NetworkCurve& c : g.curves) {
    std::vector<int32_t> ids;
    for (int32_t v : c.vertices) ids.push_back(g.input_of_vertex[v]);
    report.curve_vertices.push_back(std::move(ids));
  }
  report.merged_vertices = g.merged_vertices;
  report.dangling = g.dangling;
  {
    std::set<int32_t> ends;
    for (const NetworkCurve& c : g.curves) {
      ends.insert(c.vertices.front());
      ends.insert(c.vertices.back());
    }
    report.junctions = static_cast<int32_t>(ends.size());
  }
  auto t = Clock::now();
  std::vector<NetworkCycle> cycles;
  s = options.cycles.empty()
          ? FindNetworkCycles(g, &cycles, &report.notes, control,
                              {options.islands, options.walls})
          : CyclesFromVertices(g, options.cycles, &cycles, control);
  if (!s.ok()) return fail(s);
  report.cycles_ms = MsSince(t);
  if (cycles.empty()) {
    return fail(InvalidArgument(
        "the network bounds no patch (" + std::to_string(g.dangling.size()) +
        " of its " + std::to_string(g.curves.size()) +
        " curves are dangling: an end no other curve meets)"));
  }
  const auto first_new = static_cast<int32_t>(g.vertices.size());
  const size_t patch_count = cycles.size();
  std::vector<Work> work(patch_count);
  report.patches.resize(patch_count);
  std::vector<std::vector<int32_t>> neighbours(g.vertices.size());
  for (const NetworkCurve& c : g.curves) {
    for (size_t k = 0; k + 1 < c.vertices.size(); ++k) {
      neighbours[c.vertices[k]].push_back(c.vertices[k + 1]);
      neighbours[c.vertices[k + 1]].push_back(c.vertices[k]);
    }
  }
  for (size_t p = 0; p < patch_count; ++p) {
    PatchReport& r = report.patches[p];
    r.id = static_cast<int32_t>(p);
    r.loops = cycles[p].loops;
    Work& w = work[p];
    std::set<int32_t> in_patch;
    for (const auto& loop : cycles[p].loops) {
      w.loops.push_back(LoopVertices(g, loop));
      const auto& vs = w.loops.back();
      r.loop_vertices.emplace_back();
      for (int32_t v : vs)
        r.loop_vertices.back().push_back(g.input_of_vertex[v]);
      r.boundary_vertices += static_cast<int32_t>(vs.size());
      for (size_t k = 0; k < vs.size(); ++k) {
        ++w.boundary[Key(vs[k], vs[(k + 1) % vs.size()])];
        in_patch.insert(vs[k]);
      }
    }
    for (int32_t v : in_patch) {
      for (int32_t u : neighbours[v]) {
        if (v < u && in_patch.count(u)) w.forbidden.emplace_back(v, u);
      }
    }
    if (cycles[p].loops.size() == 1 && RunsACurveTwice(cycles[p].loops[0])) {
      std::string why;
      if (!SplitSeam(g, cycles[p].loops[0], &w.seam, &why)) {
        r.reason = "it runs a curve both ways and " + why;
        continue;
      }
      report.notes.push_back(
          "patch " + std::to_string(p) +
          " runs a seam both ways: surfaced in two pieces joined by a new "
          "path of " +
          std::to_string(w.seam.new_vertices.size()) +
          " vertices between input vertices " +
          std::to_string(g.input_of_vertex[w.seam.from]) + " and " +
          std::to_string(g.input_of_vertex[w.seam.to]) + " (numbered from 0)");
    }
  }
  std::vector<int> todo;
  if (options.skip_longest && options.cycles.empty()) {
    // By its outer loop: an island makes a face no longer (a sheet's back
    // face is as long as its front, which may hold an island), and an
    // island's own patch (inset) is never the rim.
    std::set<int32_t> island_curves;
    for (const NetworkCycle& c : cycles) {
      for (size_t k = 1; k < c.loops.size(); ++k) {
        for (const CurveUse& u : c.loops[k]) island_curves.insert(u.curve);
      }
    }
    int64_t longest = -1;
    for (size_t p = 0; p < patch_count; ++p) {
      if (island_curves.count(cycles[p].loops[0][0].curve)) continue;
      if (longest < 0 ||
          work[p].loops[0].size() > work[longest].loops[0].size()) {
        longest = static_cast<int64_t>(p);
      }
    }
    if (longest < 0) longest = 0;
    report.patches[longest].reason = "the longest cycle (skip_longest)";
  }
  for (size_t p = 0; p < patch_count; ++p) {
    if (report.patches[p].reason.empty()) todo.push_back(static_cast<int>(p));
  }
  if (on_progress) on_progress(0, static_cast<int>(todo.size()));

  // Pass 1: DOT without normals, for the normals the curves share.
  t = Clock::now();
  Control patch_control = control;
  patch_control.progress = nullptr;
  std::vector<Status> first_status(patch_count);
  std::vector<Vec3> normals = g.normals;
  if (normals.empty()) {
    s = ForEachPatch(options, todo, [&](int p) {
      PatchReport scratch;
      Status r = SolvePatch(g, work[p], {}, options, patch_control,
                            &work[p].dot, &scratch);
      if (r.code == StatusCode::kCancelled ||
          r.code == StatusCode::kDeadlineExceeded) {
        return r;
      }
      first_status[p] = r;
      return OkStatus();
    });
    if (!s.ok()) return fail(s);
    normals.assign(g.vertices.size(), Vec3{});
    for (int p : todo) {
      // A wall faces either way: the patches around its curves decide.
      if (!first_status[p].ok() || cycles[p].wall) continue;
      const PatchMesh& pm = work[p].dot;
      auto at = [&](int32_t v) -> const Vec3& {
        return v < first_new ? g.vertices[v] : pm.new_vertices[v - first_new];
      };
      for (const Triangle& tri : pm.faces) {
        const Vec3& a = at(tri[0]);
        const Vec3& b = at(tri[1]);
        const Vec3& c = at(tri[2]);
        const Vec3 n = Cross(b - a, c - a);
        if (Norm(n) == 0) continue;
        const Vec3 unit = Normalized(n);
        // Angle-weighted: each corner adds the face normal times its angle.
        const Vec3* corner[3] = {&a, &b, &c};
        for (int k = 0; k < 3; ++k) {
          const Vec3 e1 = *corner[(k + 1) % 3] - *corner[k];
          const Vec3 e2 = *corner[(k + 2) % 3] - *corner[k];
          const double angle = std::atan2(Norm(Cross(e1, e2)), Dot(e1, e2));
          if (tri[k] >= first_new) continue;  // a seam's new path
          normals[tri[k]] = normals[tri[k]] + angle * unit;
        }
      }
    }
    for (Vec3& n : normals) {
      if (Norm(n) > 0) n = Normalized(n);
    }
  }
  // Pass 2: with the shared normals (a vertex no first patch reached has a
  // zero normal, which the metric ignores).
  std::mutex progress_mu;
  int done = 0;
  std::vector<Status> status(patch_count);
  auto solve = [&](int p) {
    Status r = SolvePatch(g, work[p], normals, options, patch_control,
                          &work[p].dot, &report.patches[p]);
    if (r.code == StatusCode::kCancelled ||
        r.code == StatusCode::kDeadlineExceeded) {
      return r;
    }
    status[p] = r;
    work[p].live = r.ok();
    return OkStatus();
  };
  s = ForEachPatch(options, todo, [&](int p) {
    Status r = solve(p);
    if (r.ok() && on_progress) {
      std::lock_guard<std::mutex> lock(progress_mu);
      on_progress(++done, static_cast<int>(todo.size()));
    }
    return r;
  });
  if (!s.ok()) return fail(s);
  std::vector<RescueTry> first_dot(patch_count);
  for (int p : todo) {
    if (work[p].live) first_dot[p] = {work[p].dot, report.patches[p]};
  }
  // Patches that meet others wrongly are solved again without the chords
  // of their faces in the conflict.
  // A patch DOT could not triangulate, or that still meets others after
  // its re-solves, gets a fan (once). A patch whose re-solve finds nothing
  // is put back as it was and made to stand: the other patch of its
  // conflicts gives way next time.
  std::vector<char> stubborn(patch_count, 0), fanned(patch_count, 0);
  auto fan = [&](int p, const std::string& why) {
    fanned[p] = 1;
    if (!FanWork(g, work[p], &work[p].dot).ok()) return;
    work[p].live = true;
    report.patches[p].fan = true;
    report.patches[p].space = SpaceUsed::kNone;
    report.patches[p].solver = Solver::kNone;
    report.patches[p].cost = 0;
    report.patches[p].reason = "a fan from the centroid: " + why;
    status[p] = OkStatus();
  };
  for (int p : todo) {
    if (status[p].code == StatusCode::kNoTriangulation) {
      fan(p, "DOT found no triangulation (" + status[p].message + ")");
    }
  }
  for (int round = 0;; ++round) {
    std::map<int32_t, std::set<Chord>> more;
    std::map<int32_t, std::string> why;
    s = FindConflicts(g, work, stubborn, round % 2 == 1, control, &more, &why);
    if (!s.ok()) return fail(s);
    if (more.empty()) break;
    std::vector<int> again;
    std::map<int, Work> before;
    for (auto& [p, chords] : more) {
      const std::string failure =
          "its surface " + why[p] + " after " +
          std::to_string(report.patches[p].resolves) +
          (report.patches[p].resolves == 1 ? " re-solve" : " re-solves");
      if (round >= kResolveRounds || chords.empty() || fanned[p]) {
        if (!fanned[p]) {
          fan(p, failure);
          if (work[p].live) continue;
        }
        work[p].live = false;
        status[p] = MakeStatus(
            StatusCode::kNoTriangulation,
            report.patches[p].fan ? failure + ", and so does a fan" : failure);
        continue;
      }
      before[p] = work[p];
      work[p].forbidden.insert(work[p].forbidden.end(), chords.begin(),
                               chords.end());
      ++report.patches[p].resolves;
      again.push_back(p);
    }
    s = ForEachPatch(options, again, solve);
    if (!s.ok()) return fail(s);
    for (auto& [p, old] : before) {
      if (work[p].live) continue;
      work[p] = std::move(old);
      status[p] = OkStatus();
      stubborn[p] = 1;
    }
  }
  for (int p : todo) {
    PatchReport& r = report.patches[p];
    if (work[p].live) {
      r.status = PatchStatus::kSurfaced;
      work[p].mesh = work[p].dot;
    } else {
      r.status = PatchStatus::kFailed;
      r.reason = status[p].message;
      work[p].dot = {};
    }
  }
  report.triangulate_ms = MsSince(t);

  // Refinement, patch by patch, each within its share of the memory
  // budget. A refined patch that made a chord on an edge another face
  // already has is put back (and one that crosses another, unless the
  // fairing follows).
  std::set<Chord> curve_edges;
  for (const NetworkCurve& c : g.curves) {
    for (size_t k = 0; k + 1 < c.vertices.size(); ++k) {
      curve_edges.insert(Key(c.vertices[k], c.vertices[k + 1]));
    }
  }
  std::vector<int> live;
  for (int p : todo) {
    if (work[p].live) live.push_back(p);
  }
  if (options.stage != FillStage::kTriangulate) {
    t = Clock::now();
    // Each patch gets its share of the memory budget (what refinement and
    // fairing take per new vertex), so the whole network stays within it.
    const int64_t share =
        options.triangulate.memory_budget_bytes /
        std::max<int64_t>(1, static_cast<int64_t>(live.size()));
    s = ForEachPatch(options, live, [&](int p) {
      const size_t cap = RefinedVertexCap(
          static_cast<size_t>(report.patches[p].boundary_vertices), share,
          /*floor=*/0);
      return RefinePatch(g, options, patch_control, first_new, cap,
                         &work[p].mesh, &report.patches[p]);
    });
    if (!s.ok()) return fail(s);
    // Crossings of refined patches are the fairing's to judge (a coarse
    // fan crosses where its faired surface does not); without fairing,
    // they are undone here.
    s = PutBack(g, control, curve_edges, options.stage == FillStage::kRefine,
                &work, &report.patches);
    if (!s.ok()) return fail(s);
    report.refine_ms = MsSince(t);
  }

  // Fairing of the whole network. A patch whose faired surface crosses
  // anything is fixed where refinement left it, and if it crosses again,
  // put back to its DOT surface; the rest are faired again. The DOT
  // surfaces were checked apart, so this ends.
  std::vector<int32_t> owner, first;
  MeshData mesh = Assemble(g, work, true, &owner, &first);
  if (options.stage == FillStage::kFair &&
      mesh.vertices.size() > g.vertices.size()) {
    t = Clock::now();
    std::vector<char> pinned(patch_count, 0);
    std::string why;
    for (size_t round = 0; round <= 2 * patch_count; ++round) {
      mesh = Assemble(g, work, true, &owner, &first);
      std::vector<char> fixed(mesh.vertices.size(), 0);
      for (int p : live) {
        if (!pinned[p]) continue;
        std::fill(
            fixed.begin() + first[p],
            fixed.begin() + first[p] +
                static_cast<std::ptrdiff_t>(work[p].mesh.new_vertices.size()),
            1);
      }
      bool faired = false;
      std::string fair_why;  // empty: every patch pinned (why says why)
      s = FairMesh(&mesh, first_new, fixed, options.fairing_continuity, control,
                   &faired, &fair_why);
      if (!s.ok()) return fail(s);
      if (!faired) {
        if (!fair_why.empty()) why = fair_why;
        break;
      }
      std::set<int32_t> crossing;
      int64_t pairs = 0;
      s = CrossingPatches(mesh, owner, nullptr, control, &crossing, &pairs);
      if (!s.ok()) return fail(s);
      if (pairs == 0) {
        report.faired_whole = true;
        break;
      }
      bool changed = false;
      for (int32_t p : crossing) {
        if (!pinned[p]) {
          pinned[p] = 1;
          changed = true;
          Note(&report.patches[p], "fairing undone: it made faces cross");
        } else {
          changed |= PutBackOne(&work[p], &report.patches[p],
                                "refinement undone: it crossed unfaired");
        }
      }
      why = "faces still crossed after " + std::to_string(round + 1) +
            (round == 0 ? " round" : " rounds");
      if (!changed) break;
    }
    if (report.faired_whole) {
      for (int p : live) {
        auto& moved = work[p].mesh.new_vertices;
        std::copy(mesh.vertices.begin() + first[p],
                  mesh.vertices.begin() + first[p] +
                      static_cast<std::ptrdiff_t>(moved.size()),
                  moved.begin());
        report.patches[p].faired = !moved.empty() && !pinned[p];
      }
    } else {
      report.notes.push_back("the network was faired patch by patch: " + why);
      s = PutBack(g, control, curve_edges, true, &work, &report.patches);
      if (!s.ok()) return fail(s);
      s = FairEachPatch(g, options, control, &work, &report.patches);
      if (!s.ok()) return fail(s);
    }
    // A patch left open because its DOT surface (and its fan) met a
    // neighbour may not once faired: the coarse triangles were what met.
    // Tried again against the finished surface, faired alone with all
    // else fixed or with the neighbours it crosses, kept only if it meets
    // nothing. One pass: trying the rest again after a rescue found no
    // more on the benchmark's networks and took a third longer.
    for (int p : todo) {
      if (work[p].live) continue;
      std::vector<RescueTry> tries;
      if (!first_dot[p].mesh.faces.empty()) tries.push_back(first_dot[p]);
      RescueTry fan_try;
      if (FanWork(g, work[p], &fan_try.mesh).ok()) {
        fan_try.report = report.patches[p];
        fan_try.report.fan = true;
        fan_try.report.space = SpaceUsed::kNone;
        fan_try.report.solver = Solver::kNone;
        fan_try.report.cost = 0;
        tries.push_back(std::move(fan_try));
      }
      const int64_t share =
          options.triangulate.memory_budget_bytes /
          std::max<int64_t>(1, static_cast<int64_t>(live.size()) + 1);
      const size_t cap = RefinedVertexCap(
          static_cast<size_t>(report.patches[p].boundary_vertices), share,
          /*floor=*/0);
      bool rescued = false;
      s = RescuePatch(g, options, control, curve_edges, p, tries, cap, &work,
                      &report.patches, &rescued);
      if (!s.ok()) return fail(s);
      if (rescued) live.push_back(p);
    }
    std::sort(live.begin(), live.end());
    mesh = Assemble(g, work, true, &owner, &first);
    report.fair_ms = MsSince(t);
  }

  // The contract, checked: no crossings, and which curves close.
  t = Clock::now();
  std::set<int32_t> crossing;
  s = CrossingPatches(mesh, owner, nullptr, control, &crossing,
                      &report.intersecting_pairs);
  if (!s.ok()) return fail(s);
  if (report.intersecting_pairs != 0) {
    return fail(MakeStatus(StatusCode::kInternal,
                           "the surface crosses itself after every check (" +
                               std::to_string(report.intersecting_pairs) +
                               " pairs)"));
  }
  std::string what;
  if (!SharedEdgePatches(mesh, owner, work, curve_edges, &what).empty()) {
    return fail(MakeStatus(StatusCode::kInternal,
                           "patches meet along an edge that is not a curve "
                           "they share, after every check: " +
                               (what.empty() ? "an edge with more than two "
                                               "faces, or two the same way"
                                             : what)));
  }
  std::vector<int> uses(g.curves.size(), 0);
  for (int p : live) {
    for (const auto& loop : report.patches[p].loops) {
      for (const CurveUse& u : loop) ++uses[u.curve];
    }
  }
  std::vector<char> dangling(g.curves.size(), 0);
  for (int32_t c : g.dangling) dangling[c] = 1;
  report.closed = !live.empty();
  for (size_t c = 0; c < g.curves.size(); ++c) {
    if (!dangling[c] && uses[c] < 2) report.closed = false;
    if (uses[c] > 2) ++report.non_manifold_curves;
  }
  if (report.closed) {
    // A closed surface faces out (the embedding's sign is arbitrary). Its
    // walls, open and facing either way, would add a volume that grows
    // with their distance from the origin.
    double volume6 = 0;
    for (size_t f = 0; f < mesh.triangles.size(); ++f) {
      if (cycles[owner[f]].wall) continue;
      const Triangle& tri = mesh.triangles[f];
      volume6 += Dot(mesh.vertices[tri[0]],
                     Cross(mesh.vertices[tri[1]], mesh.vertices[tri[2]]));
    }
    if (volume6 < 0) {
      for (Triangle& tri : mesh.triangles) std::swap(tri[1], tri[2]);
      for (int p : live) {
        for (Triangle& tri : work[p].mesh.faces) std::swap(tri[1], tri[2]);
      }
    }
  }
  report.check_ms = MsSince(t);
  for (const PatchReport& r : report.patches) {
    if (r.status == PatchStatus::kSurfaced) ++report.surfaced;
    if (r.status == PatchStatus::kFailed) ++report.failed;
  }
  for (int p : live) {
    report.patches[p].triangles =
        static_cast<int32_t>(work[p].mesh.faces.size());
  }
  // In the input's numbering: its vertices, every one, then the new ones.
  const auto inputs = static_cast<int32_t>(network.vertices.size());
  out.mesh.vertices = network.vertices;
  out.mesh.vertices.insert(out.mesh.vertices.end(),
                           mesh.vertices.begin() + first_new,
                           mesh.vertices.end());
  out.mesh.triangles = std::move(mesh.triangles);
  for (Triangle& tri : out.mesh.triangles) {
    for (int32_t& v : tri) {
      v = v < first_new ? g.input_of_vertex[v] : inputs + (v - first_new);
    }
  }
  report.total_ms = MsSince(t_start);
  return out;
}

}  // namespace

SurfaceResult SurfaceNetwork(const CurveNetwork& network,
                             const SurfaceOptions& options,
                             const Control& control,
                             const SurfaceProgressFn& on_progress) {
  // Memory runs out as an error of this call, not of the process.
  SurfaceResult out;
  try {
    return Surface(network, options, control, on_progress);
  } catch (const std::bad_alloc&) {
    out.status = MakeStatus(StatusCode::kResourceExhausted,
                            "out of memory surfacing the network");
  } catch (const std::exception& e) {
    out.status = MakeStatus(StatusCode::kInternal,
                            std::string("surfacing failed: ") + e.what());
  }
  return out;
}

}  // namespace dot
