// SPDX-License-Identifier: AGPL-3.0-or-later
#include "fill/soup_output.h"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <unordered_map>
#include <utility>

#include "mesh/edge_index.h"

namespace dot {
namespace {

constexpr int32_t kNone = -1;

bool SameEntry(const AttributeChannel& ch, int32_t a, int32_t b) {
  return a == b || std::equal(ch.entry(a), ch.entry(a) + ch.dims, ch.entry(b));
}

// Appends an entry and returns its index; normals renormalized, colours
// clamped, as the channel's name says.
int32_t AddEntry(AttributeChannel* ch, std::vector<double> value) {
  if (ch->name == "normal" && value.size() == 3) {
    const double n = std::sqrt(value[0] * value[0] + value[1] * value[1] +
                               value[2] * value[2]);
    if (n > 0) {
      for (double& x : value) x /= n;
    }
  } else if (ch->name == "color") {
    for (double& x : value) x = std::clamp(x, 0.0, 1.0);
  }
  const auto e = static_cast<int32_t>(ch->entries());
  for (double x : value) ch->values.push_back(static_cast<float>(x));
  return e;
}

// A weighted sum of entries.
std::vector<double> Blend(const AttributeChannel& ch,
                          const std::vector<std::pair<int32_t, double>>& w) {
  std::vector<double> v(ch.dims, 0.0);
  for (const auto& [e, weight] : w) {
    for (int d = 0; d < ch.dims; ++d) v[d] += weight * ch.entry(e)[d];
  }
  return v;
}

// Barycentric coordinates of p in triangle abc (of its projection onto the
// triangle's plane), clamped into the triangle.
std::array<double, 3> Barycentric(const Vec3& a, const Vec3& b, const Vec3& c,
                                  const Vec3& p) {
  const Vec3 v0 = b - a, v1 = c - a, v2 = p - a;
  const double d00 = Dot(v0, v0), d01 = Dot(v0, v1), d11 = Dot(v1, v1);
  const double d20 = Dot(v2, v0), d21 = Dot(v2, v1);
  const double denom = d00 * d11 - d01 * d01;
  if (!(std::abs(denom) > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  const double v = (d11 * d20 - d01 * d21) / denom;
  const double w = (d00 * d21 - d01 * d20) / denom;
  std::array<double, 3> l = {std::max(0.0, 1 - v - w), std::max(0.0, v),
                             std::max(0.0, w)};
  const double sum = l[0] + l[1] + l[2];
  for (double& x : l) x /= sum;
  return l;
}

// Per corner of the result's triangles, the entry of each channel.
using CornerEntries = std::vector<std::vector<int32_t>>;  // [channel][3t+k]

// The corners of one filled hole's patch faces, given the entries of every
// other face: see the header for the method.
class PatchInterpolator {
 public:
  PatchInterpolator(const std::vector<Vec3>& points,
                    const std::vector<Triangle>& faces, size_t first_face,
                    size_t count)
      : points_(points), faces_(faces), first_(first_face), count_(count) {
    std::unordered_map<uint64_t, int> uses;
    for (size_t f = first_; f < first_ + count_; ++f) {
      for (int k = 0; k < 3; ++k) {
        const Triangle& t = faces_[f];
        Local(t[k]);
        ++uses[UndirectedEdgeKey(t[k], t[(k + 1) % 3])];
      }
    }
    neighbours_.resize(vertices_.size());
    for (size_t f = first_; f < first_ + count_; ++f) {
      const Triangle& t = faces_[f];
      for (int k = 0; k < 3; ++k) {
        const int32_t a = t[k], b = t[(k + 1) % 3];
        const int la = local_.at(a), lb = local_.at(b);
        auto& na = neighbours_[la];
        if (std::find(na.begin(), na.end(), lb) == na.end()) {
          na.push_back(lb);
          neighbours_[lb].push_back(la);
        }
        if (uses[UndirectedEdgeKey(a, b)] == 1) rim_.push_back({a, b});
      }
    }
  }

  // The rim's directed edges (as in the patch faces).
  const std::vector<std::pair<int32_t, int32_t>>& rim() const { return rim_; }

  // Fills the patch corners of channel `ch` in `entries`, given per rim
  // edge the entries of its two ends in the face across (kNone: no face).
  void Interpolate(AttributeChannel* ch,
                   const std::vector<std::pair<int32_t, int32_t>>& across,
                   std::vector<int32_t>* entries) {
    const std::vector<std::vector<std::pair<int, int32_t>>> arcs =
        Arcs(*ch, across);
    if (arcs.empty()) return;  // no face across: see CarryThroughFill
    // Nearest arc of each patch face: least sum of corner hops.
    std::vector<std::vector<int>> hops;
    for (const auto& arc : arcs) hops.push_back(Hops(arc));
    std::vector<int> arc_of(count_, 0);
    for (size_t f = 0; f < count_; ++f) {
      long best = std::numeric_limits<long>::max();
      for (size_t a = 0; a < arcs.size(); ++a) {
        long sum = 0;
        for (int32_t v : faces_[first_ + f]) sum += hops[a][local_.at(v)];
        if (sum < best) {
          best = sum;
          arc_of[f] = static_cast<int>(a);
        }
      }
    }
    for (size_t a = 0; a < arcs.size(); ++a) {
      if (std::find(arc_of.begin(), arc_of.end(), static_cast<int>(a)) ==
          arc_of.end()) {
        continue;
      }
      const std::vector<int32_t> field = ch->name == "normal" && ch->dims == 3
                                             ? SurfaceNormals(ch, arcs[a])
                                             : Solve(ch, arcs[a]);
      for (size_t f = 0; f < count_; ++f) {
        if (arc_of[f] != static_cast<int>(a)) continue;
        const Triangle& t = faces_[first_ + f];
        for (int k = 0; k < 3; ++k) {
          (*entries)[3 * (first_ + f) + k] = field[local_.at(t[k])];
        }
      }
    }
  }

 private:
  int Local(int32_t v) {
    auto [it, fresh] =
        local_.try_emplace(v, static_cast<int>(vertices_.size()));
    if (fresh) vertices_.push_back(v);
    return it->second;
  }

  // The rim cut into arcs of agreeing values: per arc, (local vertex,
  // entry) pairs. One arc when no rim vertex sees two values.
  std::vector<std::vector<std::pair<int, int32_t>>> Arcs(
      const AttributeChannel& ch,
      const std::vector<std::pair<int32_t, int32_t>>& across) const {
    const size_t n = rim_.size();
    // Chain the rim edges: next[i] starts where edge i ends.
    std::unordered_map<int32_t, size_t> starting;
    for (size_t i = 0; i < n; ++i) starting[rim_[i].first] = i;
    std::vector<size_t> next(n, n);
    for (size_t i = 0; i < n; ++i) {
      auto it = starting.find(rim_[i].second);
      if (it != starting.end()) next[i] = it->second;
    }
    // A break between edge i and next[i]: their values at the shared vertex
    // differ (a seam), or one has no face across.
    auto breaks = [&](size_t i) {
      const size_t j = next[i];
      if (j == n) return true;
      const int32_t a = across[i].second, b = across[j].first;
      return a == kNone || b == kNone || !SameEntry(ch, a, b);
    };
    size_t start = 0;
    bool any_break = false;
    for (size_t i = 0; i < n; ++i) {
      if (breaks(i)) {
        start = next[i] == n ? 0 : next[i];
        any_break = true;
        break;
      }
    }
    std::vector<std::vector<std::pair<int, int32_t>>> arcs(1);
    std::vector<bool> seen(n, false);
    auto add = [&](size_t i) {
      seen[i] = true;
      auto& arc = arcs.back();
      const auto [ea, eb] = across[i];
      if (ea != kNone) arc.push_back({local_.at(rim_[i].first), ea});
      if (eb != kNone) arc.push_back({local_.at(rim_[i].second), eb});
    };
    for (size_t i = start; i < n && !seen[i]; i = next[i]) {
      add(i);
      if (any_break && breaks(i) && next[i] < n && !seen[next[i]]) {
        arcs.emplace_back();
      }
    }
    for (size_t i = 0; i < n; ++i) {
      if (seen[i]) continue;  // a rim that does not chain (pinched): a new arc
      arcs.emplace_back();
      for (size_t j = i; j < n && !seen[j]; j = next[j]) add(j);
    }
    // A vertex named twice in an arc keeps its first entry; arcs without
    // any value are dropped.
    for (auto& arc : arcs) {
      std::vector<std::pair<int, int32_t>> unique;
      for (const auto& p : arc) {
        if (std::none_of(unique.begin(), unique.end(),
                         [&](const auto& q) { return q.first == p.first; })) {
          unique.push_back(p);
        }
      }
      arc = std::move(unique);
    }
    arcs.erase(std::remove_if(arcs.begin(), arcs.end(),
                              [](const auto& a) { return a.empty(); }),
               arcs.end());
    return arcs;
  }

  // Hops from the arc's vertices over patch edges.
  std::vector<int> Hops(const std::vector<std::pair<int, int32_t>>& arc) const {
    std::vector<int> d(vertices_.size(), std::numeric_limits<int>::max() / 4);
    std::deque<int> queue;
    for (const auto& [v, e] : arc) {
      d[v] = 0;
      queue.push_back(v);
    }
    while (!queue.empty()) {
      const int v = queue.front();
      queue.pop_front();
      for (int w : neighbours_[v]) {
        if (d[w] > d[v] + 1) {
          d[w] = d[v] + 1;
          queue.push_back(w);
        }
      }
    }
    return d;
  }

  // The harmonic field with the arc fixed: an entry per local vertex (the
  // arc's own entries on it, new entries elsewhere).
  std::vector<int32_t> Solve(AttributeChannel* ch,
                             const std::vector<std::pair<int, int32_t>>& arc) {
    const size_t nv = vertices_.size();
    std::vector<int32_t> field(nv, kNone);
    for (const auto& [v, e] : arc) field[v] = e;
    std::vector<int> unknown(nv, -1);
    int m = 0;
    for (size_t v = 0; v < nv; ++v) {
      if (field[v] == kNone) unknown[v] = m++;
    }
    if (m == 0) return field;
    const int dims = ch->dims;
    if (weights_.empty()) weights_ = MeanValueWeights();
    using SpMat = Eigen::SparseMatrix<double>;
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m, dims);
    for (size_t v = 0; v < nv; ++v) {
      const int row = unknown[v];
      if (row < 0) continue;
      double diagonal = 0;
      for (const auto& [w, weight] : weights_[v]) {
        diagonal += weight;
        if (unknown[w] >= 0) {
          entries.emplace_back(row, unknown[w], -weight);
        } else {
          for (int d = 0; d < dims; ++d) {
            rhs(row, d) += weight * ch->entry(field[w])[d];
          }
        }
      }
      entries.emplace_back(row, row, diagonal);
    }
    SpMat a(m, m);
    a.setFromTriplets(entries.begin(), entries.end());
    Eigen::SparseLU<SpMat> lu;
    lu.compute(a);
    Eigen::MatrixXd x;
    bool solved = lu.info() == Eigen::Success;
    if (solved) {
      x = lu.solve(rhs);
      solved = lu.info() == Eigen::Success && x.allFinite();
    }
    if (!solved) {  // unreachable for a connected patch: the arc's mean
      std::vector<std::pair<int32_t, double>> w;
      for (const auto& p : arc) w.push_back({p.second, 1.0 / arc.size()});
      const std::vector<double> mean = Blend(*ch, w);
      x = Eigen::MatrixXd(m, dims);
      for (int r = 0; r < m; ++r) {
        for (int d = 0; d < dims; ++d) x(r, d) = mean[d];
      }
    }
    for (size_t v = 0; v < nv; ++v) {
      const int row = unknown[v];
      if (row < 0) continue;
      std::vector<double> value(dims);
      for (int d = 0; d < dims; ++d) value[d] = x(row, d);
      field[v] = AddEntry(ch, std::move(value));
    }
    return field;
  }

  // Floater's mean-value weights, per local vertex (neighbour, weight):
  // w_ij = (tan(a/2) + tan(b/2)) / |x_i - x_j|, a and b the face angles at
  // i beside edge ij. Always positive (values stay within the rim's, as
  // with uniform weights), and a linear field on a flat patch is
  // reproduced exactly (uniform weights distort UVs there).
  std::vector<std::vector<std::pair<int, double>>> MeanValueWeights() const {
    std::vector<std::vector<std::pair<int, double>>> w(vertices_.size());
    auto add = [&](int i, int j, double weight) {
      for (auto& [k, x] : w[i]) {
        if (k == j) {
          x += weight;
          return;
        }
      }
      w[i].push_back({j, weight});
    };
    for (size_t f = first_; f < first_ + count_; ++f) {
      const Triangle& t = faces_[f];
      for (int k = 0; k < 3; ++k) {
        const int i = local_.at(t[k]), j = local_.at(t[(k + 1) % 3]),
                  l = local_.at(t[(k + 2) % 3]);
        const Vec3 u = points_[t[(k + 1) % 3]] - points_[t[k]];
        const Vec3 v = points_[t[(k + 2) % 3]] - points_[t[k]];
        const double lu = std::sqrt(Dot(u, u)), lv = std::sqrt(Dot(v, v));
        const double sin_part = std::sqrt(Dot(Cross(u, v), Cross(u, v)));
        const double cos_part = lu * lv + Dot(u, v);
        // tan(angle / 2), bounded for a degenerate corner.
        const double half_tan =
            cos_part > 1e-300 ? std::min(sin_part / cos_part, 1e6) : 1e6;
        if (lu > 0) add(i, j, half_tan / lu);
        if (lv > 0) add(i, l, half_tan / lv);
      }
    }
    return w;
  }

  // Normals of new vertices follow the patch's own faces (area-weighted),
  // turned to agree with the arc's normals; a blend of the rim's normals
  // would not follow the surface the fill made.
  std::vector<int32_t> SurfaceNormals(
      AttributeChannel* ch, const std::vector<std::pair<int, int32_t>>& arc) {
    std::vector<Vec3> n(vertices_.size(), Vec3{0, 0, 0});
    for (size_t f = first_; f < first_ + count_; ++f) {
      const Triangle& t = faces_[f];
      const Vec3 c =
          Cross(points_[t[1]] - points_[t[0]], points_[t[2]] - points_[t[0]]);
      for (int32_t v : t) n[local_.at(v)] = n[local_.at(v)] + c;
    }
    double agree = 0;
    for (const auto& [v, e] : arc) {
      const float* a = ch->entry(e);
      agree += a[0] * n[v].x + a[1] * n[v].y + a[2] * n[v].z;
    }
    const double sign = agree < 0 ? -1 : 1;
    std::vector<int32_t> field(vertices_.size(), kNone);
    for (const auto& [v, e] : arc) field[v] = e;
    for (size_t v = 0; v < field.size(); ++v) {
      if (field[v] == kNone) {
        field[v] = AddEntry(ch, {sign * n[v].x, sign * n[v].y, sign * n[v].z});
      }
    }
    return field;
  }

  const std::vector<Vec3>& points_;
  const std::vector<Triangle>& faces_;
  size_t first_, count_;
  std::unordered_map<int32_t, int> local_;
  std::vector<int32_t> vertices_;  // local -> mesh id
  std::vector<std::vector<int>> neighbours_;
  std::vector<std::vector<std::pair<int, double>>> weights_;  // when solved
  std::vector<std::pair<int32_t, int32_t>> rim_;
};

// Faces of the result at given vertices, found in one pass over the faces
// that are not in patches: (vertex, face) pairs sorted by vertex.
class FacesAt {
 public:
  FacesAt(const std::vector<Triangle>& faces, const std::vector<bool>& skip,
          const std::vector<bool>& wanted) {
    for (size_t f = 0; f < faces.size(); ++f) {
      if (skip[f]) continue;
      for (int32_t v : faces[f]) {
        if (wanted[v]) pairs_.push_back({v, static_cast<int32_t>(f)});
      }
    }
    std::sort(pairs_.begin(), pairs_.end());
  }
  // The face that has side b -> a (the face across patch side a -> b), or
  // kNone, and the corners of a and b in it.
  int32_t Across(const std::vector<Triangle>& faces, int32_t a, int32_t b,
                 int* ka, int* kb) const {
    auto it = std::lower_bound(pairs_.begin(), pairs_.end(),
                               std::make_pair(a, int32_t{-1}));
    for (; it != pairs_.end() && it->first == a; ++it) {
      const Triangle& t = faces[it->second];
      for (int k = 0; k < 3; ++k) {
        if (t[k] == b && t[(k + 1) % 3] == a) {
          *kb = k;
          *ka = (k + 1) % 3;
          return it->second;
        }
      }
    }
    return kNone;
  }

 private:
  std::vector<std::pair<int32_t, int32_t>> pairs_;
};

// The corners of the result's triangles, channel by channel: the trace's
// for the input triangles, then the split pieces and the patches.
bool CarryThroughFill(const FillResult& fill, int64_t input_faces,
                      SoupTrace* trace, CornerEntries* corners) {
  const std::vector<Triangle>& tris = fill.mesh.triangles;
  const std::vector<Vec3>& points = fill.mesh.vertices;
  const size_t nc = trace->channels.size();
  corners->assign(nc, {});
  if (nc == 0) return true;
  for (size_t c = 0; c < nc; ++c) {
    (*corners)[c] = std::move(trace->channels[c].indices);
    (*corners)[c].resize(3 * tris.size(), kNone);
  }
  // Where each hole's faces are in the result (see Merge in fill_holes.cc):
  // its split faces in place, their other pieces, then its patch.
  std::vector<bool> in_patch(tris.size(), false);
  std::vector<bool> on_rim(points.size(), false);
  struct Span {
    size_t first, count;
  };
  std::vector<Span> patches;
  size_t cursor = static_cast<size_t>(input_faces);
  for (const FilledHole& h : fill.patches) {
    for (size_t k = 0; k < h.patch.split_faces.size(); ++k) {
      const int32_t f = h.patch.split_faces[k];
      const Triangle& orig = trace->triangles[f];
      const auto& pieces = h.patch.pieces[k];
      // The split face's own entries, before its first piece takes its place.
      std::vector<std::array<int32_t, 3>> own(nc);
      for (size_t c = 0; c < nc; ++c) {
        const std::vector<int32_t>& e = (*corners)[c];
        own[c] = {e[3 * f], e[3 * f + 1], e[3 * f + 2]};
      }
      for (size_t p = 0; p < pieces.size(); ++p) {
        const size_t at = p == 0 ? static_cast<size_t>(f) : cursor++;
        if (at >= tris.size() || tris[at] != pieces[p]) return false;
        for (size_t c = 0; c < nc; ++c) {
          AttributeChannel* ch = &trace->channels[c];
          std::vector<int32_t>& e = (*corners)[c];
          const auto [e0, e1, e2] = own[c];
          for (int j = 0; j < 3; ++j) {
            const int32_t v = pieces[p][j];
            int32_t entry = v == orig[0]   ? e0
                            : v == orig[1] ? e1
                            : v == orig[2] ? e2
                                           : kNone;
            if (entry == kNone) {
              const auto l = Barycentric(points[orig[0]], points[orig[1]],
                                         points[orig[2]], points[v]);
              entry = AddEntry(
                  ch, Blend(*ch, {{e0, l[0]}, {e1, l[1]}, {e2, l[2]}}));
            }
            e[3 * at + j] = entry;
          }
        }
      }
    }
    patches.push_back({cursor, h.patch.faces.size()});
    for (size_t f = cursor; f < cursor + h.patch.faces.size(); ++f) {
      if (f >= tris.size()) return false;
      in_patch[f] = true;
      for (int32_t v : tris[f]) on_rim[v] = true;
    }
    cursor += h.patch.faces.size();
  }
  if (cursor != tris.size()) return false;
  const FacesAt faces_at(tris, in_patch, on_rim);
  for (const Span& span : patches) {
    PatchInterpolator patch(points, tris, span.first, span.count);
    for (size_t c = 0; c < nc; ++c) {
      std::vector<std::pair<int32_t, int32_t>> across;
      for (const auto& [a, b] : patch.rim()) {
        int ka = 0, kb = 0;
        const int32_t f = faces_at.Across(tris, a, b, &ka, &kb);
        across.push_back(f == kNone
                             ? std::make_pair(kNone, kNone)
                             : std::make_pair((*corners)[c][3 * f + ka],
                                              (*corners)[c][3 * f + kb]));
      }
      patch.Interpolate(&trace->channels[c], across, &(*corners)[c]);
    }
  }
  // A patch with no face across its rim (the mesh's orientation disagrees
  // with it, as with repair off) has nothing to blend from: its corners get
  // the channel's mean, so that no corner is left without an entry.
  for (size_t c = 0; c < nc; ++c) {
    AttributeChannel* ch = &trace->channels[c];
    int32_t fallback = kNone;
    for (int32_t& e : (*corners)[c]) {
      if (e != kNone) continue;
      if (fallback == kNone) {
        const size_t n = ch->entries();
        std::vector<std::pair<int32_t, double>> w;
        for (size_t k = 0; k < n; ++k) w.push_back({int32_t(k), 1.0 / n});
        fallback = AddEntry(
            ch, n > 0 ? Blend(*ch, w) : std::vector<double>(ch->dims, 0.0));
      }
      e = fallback;
    }
  }
  return true;
}

// The polygon a group of triangles was cut from, from the sides they do
// not share, or empty when they do not make one simple polygon. Each
// corner comes with the triangle corner (3t + k) it takes its entries from.
std::vector<std::pair<int32_t, size_t>> Regroup(
    const std::vector<Triangle>& tris, const int32_t* group, size_t size) {
  std::unordered_map<int32_t, std::pair<int32_t, size_t>> next;  // a -> b
  std::unordered_map<uint64_t, int> uses;
  for (size_t i = 0; i < size; ++i) {
    const Triangle& t = tris[group[i]];
    for (int k = 0; k < 3; ++k) ++uses[UndirectedEdgeKey(t[k], t[(k + 1) % 3])];
  }
  for (size_t i = 0; i < size; ++i) {
    const Triangle& t = tris[group[i]];
    for (int k = 0; k < 3; ++k) {
      const int32_t a = t[k], b = t[(k + 1) % 3];
      if (uses[UndirectedEdgeKey(a, b)] != 1) continue;
      if (!next.emplace(a, std::make_pair(b, 3 * size_t(group[i]) + k))
               .second) {
        return {};  // a vertex twice on the border
      }
    }
  }
  if (next.size() != size + 2) return {};
  std::vector<std::pair<int32_t, size_t>> polygon;
  int32_t v = tris[group[0]][0];
  if (!next.count(v)) return {};
  for (size_t i = 0; i < next.size(); ++i) {
    const auto& [to, corner] = next.at(v);
    polygon.push_back({v, corner});
    v = to;
    if (!next.count(v)) return {};
  }
  if (v != polygon.front().first) return {};
  return polygon;
}

// A channel per vertex where every vertex's corners agree in value (the
// shape most formats and tools take); left per corner otherwise.
void PerVertexWhereSeamless(size_t vertices, const FaceList& faces,
                            const std::vector<int32_t>* sent_vertex,
                            AttributeChannel* ch) {
  std::vector<int32_t> of(vertices, kNone);
  if (sent_vertex != nullptr) {  // a vertex on no face keeps its own entry
    std::copy(sent_vertex->begin(), sent_vertex->end(), of.begin());
  }
  std::vector<bool> seen(vertices, false);
  const std::vector<int32_t>& corner_vertex = faces.indices();
  for (size_t c = 0; c < corner_vertex.size(); ++c) {
    int32_t& e = of[corner_vertex[c]];
    if (!seen[corner_vertex[c]]) {
      seen[corner_vertex[c]] = true;
      e = ch->indices[c];
    } else if (!SameEntry(*ch, e, ch->indices[c])) {
      return;
    }
  }
  std::vector<float> values;
  values.reserve(vertices * ch->dims);
  for (size_t v = 0; v < vertices; ++v) {
    if (of[v] == kNone) {
      values.insert(values.end(), ch->dims, 0.0f);  // on no face
    } else {
      values.insert(values.end(), ch->entry(of[v]),
                    ch->entry(of[v]) + ch->dims);
    }
  }
  ch->values = std::move(values);
  ch->indices = {};
}

}  // namespace

SoupTrace TraceSoup(const FaceList& faces,
                    std::vector<AttributeChannel> channels,
                    const RepairReport& repair, const MeshData& repaired) {
  SoupTrace trace;
  trace.triangles = repaired.triangles;
  trace.sent_vertex.assign(repaired.vertices.size(), kNone);
  for (size_t v = repair.vertex_map.empty() ? repaired.vertices.size()
                                            : repair.vertex_map.size();
       v-- > 0;) {
    trace.sent_vertex[repair.vertex_map.empty() ? v : repair.vertex_map[v]] =
        static_cast<int32_t>(v);
  }
  const int32_t* first = faces.indices().data();
  auto mapped = [&](int32_t v) {
    return repair.vertex_map.empty() ? v : repair.vertex_map[v];
  };
  for (AttributeChannel& ch : channels) {
    std::vector<int32_t> entries(3 * repaired.triangles.size(), 0);
    for (size_t t = 0; t < repaired.triangles.size(); ++t) {
      const FaceView face = faces[repair.face_origin[t]];
      for (int k = 0; k < 3; ++k) {
        size_t c = 0;
        while (c + 1 < face.size() &&
               mapped(face[c]) != repaired.triangles[t][k])
          ++c;
        const auto corner = static_cast<size_t>(face.begin() - first) + c;
        entries[3 * t + k] = ch.per_corner() ? ch.indices[corner] : face[c];
      }
    }
    trace.per_vertex.push_back(!ch.per_corner());
    ch.indices = std::move(entries);
    trace.channels.push_back(std::move(ch));
  }
  return trace;
}

PolygonSoup SoupOfFill(FillResult* fill,
                       const std::vector<int32_t>& face_origin,
                       int64_t input_faces, SoupTrace trace,
                       std::vector<std::string>* notes) {
  CornerEntries corners;
  if (!CarryThroughFill(*fill, input_faces, &trace, &corners)) {
    for (const AttributeChannel& ch : trace.channels) {
      notes->push_back("attribute '" + ch.name +
                       "' could not be carried: the filled mesh is not laid "
                       "out as the fill promised");
    }
    trace.channels.clear();
    corners.clear();
  }
  std::vector<Triangle> tris = std::move(fill->mesh.triangles);
  fill->mesh.triangles = {};
  PolygonSoup out;
  out.vertices = std::move(fill->mesh.vertices);
  fill->mesh.vertices = {};
  // Triangles grouped by the input face they come from (counting sort);
  // a group with a split face is given as its triangles.
  const auto n_in = static_cast<size_t>(input_faces);
  int32_t origins = 0;
  for (size_t t = 0; t < n_in; ++t)
    origins = std::max(origins, face_origin[t] + 1);
  std::vector<int32_t> start(origins + 1, 0);
  for (size_t t = 0; t < n_in; ++t) ++start[face_origin[t] + 1];
  for (int32_t o = 0; o < origins; ++o) start[o + 1] += start[o];
  std::vector<int32_t> group(n_in), fill_at(start.begin(), start.end() - 1);
  for (size_t t = 0; t < n_in; ++t) {
    group[fill_at[face_origin[t]]++] = static_cast<int32_t>(t);
  }
  std::vector<bool> split(n_in, false);
  for (const FilledHole& h : fill->patches) {
    for (int32_t f : h.patch.split_faces) split[f] = true;
  }
  std::vector<std::vector<int32_t>> out_entries(trace.channels.size());
  std::vector<int32_t> ids;
  auto emit = [&](const std::vector<std::pair<int32_t, size_t>>& polygon) {
    ids.clear();
    for (const auto& [v, corner] : polygon) {
      ids.push_back(v);
      for (size_t c = 0; c < out_entries.size(); ++c) {
        out_entries[c].push_back(corners[c][corner]);
      }
    }
    out.faces.push_back(ids);
  };
  auto emit_triangle = [&](size_t t) {
    emit({{tris[t][0], 3 * t},
          {tris[t][1], 3 * t + 1},
          {tris[t][2], 3 * t + 2}});
  };
  out.faces.reserve(tris.size());
  for (size_t t = 0; t < n_in; ++t) {
    const int32_t o = face_origin[t];
    const int32_t* g = group.data() + start[o];
    const auto size = static_cast<size_t>(start[o + 1] - start[o]);
    if (size == 1) {
      emit_triangle(t);
      continue;
    }
    if (static_cast<size_t>(g[0]) != t) {
      if (std::any_of(g, g + size, [&](int32_t f) { return split[f]; }))
        emit_triangle(t);
      continue;  // emitted with its group's first triangle
    }
    std::vector<std::pair<int32_t, size_t>> polygon;
    if (std::none_of(g, g + size, [&](int32_t f) { return split[f]; })) {
      polygon = Regroup(tris, g, size);
    }
    if (polygon.empty()) {
      emit_triangle(t);
      if (std::none_of(g, g + size, [&](int32_t f) { return split[f]; })) {
        for (size_t i = 1; i < size; ++i) emit_triangle(g[i]);
      }
    } else {
      emit(polygon);
    }
  }
  for (size_t t = n_in; t < tris.size(); ++t) emit_triangle(t);
  for (size_t c = 0; c < trace.channels.size(); ++c) {
    AttributeChannel& ch =
        out.attributes.emplace_back(std::move(trace.channels[c]));
    ch.indices = std::move(out_entries[c]);
    PerVertexWhereSeamless(out.vertices.size(), out.faces,
                           trace.per_vertex[c] ? &trace.sent_vertex : nullptr,
                           &ch);
  }
  return out;
}

}  // namespace dot
