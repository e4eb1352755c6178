// Stick-slip statistics on signals whose answers are known by construction.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/cases/statistics.hpp"

namespace drillwave::cases {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A stick-slip cycle of period T: stuck for 1 s, then a slip burst v = A sin^2(pi (t - 1) / (T - 1)); in every other
// cycle a short re-stick of 0.05 s at the end of the burst. The oscillation period is T whatever the re-sticks do.
TEST(Statistics, OscillationPeriodIgnoresShortReSticks) {
  const double period = 3.0, amplitude = 16.0, dt = 1e-3, duration = 60;
  std::vector<double> t, v, angle;
  std::vector<StuckInterval> stuck;
  double phi = 0;
  for (int k = 0; k * period < duration; ++k) {
    stuck.push_back({k * period, k * period + 1.0});
    if (k % 2 == 1) stuck.push_back({(k + 1) * period - 0.05, (k + 1) * period});
  }
  for (double s = 0; s <= duration; s += dt) {
    const double in_cycle = std::fmod(s, period);
    const double speed = in_cycle < 1.0 ? 0.0 : amplitude * std::pow(std::sin(kPi * (in_cycle - 1.0) / (period - 1.0)), 2);
    t.push_back(s), v.push_back(speed), angle.push_back(phi);
    phi += speed * dt;
  }
  const StickSlipStatistics stats = ComputeStickSlipStatistics(stuck, t, v, angle, 10.0, 50.0);
  EXPECT_NEAR(stats.oscillation_period_s, period, 1e-3);
  EXPECT_LT(stats.stick_slip_period_s, 0.8 * period);  // the onset statistic counts the re-sticks
}

TEST(Statistics, NoOscillationWithoutASwing) {
  std::vector<double> t, v, angle;
  for (int i = 0; i <= 1000; ++i) t.push_back(0.01 * i), v.push_back(5.0), angle.push_back(0.05 * i);
  const StickSlipStatistics stats = ComputeStickSlipStatistics({}, t, v, angle, 0.0, 10.0);
  EXPECT_TRUE(std::isnan(stats.oscillation_period_s));
}

}  // namespace
}  // namespace drillwave::cases
