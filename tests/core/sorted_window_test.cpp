// core/sorted_window: the sliding median and MAD equal, to the last bit, a sort of each window and the merge the
// Hampel filter used before (issue 40), on random data with ties, NaN and infinities. Inserting and erasing are the
// filter's own code moved here unchanged.
#include "drillwave/core/sorted_window.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/core/median.hpp"

namespace drillwave {
namespace {

// The straightforward definition: the median of the window, the median of |x - median| (finite windows).
std::pair<double, double> SortedCopyMedianAndMad(const std::vector<double>& x, int lo, int hi) {
  const std::vector<double> window(x.begin() + lo, x.begin() + hi + 1);
  const double median = Median(window);
  std::vector<double> deviation;
  for (const double v : window) deviation.push_back(std::abs(v - median));
  return {median, Median(deviation)};
}

bool SameBits(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

// Slides a window over `x` as the Hampel filter does ([i - half, i + half], cut at the ends) and compares, at every
// sample, the selection with the merge the filter had before; with `finite`, with a sorted copy of the window too.
void ExpectSameAsBefore(const std::vector<double>& x, int half, bool finite) {
  SortedWindow window;
  const int n = static_cast<int>(x.size());
  int window_lo = 0, window_hi = -1;
  for (int i = 0; i < n; ++i) {
    const int lo = std::max(0, i - half), hi = std::min(n - 1, i + half);
    for (; window_lo < lo; ++window_lo) window.Erase(x[window_lo]);
    for (; window_hi < hi; ++window_hi) window.Insert(x[window_hi + 1]);
    // (With NaN, a value out of order may not be found when it leaves, as before: the window then keeps it.)
    if (finite) {
      ASSERT_EQ(window.size(), static_cast<std::size_t>(hi - lo + 1));
    }
    const auto [median, mad] = window.MedianAndMad();
    const auto [median_before, mad_before] = window.MedianAndMadByMerge();
    ASSERT_TRUE(SameBits(median, median_before)) << "sample " << i << ", half window " << half;
    ASSERT_TRUE(SameBits(mad, mad_before)) << "sample " << i << ", half window " << half << ": " << mad << " vs "
                                           << mad_before;
    if (!finite) continue;
    const auto [median_sorted, mad_sorted] = SortedCopyMedianAndMad(x, lo, hi);
    ASSERT_EQ(median, median_sorted) << "sample " << i;
    ASSERT_EQ(mad, mad_sorted) << "sample " << i;
  }
}

// A noisy signal quantised to `step` (so that windows hold ties, and flat stretches a MAD of 0), with spikes.
std::vector<double> QuantisedSignal(std::mt19937_64& random, int n, double step) {
  std::normal_distribution<double> noise(0, 1);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<double> x(n);
  for (int i = 0; i < n; ++i) {
    const double level = i % 400 < 100 ? 0 : 10 * std::sin(0.01 * i) + noise(random);
    x[i] = step * std::round(level / step) + (unit(random) < 0.01 ? 50 * noise(random) : 0);
  }
  return x;
}

TEST(SortedWindow, MedianAndMadAreTheSortedWindowsOnRandomDataWithTies) {
  std::mt19937_64 random(40);
  for (const double step : {1e-9, 0.25, 1.0, 5.0})
    for (const int half : {1, 2, 3, 10, 100}) ExpectSameAsBefore(QuantisedSignal(random, 3000, step), half, true);
  ExpectSameAsBefore(std::vector<double>(500, 3.5), 7, true);  // all ties: MAD 0
  ExpectSameAsBefore({-0.0, 0.0, -0.0, 1e-300, -1e300, 1e300, 0.0}, 2, true);
}

TEST(SortedWindow, NaNAndInfinitiesGiveWhatTheMergeGave) {
  // A NaN has no place in a sorted vector, so values inserted beside it may land out of order, and an infinite
  // value's deviation may be NaN: there the merge's result is kept, bit for bit (also after the NaN has left).
  std::mt19937_64 random(41);
  std::uniform_real_distribution<double> unit(0, 1);
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  for (const int half : {1, 2, 5, 20}) {
    std::vector<double> x = QuantisedSignal(random, 3000, 0.5);
    for (double& v : x) {
      const double u = unit(random);
      if (u < 0.02) v = nan;
      else if (u < 0.03) v = u < 0.025 ? inf : -inf;
    }
    for (int i = 1000; i < 1010; ++i) x[i] = nan;  // a window of NaN only
    ExpectSameAsBefore(x, half, false);
  }
  // Infinite medians: deviations inf - inf are NaN.
  ExpectSameAsBefore({inf, inf, 1, inf, 2, inf, inf, 3, -inf, -inf, 4, -inf, 5, inf, inf, inf, 6, 7}, 3, false);
}

TEST(SortedWindow, ErasingAValueNotInTheWindowChangesNothing) {
  SortedWindow window;
  for (const double v : {3.0, 1.0, 2.0}) window.Insert(v);
  window.Erase(7.0);
  EXPECT_EQ(window.size(), 3u);
  EXPECT_EQ(window.MedianAndMad(), std::make_pair(2.0, 1.0));
  window.Erase(1.0);
  EXPECT_EQ(window.MedianAndMad(), std::make_pair(2.5, 0.5));
}

}  // namespace
}  // namespace drillwave
