// Rainflow counting against the worked example of ASTM E1049-85 (sect. 5.4.4, counted by hand below), the S-N
// curve against its defining points, and Miner's damage of a constant-amplitude history against n / N_f.
#include "drillwave/analysis/fatigue.hpp"
#include "drillwave/core/constants.hpp"

#include <cmath>
#include <map>
#include <vector>

#include <gtest/gtest.h>

namespace drillwave::analysis {
namespace {


TEST(Reversals, KeepsPeaksValleysAndTheEndsOnly) {
  EXPECT_EQ(Reversals({0, 1, 2, 2, 3, 1, 1, 0, 4, 5}), (std::vector<double>{0, 3, 0, 5}));
  EXPECT_EQ(Reversals({2, 2, 2}), (std::vector<double>{2}));
  EXPECT_TRUE(Reversals({}).empty());
}

// E1049's history -2, 1, -3, 5, -1, 3, -4, 4, -2 (with points between the reversals added, which must not count).
// By hand: [-2 1 -3] X=4 >= Y=3, Y holds the start: half of 3 (mean -0.5); [1 -3 5] X=8 >= 4: half of 4 (mean
// -1); [-3 5 -1 3 -4]: X=7 >= Y=4 (-1..3): one cycle of 4 (mean 1), then [-3 5 -4] X=9 >= 8: half of 8 (mean 1);
// [5 -4 4 -2] ends with halves of 9 (mean 0.5), 8 (mean 0) and 6 (mean 1). Totals: 3: 0.5, 4: 1.5, 6: 0.5, 8: 1,
// 9: 0.5 -- E1049's table.
TEST(Rainflow, CountsTheAstmE1049Example) {
  const auto cycles = RainflowCount({-2, -0.5, 1, -3, 0, 5, -1, 3, 2, -4, 4, -2});
  std::map<double, double> count_by_range;
  for (const auto& c : cycles) count_by_range[c.range] += c.count;
  EXPECT_EQ(count_by_range, (std::map<double, double>{{3, 0.5}, {4, 1.5}, {6, 0.5}, {8, 1.0}, {9, 0.5}}));
  ASSERT_EQ(cycles.size(), 7u);
  const std::vector<RainflowCycle> expected = {{3, -0.5, 0.5}, {4, -1, 0.5}, {4, 1, 1}, {8, 1, 0.5},
                                               {9, 0.5, 0.5},  {8, 0, 0.5},  {6, 1, 0.5}};
  for (std::size_t i = 0; i < cycles.size(); ++i) {
    EXPECT_EQ(cycles[i].range, expected[i].range) << i;
    EXPECT_EQ(cycles[i].mean, expected[i].mean) << i;
    EXPECT_EQ(cycles[i].count, expected[i].count) << i;
  }
}

// A small cycle interrupting a large one is closed and taken out; the large one counts whole.
TEST(Rainflow, SeparatesANestedCycle) {
  const auto cycles = RainflowCount({0, 10, 4, 6, 0, 10});
  double nested = 0, large = 0;
  for (const auto& c : cycles) (c.range == 2 ? nested : c.range == 10 ? large : nested) += c.count;
  EXPECT_EQ(nested, 1.0);
  EXPECT_EQ(large, 1.5);  // 0-10 half (from the start), 10-0 and 0-10 halves at the end
}

TEST(SnCurve, MildSteelPassesThroughItsDefiningPoints) {
  const SnCurve steel = SnCurve::MildSteel();
  EXPECT_NEAR(steel.CyclesToFailure(0.9 * 400e6), 1e3, 1e-6);
  EXPECT_NEAR(steel.CyclesToFailure(0.5 * 400e6), 1e6, 1e-3);
  EXPECT_TRUE(std::isinf(steel.CyclesToFailure(0.49 * 400e6)));
  EXPECT_TRUE(std::isinf(steel.CyclesToFailure(0)));
}

// n periods of a fully reversed sine starting and ending at a peak: 2n half cycles of range 2 S_a, D = n / N_f.
TEST(Miner, ConstantAmplitudeDamageIsCyclesOverCyclesToFailure) {
  const SnCurve curve{500e6, -0.1, 100e6};
  for (double amplitude : {150e6, 300e6}) {
    const int periods = 37, per_period = 50;
    std::vector<double> stress;
    for (int i = 0; i <= periods * per_period; ++i)
      stress.push_back(20e6 + amplitude * std::cos(2 * kPi * i / per_period));
    const double closed_form = periods / std::pow(amplitude / 500e6, 1 / -0.1);
    EXPECT_NEAR(MinerDamage(RainflowCount(stress), curve), closed_form, 1e-12 * closed_form) << amplitude;
  }
  // Below the endurance limit nothing accumulates.
  EXPECT_EQ(MinerDamage(RainflowCount({0, 90e6, -90e6, 90e6}), curve), 0.0);
}

}  // namespace
}  // namespace drillwave::analysis
