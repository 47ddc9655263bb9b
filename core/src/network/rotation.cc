// SPDX-License-Identifier: AGPL-3.0-or-later
#include "network/rotation.h"

#include <algorithm>
#include <map>
#include <tuple>
#include <unordered_map>

#include "network/seam.h"

namespace dot {

// A position per junction on the stack: linear in the face.
std::vector<std::vector<CurveUse>> SplitAtRepeats(
    const NetworkGraph& g, const std::vector<CurveUse>& face) {
  std::vector<std::vector<CurveUse>> out;
  std::vector<CurveUse> stack;
  std::vector<int32_t> starts;  // start junction of each use on the stack
  std::unordered_map<int32_t, size_t> at;  // junction -> its stack position
  for (const CurveUse& u : face) {
    const auto& vs = g.curves[u.curve].vertices;
    const int32_t from = u.reversed ? vs.back() : vs.front();
    const int32_t to = u.reversed ? vs.front() : vs.back();
    at.emplace(from, stack.size());
    stack.push_back(u);
    starts.push_back(from);
    // Close a loop as soon as the walk returns to a junction on the stack.
    const auto it = at.find(to);
    if (it == at.end()) continue;
    const size_t k = it->second;
    out.emplace_back(stack.begin() + static_cast<long>(k), stack.end());
    for (size_t j = k; j < starts.size(); ++j) at.erase(starts[j]);
    stack.resize(k);
    starts.resize(k);
  }
  return out;
}

void Rotation::SetRing(int32_t r) {
  const auto& ring = rings[r];
  for (size_t k = 0; k < ring.size(); ++k) {
    before[ring[k]] = ring[(k + ring.size() - 1) % ring.size()];
  }
}

void Rotation::Flip(int32_t r) {
  if (!sign.empty()) sign[r] = static_cast<signed char>(-sign[r]);
  std::reverse(rings[r].begin(), rings[r].end());
  SetRing(r);
}

void FaceCount::Add(const std::vector<CurveUse>& face) {
  ++faces;
  if (!RunsACurveTwice(face)) {
    ++simple;
  } else if (IsSeamLoop(face)) {
    ++seams;
  }
}

bool MoreSimple(const FaceCount& a, const FaceCount& b) {
  return std::tie(a.simple, a.faces) > std::tie(b.simple, b.faces);
}

bool MoreSurfaceable(const FaceCount& a, const FaceCount& b) {
  return a.faces >= b.faces && a.simple + a.seams > b.simple + b.seams;
}

namespace {

// The face that leaves along dart `start`, each dart marked in `seen`;
// false when the ticker says stop (polled per dart: faces can be long).
template <typename Seen>
bool TraceFace(const Rotation& rot, int32_t start, Seen* seen,
               std::vector<CurveUse>* face, RunTicker* ticker) {
  face->clear();
  int32_t d = start;
  do {
    if (ticker != nullptr && !ticker->Tick()) return false;
    (*seen)[d] = 1;
    face->push_back({d / 2, (d & 1) == 1});
    d = rot.Next(d);
  } while (d != start);
  return true;
}

// The faces through ring r's junction, counted; *stop when the ticker
// says so.
FaceCount FacesAt(const Rotation& rot, int32_t r, RunTicker* ticker,
                  bool* stop) {
  std::vector<std::vector<CurveUse>> faces;
  FaceCount count;
  if (!FacesThrough(rot, {r}, &faces, ticker)) {
    *stop = true;
    return count;
  }
  for (const auto& face : faces) count.Add(face);
  return count;
}

}  // namespace

FaceCount AllFaces(const Rotation& rot) {
  std::vector<char> seen(rot.before.size(), 0);
  FaceCount count;
  std::vector<CurveUse> face;
  for (const auto& ring : rot.rings) {
    for (int32_t start : ring) {
      if (seen[start]) continue;
      TraceFace(rot, start, &seen, &face, nullptr);
      count.Add(face);
    }
  }
  return count;
}

bool FacesThrough(const Rotation& rot, const std::vector<int32_t>& rings,
                  std::vector<std::vector<CurveUse>>* faces,
                  RunTicker* ticker) {
  faces->clear();
  std::map<int32_t, char> seen;
  std::vector<CurveUse> face;
  for (int32_t r : rings) {
    for (int32_t a : rot.rings[r]) {
      if (seen.count(a ^ 1)) continue;
      if (!TraceFace(rot, a ^ 1, &seen, &face, ticker)) return false;
      faces->push_back(face);
    }
  }
  return true;
}

Status ImproveSigns(Rotation* rot, const std::vector<int32_t>& order,
                    const std::vector<std::pair<size_t, size_t>>& subtrees,
                    bool (*better)(const FaceCount&, const FaceCount&),
                    RunTicker* ticker) {
  bool stop = false;
  for (int pass = 0; pass < 8; ++pass) {
    bool improved = false;
    for (size_t r = 0; r < rot->rings.size(); ++r) {
      if (rot->rings[r].size() < 3) continue;
      const auto before = FacesAt(*rot, static_cast<int32_t>(r), ticker, &stop);
      rot->Flip(static_cast<int32_t>(r));
      const auto after = FacesAt(*rot, static_cast<int32_t>(r), ticker, &stop);
      if (stop) return ticker->status();
      if (better(after, before)) {
        improved = true;
      } else {
        rot->Flip(static_cast<int32_t>(r));
      }
      // Where four or more curves meet, their order is a guess too: swap
      // neighbours.
      auto& ring = rot->rings[r];
      for (size_t k = 0; ring.size() >= 4 && k < ring.size(); ++k) {
        const size_t l = (k + 1) % ring.size();
        const auto old_score =
            FacesAt(*rot, static_cast<int32_t>(r), ticker, &stop);
        std::swap(ring[k], ring[l]);
        rot->SetRing(static_cast<int32_t>(r));
        const auto new_score =
            FacesAt(*rot, static_cast<int32_t>(r), ticker, &stop);
        if (stop) return ticker->status();
        if (better(new_score, old_score)) {
          improved = true;
        } else {
          std::swap(ring[k], ring[l]);
          rot->SetRing(static_cast<int32_t>(r));
        }
      }
    }
    if (!subtrees.empty()) {
      auto score = AllFaces(*rot);
      for (const auto& [first, last] : subtrees) {
        if (!ticker->Poll()) return ticker->status();
        for (size_t k = first; k < last; ++k) rot->Flip(order[k]);
        const auto flipped = AllFaces(*rot);
        if (better(flipped, score)) {
          score = flipped;
          improved = true;
        } else {
          for (size_t k = first; k < last; ++k) rot->Flip(order[k]);
        }
      }
    }
    if (!improved) break;
  }
  return OkStatus();
}

}  // namespace dot
