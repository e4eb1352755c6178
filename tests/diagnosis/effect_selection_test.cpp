// The effect selection's pairing of two judged models' draws (effect_selection.hpp, internal to the loop): a draw is
// compared with the other model's draw of the same seed, and only where both are in the recording's regime.
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "effect_selection.hpp"
#include "regime_margin.hpp"

namespace drillwave::diagnosis::loop_internal {
namespace {

using Pairs = std::vector<std::pair<double, double>>;

// Train rec01's held out: the baseline's draws 2 and 4 bounce (434, 403) where the recording stays on the bottom; the
// Stribeck fit's five draws (seeds 0-4) all stay. Paired by position, as before, the bouncing draws made the spread of
// the differences 190 and hid a gain every shared draw shows.
TEST(PairedDraws, AreThoseOfOneSeedBothInTheRecordingsRegime) {
  const std::vector<double> mine_errors{0.119, 0.093, 0.139, 0.126, 0.044};
  const std::vector<char> mine_regime{1, 1, 1, 1, 1};
  const std::vector<int> mine_seeds{0, 1, 2, 3, 4};
  const std::vector<double> base_errors{0.308, 0.371, 434.2, 0.215, 403.4, 143.5, 25.9, 0.211, 0.243};
  const std::vector<char> base_regime{1, 1, 0, 1, 0, 0, 0, 1, 1};
  const std::vector<int> base_seeds{0, 1, 2, 3, 4, 5, 6, 7, 8};
  const Pairs pairs = PairedDraws({&mine_errors, &mine_regime, &mine_seeds}, {&base_errors, &base_regime, &base_seeds});
  EXPECT_EQ(pairs, (Pairs{{0.119, 0.308}, {0.093, 0.371}, {0.126, 0.215}}));
}

// A draw whose run failed is left out of a model's draws, so positions and seeds part: seed 1 failed for `mine`.
TEST(PairedDraws, FollowSeedsPastAFailedDraw) {
  const std::vector<double> mine_errors{1.0, 3.0, 4.0};
  const std::vector<char> mine_regime{1, 1, 1};
  const std::vector<int> mine_seeds{0, 2, 3};
  const std::vector<double> their_errors{10.0, 20.0, 30.0, 40.0};
  const std::vector<char> their_regime{1, 1, 1, 1};
  const std::vector<int> their_seeds{0, 1, 2, 3};
  EXPECT_EQ(PairedDraws({&mine_errors, &mine_regime, &mine_seeds}, {&their_errors, &their_regime, &their_seeds}),
            (Pairs{{1.0, 10.0}, {3.0, 30.0}, {4.0, 40.0}}));
}

// Where no seed has both models in the recording's regime (a recording neither reproduces), every shared seed counts.
TEST(PairedDraws, FallBackToEverySharedSeedWhereNoneIsInRegimeForBoth) {
  const std::vector<double> mine_errors{1.0, 2.0};
  const std::vector<char> mine_regime{0, 1};
  const std::vector<int> mine_seeds{0, 1};
  const std::vector<double> their_errors{5.0, 6.0, 7.0};
  const std::vector<char> their_regime{1, 0, 0};
  const std::vector<int> their_seeds{0, 1, 2};
  EXPECT_EQ(PairedDraws({&mine_errors, &mine_regime, &mine_seeds}, {&their_errors, &their_regime, &their_seeds}),
            (Pairs{{1.0, 5.0}, {2.0, 6.0}}));
}

// The held-out regime of a stick-slip window (the bit stuck more than 1 % of it) or a smooth one, and a fit rejected
// only where it leaves the recording's regime clearly (stuck more than 2 % against less than 0.5 %, or bouncing
// against not) while the baseline does not.
TEST(RegimeOf, StickSlipIsABitStuckMoreThanOnePercentOfTheWindow) {
  FeatureSet sticks, smooth;
  sticks.features = {{"stick_fraction", 0.2, 0.03}};
  smooth.features = {{"stick_fraction", 0.005, 0.03}};
  EXPECT_EQ(RegimeOf(sticks, false), "stick-slip");
  EXPECT_EQ(RegimeOf(smooth, false), "smooth");
  EXPECT_EQ(RegimeOf(smooth, true), "bouncing, smooth");
}

// Against a stick-fraction scale of 0.03 (its floor): three scales are 0.09.
TEST(RegimeRejection, OnlyAFitClearlyOutOfTheRecordingsRegimeWhereTheBaselineIsInItIsRejected) {
  const double scale = 0.03;
  const HeldOutMotion sticks{0.2, false}, smooth{0.0, false}, bouncing{0.0, true}, rec07{0.052, false};
  EXPECT_TRUE(RejectedForRegime(sticks, smooth, sticks, scale));
  EXPECT_FALSE(RejectedForRegime(sticks, sticks, smooth, scale));   // the fit found the regime: judged on its features
  EXPECT_FALSE(RejectedForRegime(sticks, smooth, smooth, scale));   // neither has it: features decide
  EXPECT_TRUE(RejectedForRegime(smooth, bouncing, smooth, scale));
  // Dev rec07: stuck 5.2 % recorded, its side-friction fit 0 %: 1.2 of its scales (0.044), whatever the baseline does,
  // no other regime.
  EXPECT_FALSE(RejectedForRegime(rec07, smooth, sticks, 0.044));
  EXPECT_TRUE(ClearlyDifferentRegimes({0.1, false}, {0.005, false}, scale));
  EXPECT_FALSE(ClearlyDifferentRegimes({0.08, false}, {0.0, false}, scale));
  EXPECT_FALSE(ClearlyDifferentRegimes({0.5, false}, {0.2, false}, scale));  // both stick: one regime
}

}  // namespace
}  // namespace drillwave::diagnosis::loop_internal
