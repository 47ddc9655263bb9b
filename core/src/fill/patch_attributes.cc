// SPDX-License-Identifier: AGPL-3.0-or-later
#include "fill/patch_attributes.h"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <unordered_map>

#include "mesh/edge_index.h"

namespace dot {
namespace {

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
  // edge the entries of its two ends in the face across (kNoEntry: no face).
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
      return a == kNoEntry || b == kNoEntry || !SameEntry(ch, a, b);
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
      if (ea != kNoEntry) arc.push_back({local_.at(rim_[i].first), ea});
      if (eb != kNoEntry) arc.push_back({local_.at(rim_[i].second), eb});
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
    // More arcs than a texture's seams make (values that disagree all
    // along the rim) are blended as one: a field per arc costs a solve.
    constexpr size_t kMaxArcs = 32;
    if (arcs.size() > kMaxArcs) {
      std::vector<std::pair<int, int32_t>> all;
      for (const auto& arc : arcs)
        all.insert(all.end(), arc.begin(), arc.end());
      arcs.assign(1, std::move(all));
    }
    // A vertex named twice in an arc keeps its first entry; arcs without
    // any value are dropped.
    std::vector<char> named;
    for (auto& arc : arcs) {
      std::vector<std::pair<int, int32_t>> unique;
      for (const auto& p : arc) {
        if (static_cast<size_t>(p.first) >= named.size())
          named.resize(p.first + 1, 0);
        if (!named[p.first]) unique.push_back(p);
        named[p.first] = 1;
      }
      for (const auto& p : unique) named[p.first] = 0;
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
    std::vector<int32_t> field(nv, kNoEntry);
    for (const auto& [v, e] : arc) field[v] = e;
    std::vector<int> unknown(nv, -1);
    int m = 0;
    for (size_t v = 0; v < nv; ++v) {
      if (field[v] == kNoEntry) unknown[v] = m++;
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
    std::vector<int32_t> field(vertices_.size(), kNoEntry);
    for (const auto& [v, e] : arc) field[v] = e;
    for (size_t v = 0; v < field.size(); ++v) {
      if (field[v] == kNoEntry) {
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
  // kNoEntry, and the corners of a and b in it.
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
    return kNoEntry;
  }

 private:
  std::vector<std::pair<int32_t, int32_t>> pairs_;
};

}  // namespace

void InterpolatePatches(const std::vector<Vec3>& points,
                        const std::vector<Triangle>& faces,
                        const std::vector<std::pair<size_t, size_t>>& patches,
                        std::vector<AttributeChannel>* channels,
                        CornerEntries* corners) {
  std::vector<bool> in_patch(faces.size(), false);
  std::vector<bool> on_rim(points.size(), false);
  for (const auto& [first, count] : patches) {
    for (size_t f = first; f < first + count; ++f) {
      in_patch[f] = true;
      for (int32_t v : faces[f]) on_rim[v] = true;
    }
  }
  const FacesAt faces_at(faces, in_patch, on_rim);
  for (const auto& [first, count] : patches) {
    PatchInterpolator patch(points, faces, first, count);
    for (size_t c = 0; c < channels->size(); ++c) {
      std::vector<std::pair<int32_t, int32_t>> across;
      for (const auto& [a, b] : patch.rim()) {
        int ka = 0, kb = 0;
        const int32_t f = faces_at.Across(faces, a, b, &ka, &kb);
        across.push_back(f == kNoEntry
                             ? std::make_pair(kNoEntry, kNoEntry)
                             : std::make_pair((*corners)[c][3 * f + ka],
                                              (*corners)[c][3 * f + kb]));
      }
      patch.Interpolate(&(*channels)[c], across, &(*corners)[c]);
    }
  }
}

}  // namespace dot
