// SPDX-License-Identifier: AGPL-3.0-or-later
#include "network/sign_cost.h"

#include <optional>
#include <set>

namespace dot {
namespace {

// Faces counted as ImproveSigns counts them, and what they cost as
// patches.
struct Priced {
  FaceCount count;
  double cost = 0;
};

std::optional<Priced> Price(const NetworkGraph& graph,
                            const std::vector<std::vector<CurveUse>>& faces,
                            FaceCosts* costs) {
  Priced p;
  for (const auto& face : faces) {
    p.count.Add(face);
    const std::optional<double> c = costs->Cost(face);
    if (!c) return std::nullopt;
    p.cost += *c;
  }
  return p;
}

bool Cheaper(const Priced& a, const Priced& b) {
  if (MoreSimple(a.count, b.count)) return true;
  if (MoreSimple(b.count, a.count)) return false;
  return a.cost < b.cost * (1 - 1e-9);
}

}  // namespace

Status ImproveByCost(Rotation* rot, const NetworkGraph& graph,
                     const std::vector<CurveRings>& curves,
                     const std::vector<int32_t>& order,
                     const std::vector<std::pair<size_t, size_t>>& subtrees,
                     FaceCosts* costs, RunTicker* ticker) {
  std::vector<std::vector<int32_t>> curves_at(rot->rings.size());
  for (size_t c = 0; c < curves.size(); ++c) {
    curves_at[curves[c].from].push_back(static_cast<int32_t>(c));
    curves_at[curves[c].to].push_back(static_cast<int32_t>(c));
  }
  bool out_of_points = false;
  std::vector<std::vector<CurveUse>> faces;
  // True when the move was kept.
  auto try_flip = [&](const std::vector<int32_t>& move) {
    // The votes of the curves the move cuts (one end flipped) turn over.
    const std::set<int32_t> in(move.begin(), move.end());
    int lost = 0;
    for (int32_t r : move) {
      for (int32_t k : curves_at[r]) {
        const CurveRings& c = curves[k];
        if (in.count(c.from) == in.count(c.to)) continue;
        lost += c.vote * rot->sign[c.from] * rot->sign[c.to];
      }
    }
    if (lost > kVotesOverruled) return false;
    if (!FacesThrough(*rot, move, &faces, ticker)) return false;
    const std::optional<Priced> before = Price(graph, faces, costs);
    for (int32_t r : move) rot->Flip(r);
    std::optional<Priced> after;
    if (before && FacesThrough(*rot, move, &faces, ticker)) {
      after = Price(graph, faces, costs);
    }
    if (before && after && Cheaper(*after, *before)) return true;
    for (int32_t r : move) rot->Flip(r);
    out_of_points |= costs->spent();
    return false;
  };
  auto go_on = [&] { return !out_of_points && ticker->Poll(); };
  for (int pass = 0; pass < 4; ++pass) {
    bool improved = false;
    for (size_t r = 0; r < rot->rings.size() && go_on(); ++r) {
      if (rot->rings[r].size() < 3) continue;
      improved |= try_flip({static_cast<int32_t>(r)});
    }
    for (size_t k = 0; k < curves.size() && go_on(); ++k) {
      const CurveRings& c = curves[k];
      if (c.from == c.to || rot->rings[c.from].size() < 3 ||
          rot->rings[c.to].size() < 3) {
        continue;
      }
      improved |= try_flip({c.from, c.to});
    }
    for (size_t k = 0; k < subtrees.size() && go_on(); ++k) {
      const auto [first, last] = subtrees[k];
      if (last - first < 3) continue;  // done as junctions and curves
      improved |= try_flip({order.begin() + static_cast<long>(first),
                            order.begin() + static_cast<long>(last)});
    }
    if (!improved || !go_on()) break;
  }
  return ticker->Poll() ? OkStatus() : ticker->status();
}

}  // namespace dot
