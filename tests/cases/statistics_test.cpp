// Stick-slip statistics on signals whose answers are known by construction.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/cases/statistics.hpp"
#include "drillwave/core/constants.hpp"

namespace drillwave::cases {
namespace {


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

// A sine m + a sin(2 pi t / P) with P dividing the 20-s windows: every window's severity is (max - min) / (2 mean) =
// a / m (the samples hit the crests: P / 4 is a multiple of the step). With the amplitude changing from window to
// window the median picks the middle window's, not the mean of them.
TEST(Statistics, SeverityOfASineIsAmplitudeOverMean) {
  const double mean = 8.0, period = 4.0, dt = 1e-3;
  const std::vector<double> amplitudes = {1.0, 6.0, 2.0, 3.0, 7.5};  // window by window; median 3
  std::vector<double> t, v, angle;
  for (int i = 0; i * dt <= 100.0 + 1e-9; ++i) {
    const double s = i * dt;
    const double a = amplitudes[std::min<std::size_t>(static_cast<std::size_t>(s / 20), amplitudes.size() - 1)];
    t.push_back(s), v.push_back(mean + a * std::sin(2 * kPi * s / period));
    angle.push_back(mean * s + a * period / (2 * kPi) * (1 - std::cos(2 * kPi * s / period)));
  }
  const StickSlipStatistics stats = ComputeStickSlipStatistics({}, t, v, angle, 0.0, 100.0);
  EXPECT_EQ(stats.severity_windows, 5);
  EXPECT_NEAR(stats.severity, 3.0 / mean, 1e-9);
  // The sample mean gives the same within the trapezoid of one step; one window alone gives its own.
  EXPECT_NEAR(StickSlipSeverity(t, v, {}, 40.0, 60.0), 2.0 / mean, 1e-3);
  int windows = 0;
  EXPECT_NEAR(StickSlipSeverity(t, v, angle, 20.0, 32.0, &windows), 6.0 / mean, 1e-9);  // under 20 s: whole
  EXPECT_EQ(windows, 1);
  // Steady: 0; a window that does not turn forward: no severity.
  const std::vector<double> steady(t.size(), mean), rest(t.size(), 0.0);
  EXPECT_EQ(StickSlipSeverity(t, steady, {}, 0.0, 100.0), 0.0);
  EXPECT_TRUE(std::isnan(StickSlipSeverity(t, rest, {}, 0.0, 100.0)));
}

}  // namespace
}  // namespace drillwave::cases
