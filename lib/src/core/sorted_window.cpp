#include "drillwave/core/sorted_window.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace drillwave {

void SortedWindow::Insert(double v) {
  if (std::isnan(v)) ++nans_;
  if (std::isinf(v)) ++infinities_;
  maybe_unordered_ |= nans_ > 0;
  sorted_.insert(std::upper_bound(sorted_.begin(), sorted_.end(), v), v);
  RecheckOrder();
}

void SortedWindow::Erase(double v) {
  auto leaving = std::lower_bound(sorted_.begin(), sorted_.end(), v);
  if (leaving == sorted_.end() || !(*leaving == v))  // a NaN is found by no comparison
    leaving = std::find_if(sorted_.begin(), sorted_.end(), [](double w) { return std::isnan(w); });
  if (leaving == sorted_.end()) return;
  if (std::isnan(*leaving)) --nans_;
  if (std::isinf(*leaving)) --infinities_;
  sorted_.erase(leaving);
  RecheckOrder();
}

// Once the last NaN has left, whether what was inserted beside it is in order (O(n), only until it is).
void SortedWindow::RecheckOrder() {
  if (maybe_unordered_ && nans_ == 0) maybe_unordered_ = !std::is_sorted(sorted_.begin(), sorted_.end());
}

double SortedWindow::Median() const {
  const std::size_t n = sorted_.size(), mid = n / 2;
  return n % 2 == 1 ? sorted_[mid] : 0.5 * (sorted_[mid - 1] + sorted_[mid]);
}

std::pair<double, double> SortedWindow::MedianAndMad() const {
  const double median = Median();
  const bool ordered_and_finite = nans_ == 0 && infinities_ == 0 && !maybe_unordered_;
  return {median, ordered_and_finite ? MadBySelection(median) : MadByMerge(median)};
}

// The deviations below the median, median - sorted[mid - 1 - t], and above it, sorted[mid + t] - median, are each
// sorted (rounding is monotone), and the MAD is the middle of their union: its elements mid - 1 and mid (from 0).
// The `mid` smallest are some from below and the rest from above; how many from below is found by bisection, since
// taking one more from below is right exactly while below's next one is smaller than above's last one taken.
double SortedWindow::MadBySelection(double median) const {
  const std::size_t n = sorted_.size(), mid = n / 2, below = mid, above = n - mid;
  const auto down = [&](std::size_t t) { return median - sorted_[mid - 1 - t]; };
  const auto up = [&](std::size_t t) { return sorted_[mid + t] - median; };
  std::size_t lo = 0, hi = below;  // from below: between these; the rest (mid - taken <= above) from above
  while (lo < hi) {
    const std::size_t from_below = lo + (hi - lo) / 2;
    if (down(from_below) < up(mid - from_below - 1)) lo = from_below + 1;
    else hi = from_below;
  }
  const std::size_t from_below = lo, from_above = mid - lo;
  constexpr double kNone = std::numeric_limits<double>::infinity();
  const double next =  // element mid: the smaller of the two runs' next ones
      std::min(from_below < below ? down(from_below) : kNone, from_above < above ? up(from_above) : kNone);
  if (n % 2 == 1) return next;
  const double last =  // element mid - 1: the larger of the two runs' last ones taken
      std::max(from_below > 0 ? down(from_below - 1) : -kNone, from_above > 0 ? up(from_above - 1) : -kNone);
  return 0.5 * (last + next);
}

// The merge of the two runs of deviations up to their middle, in the order the comparisons give (a NaN deviation
// loses every comparison and is taken from above).
double SortedWindow::MadByMerge(double median) const {
  const std::size_t n = sorted_.size(), mid = n / 2;
  long below = static_cast<long>(mid) - 1, above = static_cast<long>(mid);
  double previous = 0, current = 0;
  for (std::size_t taken = 0; taken <= mid; ++taken) {
    const double down = below >= 0 ? median - sorted_[below] : std::numeric_limits<double>::infinity();
    const double up = above < static_cast<long>(n) ? sorted_[above] - median : std::numeric_limits<double>::infinity();
    previous = current;
    if (down <= up) current = down, --below;
    else current = up, ++above;
  }
  return n % 2 == 1 ? current : 0.5 * (previous + current);
}

}  // namespace drillwave
