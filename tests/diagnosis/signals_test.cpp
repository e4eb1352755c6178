// Robust signal tools: the Hampel filter masks spikes (with their ramped flanks) and leaves an honest noisy signal
// alone; runs of flags become intervals.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "drillwave/core/constants.hpp"
#include "drillwave/diagnosis/recording.hpp"

namespace drillwave::diagnosis {
namespace {

TEST(Hampel, MasksRampedSpikesAndNothingElse) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  const int n = 20000;
  std::vector<double> x(n), truth(n);
  for (int i = 0; i < n; ++i) truth[i] = x[i] = 80 + 40 * std::sin(2 * kPi * i / 400.0) + noise(rng);
  // Ten glitches: a dip to -250 with 4-sample flanks on each side (like the rig's encoder artefacts).
  std::vector<char> injected(n, 0);
  for (int g = 0; g < 10; ++g) {
    const int c = 1000 + 1800 * g;
    for (int k = -6; k <= 6; ++k) {
      const double depth = std::abs(k) <= 2 ? 1.0 : 1.0 - (std::abs(k) - 2) / 5.0;
      x[c + k] = truth[c + k] + depth * (-250 - truth[c + k]);
      injected[c + k] = std::abs(k) <= 5;
    }
  }
  const HampelResult h = HampelFilter(x, 100, 5, 4.0, 2);
  std::vector<char> near(n, 0);  // within 6 samples of a glitch
  for (int g = 0; g < 10; ++g)
    for (int k = -6; k <= 6; ++k) near[1000 + 1800 * g + k] = 1;
  int missed = 0, false_flags = 0;
  double worst_centre = 0;
  for (int i = 0; i < n; ++i) {
    if (injected[i] && !h.flagged[i]) ++missed;
    if (!near[i] && h.flagged[i]) ++false_flags;
  }
  for (int g = 0; g < 10; ++g) {
    const int c = 1000 + 1800 * g;
    worst_centre = std::max(worst_centre, std::abs(h.cleaned[c] - truth[c]));
  }
  std::printf("[ measured ] Hampel: %d of 110 glitch samples missed, %d false flags in %d clean samples, worst "
              "centre %.1f from the truth\n", missed, false_flags, n - 130, worst_centre);
  EXPECT_EQ(missed, 0);
  EXPECT_LT(false_flags, n / 1000);
  EXPECT_LT(worst_centre, 50.0);  // instead of 330 below it: the window median of a sine, not its value
  const auto bursts = Runs(std::vector<double>(), std::vector<char>(), 0, 0.0);
  EXPECT_TRUE(bursts.empty());
}

// 100 Hz, 60 s: a weight on bit of 150 kN with noise, and `spikes` impacts of +400 kN lasting 30 ms, evenly spread.
Recording WithImpacts(int spikes, unsigned seed) {
  Recording r;
  r.source = "synthetic";
  r.sample_interval_s = 0.01;
  r.names = {"wob_kN"};
  r.channels.resize(1);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  const int n = 6000;
  for (int i = 0; i < n; ++i) r.time_s.push_back(0.01 * i), r.channels[0].push_back(150 + noise(rng));
  for (int s = 0; s < spikes; ++s)
    for (int k = 0; k < 3; ++k) r.channels[0][50 + s * (n - 100) / spikes + k] += 400;
  return r;
}

// The filter keeps its window sorted as it slides; its medians and MADs must be those of each window computed afresh
// (odd windows inside, even ones at the ends, repeated values from a quantized signal), so the same samples are masked.
TEST(Hampel, TheSlidingWindowGivesTheMediansOfEachWindowAfresh) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> x(3000);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = std::round(4 * (std::sin(0.01 * i) + noise(rng))) / 4;
  for (int spike : {5, 700, 2995}) x[spike] = -40;
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
  };
  const int half = 10;
  const double threshold = 3, floor = 0.1;
  std::vector<char> expected(x.size(), 0);
  for (int i = 0; i < static_cast<int>(x.size()); ++i) {
    const int lo = std::max(0, i - half), hi = std::min(static_cast<int>(x.size()) - 1, i + half);
    const std::vector<double> w(x.begin() + lo, x.begin() + hi + 1);
    const double m = median(w);
    std::vector<double> deviation;
    for (double v : w) deviation.push_back(std::abs(v - m));
    const double d = std::abs(x[i] - m);
    expected[i] = d > threshold * 1.4826 * median(deviation) && d > floor;
  }
  // A grow threshold above the detection threshold grows nothing: the flags are the detections alone.
  const HampelResult h = HampelFilter(x, half, threshold, floor, 1e9);
  EXPECT_EQ(h.flagged, expected);
  for (int spike : {5, 700, 2995}) EXPECT_TRUE(h.flagged[spike]) << spike;
}

TEST(MaskArtefacts, AFewGlitchesAreMaskedAndABouncesImpactsLeftWhole) {
  // Ten impacts in a minute: glitches (0.5 % of the samples), masked.
  const MaskedRecording glitches = MaskArtefacts(WithImpacts(10, 1));
  EXPECT_EQ(glitches.whole, std::vector<char>{0});
  EXPECT_EQ(glitches.masked.front().second, 30);
  EXPECT_LT(*std::max_element(glitches.recording.channels[0].begin(), glitches.recording.channels[0].end()), 160);
  // Four impacts a second (a bouncing bit): 12 % of the samples, motion, left whole and counted as none masked.
  const Recording bounce = WithImpacts(240, 2);
  const MaskedRecording motion = MaskArtefacts(bounce);
  EXPECT_EQ(motion.whole, std::vector<char>{1});
  EXPECT_EQ(motion.masked.front().second, 0);
  EXPECT_EQ(motion.recording.channels[0], bounce.channels[0]);
  // Another recording (a model's) follows the first one's decision, whatever its own share.
  const MaskedRecording follows = MaskArtefacts(WithImpacts(10, 3), &motion.whole);
  EXPECT_EQ(follows.whole, std::vector<char>{1});
  EXPECT_EQ(follows.masked.front().second, 0);
  const MaskedRecording masked_like = MaskArtefacts(WithImpacts(240, 4), &glitches.whole);
  EXPECT_EQ(masked_like.whole, std::vector<char>{0});
  EXPECT_GT(masked_like.masked.front().second, 600);
  const std::vector<char> wrong_size{0, 0};
  EXPECT_THROW(MaskArtefacts(bounce, &wrong_size), std::invalid_argument);
}

TEST(Signals, RunsMergeAndFilter) {
  const std::vector<double> t{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  const std::vector<char> on{1, 1, 0, 1, 0, 0, 0, 1, 0, 0};
  auto runs = Runs(t, on, 1, 0.0);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].begin_s, 0);
  EXPECT_EQ(runs[0].end_s, 3);
  EXPECT_EQ(runs[1].begin_s, 7);
  runs = Runs(t, on, 0, 0.5);
  ASSERT_EQ(runs.size(), 1u);  // only [0, 1] lasts 0.5 s or more
  EXPECT_DOUBLE_EQ(Correlation({1, 2, 3, 4}, {3, 5, 7, 9}), 1.0);
  EXPECT_DOUBLE_EQ(Correlation({1, 2, 3, 4}, {4, 3, 2, 1}), -1.0);
  EXPECT_TRUE(std::isnan(Correlation({1, 1, 1}, {1, 2, 3})));
  EXPECT_EQ(Median({5, 1, 3}), 3);
  EXPECT_EQ(Median({4, 1, 3, 2}), 2.5);
}

}  // namespace
}  // namespace drillwave::diagnosis
