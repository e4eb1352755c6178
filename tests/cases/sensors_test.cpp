// Sensors turn a simulated channel into a recorded one: each stage against what it must do exactly.
#include <cmath>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"

namespace drillwave::cases {
namespace {

struct Signal {
  std::vector<double> t, v;
};
Signal Sine(double dt, double duration) {
  Signal s;
  for (int k = 0; k * dt <= duration + 1e-12; ++k) s.t.push_back(k * dt), s.v.push_back(std::sin(1.3 * k * dt) + 2.0);
  return s;
}

TEST(Sensors, TelemetryDelayIsAnExactTimeShift) {
  const Signal s = Sine(0.01, 30);
  SensorModel m;
  m.delay_s = 6.6;  // mud pulse (chapter seed)
  const std::vector<double> y = Measure(m, s.t, s.v, 1);
  double worst = 0;
  for (std::size_t k = 660; k < s.t.size(); ++k) worst = std::max(worst, std::abs(y[k] - s.v[k - 660]));
  EXPECT_LT(worst, 1e-12);
  for (std::size_t k = 0; k < 660; ++k) EXPECT_EQ(y[k], s.v[0]);  // before anything arrived: the first reading
}

TEST(Sensors, SampleAndHoldKeepsEachTelemetrySampleUntilTheNext) {
  const Signal s = Sine(0.01, 30);
  SensorModel m;
  m.delay_s = 2.2;  // acoustic telemetry
  m.hold_s = 1.0;
  const std::vector<double> y = Measure(m, s.t, s.v, 1);
  for (std::size_t k = 0; k < s.t.size(); ++k) {
    const double sent = std::max(0.0, std::floor(s.t[k] - 2.2 + 1e-9));  // sample time of the value received
    EXPECT_NEAR(y[k], std::sin(1.3 * sent) + 2.0, 1e-12) << "at t = " << s.t[k];
  }
}

TEST(Sensors, LowPassFollowsTheExactStepResponse) {
  Signal s;
  for (int k = 0; k <= 1000; ++k) s.t.push_back(1e-3 * k), s.v.push_back(k == 0 ? 0.0 : 1.0);
  SensorModel m;
  m.time_constant_s = 0.1;
  const std::vector<double> y = Measure(m, s.t, s.v, 1);
  for (std::size_t k = 1; k < s.t.size(); ++k) EXPECT_NEAR(y[k], 1 - std::exp(-(s.t[k]) / 0.1), 1e-12);
}

TEST(Sensors, NoiseHasItsStandardDeviationAndIsReproducible) {
  const Signal s = Sine(0.001, 20);
  SensorModel m;
  m.noise_std = 0.5;
  const std::vector<double> a = Measure(m, s.t, s.v, 42), b = Measure(m, s.t, s.v, 42), c = Measure(m, s.t, s.v, 43);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  double sum = 0, sum2 = 0;
  for (std::size_t k = 0; k < a.size(); ++k) sum += a[k] - s.v[k], sum2 += (a[k] - s.v[k]) * (a[k] - s.v[k]);
  const double n = static_cast<double>(a.size()), mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(sd, 0.5, 0.5 * 4 / std::sqrt(2 * n));  // four standard errors of the estimate
  EXPECT_NEAR(mean, 0.0, 4 * 0.5 / std::sqrt(n));
}

nlohmann::json SaldivarWithSensors(const nlohmann::json& sensors) {
  nlohmann::json doc = nlohmann::json::parse(DefaultCaseText());
  doc["simulation"]["duration_s"] = 20;
  doc["simulation"]["output_interval_s"] = 0.01;
  doc["statistics"]["window_s"] = {0, 20};
  doc.erase("expect");
  doc["sensors"] = sensors;
  return doc;
}

TEST(Sensors, ACaseAddsMeasuredChannelsBesideTheTrueOnes) {
  const Case c = ParseCase(SaldivarWithSensors(
      {{"seed", 3}, {"channels", {{"bit_rpm", {{"delay_s", 6.6}, {"hold_s", 0.5}, {"noise_std", 1.0}}}}}}));
  const CaseRun run = RunCase(c);
  const auto& truth = run.result.channel("bit_rpm").values;
  const auto& measured = run.result.channel("bit_rpm_measured").values;
  ASSERT_EQ(truth.size(), measured.size());
  // The measured bit speed lags: it correlates best with the true one 6.6 s earlier (within the hold and grid).
  double best = -1, best_lag = 0;
  for (int lag = 0; lag <= 1000; lag += 10) {
    double num = 0, da = 0, db = 0, ma = 0, mb = 0;
    const std::size_t n = truth.size() - lag;
    for (std::size_t k = 0; k < n; ++k) ma += truth[k], mb += measured[k + lag];
    ma /= n, mb /= n;
    for (std::size_t k = 0; k < n; ++k)
      num += (truth[k] - ma) * (measured[k + lag] - mb), da += (truth[k] - ma) * (truth[k] - ma),
          db += (measured[k + lag] - mb) * (measured[k + lag] - mb);
    const double r = num / std::sqrt(da * db);
    if (r > best) best = r, best_lag = 0.01 * lag;
  }
  EXPECT_NEAR(best_lag, 6.6 + 0.25, 0.3);  // delay plus half a hold period on average
  EXPECT_GT(best, 0.9);
}

TEST(Sensors, AnUnknownChannelIsBadInputNamingIt) {
  const Case c = ParseCase(SaldivarWithSensors({{"channels", {{"bit_rmp", {{"delay_s", 1.0}}}}}}));
  try {
    RunCase(c);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/sensors/channels/bit_rmp"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bit_rpm"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ParseCase(SaldivarWithSensors({{"channels", {{"bit_rpm", {{"delay_s", -1.0}}}}}})), InputError);
}

}  // namespace
}  // namespace drillwave::cases
