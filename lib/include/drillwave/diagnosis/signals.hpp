#pragma once
// Robust signal tools for recordings: artefacts are flagged and masked, not modelled as physics (DESIGN.md §5).
#include <vector>

namespace drillwave::diagnosis {

struct HampelResult {
  std::vector<double> cleaned;  // flagged samples replaced by their window median
  std::vector<char> flagged;    // 1 where a sample was replaced
};

// Hampel filter: x_i is an outlier when it is more than `threshold` robust standard deviations (1.4826 MAD of the
// window of 2 half_window + 1 samples around it) and more than `min_deviation` away from the window's median. The
// floor keeps a flat or quantised stretch (MAD = 0) from flagging its every step. A flagged run then grows into its
// neighbours while they deviate by more than grow_threshold robust standard deviations (and the floor): a spike
// with ramped flanks (an encoder glitch, a filtered dropout) is masked whole, not just its tip.
HampelResult HampelFilter(const std::vector<double>& x, int half_window, double threshold, double min_deviation,
                          double grow_threshold);

struct Interval {
  double begin_s, end_s;
  double duration() const { return end_s - begin_s; }
};

// Runs of true samples as time intervals [first sample, last sample]; runs separated by at most `merge_gap`
// samples are joined, and runs shorter than min_duration_s are dropped.
std::vector<Interval> Runs(const std::vector<double>& time_s, const std::vector<char>& on, int merge_gap,
                           double min_duration_s);

// Pearson correlation of two equally long series (NaN if either is constant).
double Correlation(const std::vector<double>& a, const std::vector<double>& b);

double Median(std::vector<double> v);

// Mean and population standard deviation (NaN for an empty series).
double Mean(const std::vector<double>& v);
double Std(const std::vector<double>& v);

}  // namespace drillwave::diagnosis
