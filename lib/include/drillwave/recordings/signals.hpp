#pragma once
// Robust signal tools for recordings: artefacts are flagged and masked, not modelled as physics (DESIGN.md §5).
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "drillwave/core/median.hpp"
#include "drillwave/recordings/recording.hpp"

namespace drillwave::recordings {

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

// Artefacts are rare: a channel where the filter flags more than this share of the samples is showing its motion
// (a bouncing bit's weight-on-bit impacts are as short as a glitch, and recur at every bounce), not glitches.
// Masked, such a channel's level would depend on the shape of the impacts (rec04: weight on bit 160 kN raw, 125 kN
// masked in the recording, 37 kN masked in a model whose raw level is 156 kN), so it is left whole.
inline constexpr double kMaxArtefactShare = 0.02;
// Whether a channel's flagged samples are its motion by that rule (then it is left whole).
inline bool TooManyForArtefacts(std::size_t flagged, std::size_t samples) {
  return static_cast<double>(flagged) > kMaxArtefactShare * static_cast<double>(samples);
}

struct MaskedRecording {
  Recording recording;                              // artefacts replaced by their window's median
  std::vector<std::pair<std::string, int>> masked;  // channel, samples masked (0 where left whole)
  std::vector<char> whole;                          // 1 where the channel's bursts are motion, left whole
  std::vector<std::vector<char>> flagged = {};      // per channel, 1 where a sample was masked (none where left whole)
};

// A recording with its sensor artefacts (spikes, dropouts) masked as the inspection masks them (Hampel filter over
// 0.2 s, 5 robust standard deviations and 5 % of the channel's median |value|, grown at 2), so that a glitch is not
// read as physics; a channel with more than kMaxArtefactShare of its samples flagged is left whole. Given `whole`
// (a recording's decision), another recording's channels (a model's, mapped in the same order) are masked or left
// whole as that recording's were, so that what it takes for an artefact in a motion is masked on both sides alike.
MaskedRecording MaskArtefacts(const Recording& recording, const std::vector<char>* whole = nullptr);

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

using drillwave::Median;  // core/median.hpp

// Mean and population standard deviation (NaN for an empty series).
double Mean(const std::vector<double>& v);
double Std(const std::vector<double>& v);

}  // namespace drillwave::recordings
