#pragma once
// A window of samples kept sorted as it slides over a series (one value leaves, one enters per step), with the
// window's median and median absolute deviation (MAD): what a Hampel filter needs at every sample. Sorting a copy of
// the window per sample costs O(n log n); the merge of the deviations below and above the median, O(n); here the
// MAD is selected from those two sorted runs in O(log n), with the same result to the last bit.
#include <cstddef>
#include <utility>
#include <vector>

namespace drillwave {

class SortedWindow {
 public:
  // Adds `v`; a NaN goes to the end (no comparison places it).
  void Insert(double v);
  // Removes one value equal to `v` (for a NaN, the first NaN); nothing if there is none.
  void Erase(double v);
  std::size_t size() const { return sorted_.size(); }

  // The median (the middle value, or the mean of the two middle values) and the median of the absolute deviations
  // from it. Undefined for an empty window. A NaN has no place in the order: while one is in the window, values
  // inserted may land out of order, and then (or with an infinite value, whose deviation may be NaN) the result
  // is the merge's, in the order its comparisons give, as the Hampel filter always had it.
  std::pair<double, double> MedianAndMad() const;
  // The same by merging the deviations below and above the median up to their middle, O(n): how the Hampel filter
  // had it before (issue 40), and the reference MedianAndMad is tested against.
  std::pair<double, double> MedianAndMadByMerge() const { return {Median(), MadByMerge(Median())}; }

 private:
  double Median() const;
  double MadBySelection(double median) const;
  double MadByMerge(double median) const;
  void RecheckOrder();

  std::vector<double> sorted_;
  std::size_t nans_ = 0, infinities_ = 0;
  bool maybe_unordered_ = false;  // a value was inserted while a NaN was in the window, and no check since
};

}  // namespace drillwave
