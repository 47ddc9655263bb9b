// SPDX-License-Identifier: AGPL-3.0-or-later
// Entries of an attribute channel as the fill makes new ones: compared by
// value, blended, and added (normals renormalized, colours clamped).
#ifndef DOT_CORE_FILL_ATTRIBUTE_ENTRIES_H_
#define DOT_CORE_FILL_ATTRIBUTE_ENTRIES_H_

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "dot/mesh.h"

namespace dot {

// Per corner of a triangle list, the entry of each channel:
// [channel][3 * triangle + k].
using CornerEntries = std::vector<std::vector<int32_t>>;

// No entry (yet): a corner the fill has not given one.
inline constexpr int32_t kNoEntry = -1;

inline bool SameEntry(const AttributeChannel& ch, int32_t a, int32_t b) {
  return a == b || std::equal(ch.entry(a), ch.entry(a) + ch.dims, ch.entry(b));
}

// Appends an entry and returns its index; a "normal" renormalized. (A
// colour is not clamped to [0, 1]: blends stay within their inputs' range,
// and a client's colours may be on a 0..255 scale.)
inline int32_t AddEntry(AttributeChannel* ch, std::vector<double> value) {
  if (ch->name == "normal" && value.size() == 3) {
    const double n = std::sqrt(value[0] * value[0] + value[1] * value[1] +
                               value[2] * value[2]);
    if (n > 0) {
      for (double& x : value) x /= n;
    }
  }
  const auto e = static_cast<int32_t>(ch->entries());
  for (double x : value) ch->values.push_back(static_cast<float>(x));
  return e;
}

// A weighted sum of entries.
inline std::vector<double> Blend(
    const AttributeChannel& ch,
    const std::vector<std::pair<int32_t, double>>& w) {
  std::vector<double> v(ch.dims, 0.0);
  for (const auto& [e, weight] : w) {
    for (int d = 0; d < ch.dims; ++d) v[d] += weight * ch.entry(e)[d];
  }
  return v;
}

}  // namespace dot

#endif  // DOT_CORE_FILL_ATTRIBUTE_ENTRIES_H_
