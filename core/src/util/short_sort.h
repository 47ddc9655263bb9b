// SPDX-License-Identifier: AGPL-3.0-or-later
// Sorting the many short lists of per-vertex and per-edge records.
#ifndef DOT_CORE_UTIL_SHORT_SORT_H_
#define DOT_CORE_UTIL_SHORT_SORT_H_

#include <algorithm>
#include <utility>

namespace dot {

// Sorts [first, last) by `less`. Most lists hold a handful of elements, for
// which insertion sort is fastest; cospherical configurations make long
// ones, which get std::sort. Not stable: meant for keys without ties.
template <typename It, typename Less>
void SortShortList(It first, It last, Less less) {
  if (last - first > 16) {
    std::sort(first, last, less);
    return;
  }
  for (It i = first; i != last; ++i) {
    auto value = std::move(*i);
    It j = i;
    for (; j != first && less(value, *(j - 1)); --j) *j = std::move(*(j - 1));
    *j = std::move(value);
  }
}

}  // namespace dot

#endif  // DOT_CORE_UTIL_SHORT_SORT_H_
