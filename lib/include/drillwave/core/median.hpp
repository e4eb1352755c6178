#pragma once
// The median of a series: the middle value, or the mean of the two middle values for an even count; NaN for an empty
// one. In O(n) (nth_element), by value so that the caller's order is kept.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace drillwave {

inline double Median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  const auto mid = static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  if (v.size() % 2 == 1) return v[static_cast<std::size_t>(mid)];
  return 0.5 * (v[static_cast<std::size_t>(mid)] + *std::max_element(v.begin(), v.begin() + mid));
}

}  // namespace drillwave
