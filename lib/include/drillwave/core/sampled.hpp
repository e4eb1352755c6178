#pragma once
// A signal sampled at increasing times, read between its samples.
#include <algorithm>
#include <vector>

namespace drillwave {

// Linear interpolation of (t, y) at time s; held at the first value before the start and the last after the end.
// Exact at a sample time (the weight there is 0), so a shift by whole samples reproduces the samples.
inline double InterpolateSampled(const std::vector<double>& t, const std::vector<double>& y, double s) {
  if (s <= t.front()) return y.front();
  if (s >= t.back()) return y.back();
  const auto k = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), s) - t.begin());
  const double w = (s - t[k - 1]) / (t[k] - t[k - 1]);
  return y[k - 1] + w * (y[k] - y[k - 1]);
}

}  // namespace drillwave
