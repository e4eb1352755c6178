// Sensors turn a simulated channel into a recorded one: each stage against what it must do exactly.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>
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

// A logger's reading is the mean over the window ending at it: for a sine, the sine damped by sinc(omega w / 2) and
// late by half the window. The mean is the exact integral of the linear interpolant, the trapezoid rule on a window
// of whole samples, which scales the sine by (omega h / 2) cot(omega h / 2): with that factor the closed form holds
// to round-off on any grid, without it to the trapezoid's (omega h)^2 / 12.
TEST(Sensors, WindowMeanOfASineIsTheSincDampedSineHalfAWindowLate) {
  const double omega = 1.3, window = 0.8;  // omega * window = 1.04: a sinc factor of 0.956
  for (const int per_window : {8, 80, 800}) {
    const double h = window / per_window;
    const Signal s = Sine(h, 5);
    SensorModel m;
    m.window_s = window;
    const std::vector<double> y = Measure(m, s.t, s.v, 1);
    const double sinc = std::sin(0.5 * omega * window) / (0.5 * omega * window);
    const double trapezoid = 0.5 * omega * h / std::tan(0.5 * omega * h);
    double exact = 0, continuous = 0;
    for (std::size_t k = per_window; k < s.t.size(); ++k) {
      const double closed_form = sinc * std::sin(omega * (s.t[k] - 0.5 * window));
      exact = std::max(exact, std::abs(y[k] - 2 - trapezoid * closed_form));
      continuous = std::max(continuous, std::abs(y[k] - 2 - closed_form));
    }
    EXPECT_LT(exact, 1e-12) << per_window << " samples per window";
    EXPECT_LT(continuous, std::pow(omega * h, 2) / 12 + 1e-12) << per_window << " samples per window";
  }
}

// A step between two samples (0 before t_j, 1 from t_j on: the interpolant climbs over [t_j - h, t_j], centred at
// t_step = t_j - h / 2) is read as the ramp (t - t_step) / window, from 0 to 1 over exactly one window; a delay
// shifts that ramp by exactly the delay, also by a delay that is not a whole number of samples.
TEST(Sensors, WindowMeanOfAStepIsTheLinearRampAndADelayShiftsItExactly) {
  const double h = 1e-3, window = 0.01, t_j = 0.5, t_step = t_j - 0.5 * h;
  Signal s;
  for (int k = 0; k <= 1000; ++k) s.t.push_back(k * h), s.v.push_back(k * h >= t_j - 1e-12 ? 1.0 : 0.0);
  for (const double delay : {0.0, 0.0123}) {
    SensorModel m;
    m.window_s = window;
    m.delay_s = delay;
    const std::vector<double> y = Measure(m, s.t, s.v, 1);
    int on_ramp = 0;
    for (std::size_t k = 0; k < s.t.size(); ++k) {
      const double x = s.t[k] - delay;  // when the reading arriving at t[k] was taken
      if (x <= t_step - 0.5 * h) {
        EXPECT_NEAR(y[k], 0.0, 1e-12) << "at t = " << s.t[k];
      } else if (x >= t_step + 0.5 * h && x <= t_step + window - 0.5 * h) {  // the window holds the whole climb
        EXPECT_NEAR(y[k], (x - t_step) / window, 1e-12) << "at t = " << s.t[k];
        ++on_ramp;
      } else if (x >= t_step + window + 0.5 * h) {
        EXPECT_NEAR(y[k], 1.0, 1e-12) << "at t = " << s.t[k];
      }
    }
    EXPECT_GE(on_ramp, 8) << "delay " << delay;
  }
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

// Telemetry coded as the chapter's Fig. 2.4: a 12-bit code over [0, 300] rpm sent at 2 bit/s (mud pulse) carries a
// sample every 6 s, taken when its frame starts and decoded 6 s later, plus the transport delay; each value is the
// nearest of 4096 levels (within half a step, 0.0367 rpm, of the sensor's reading), clamped to the range.
TEST(Sensors, CodedTelemetryHoldsEachQuantizedSampleFromTheEndOfItsFrame) {
  Signal s;
  for (int k = 0; k <= 6000; ++k) s.t.push_back(0.01 * k), s.v.push_back(150 + 200 * std::sin(0.05 * k * 0.01));
  SensorModel m;
  m.delay_s = 2.2, m.bits = 12, m.code_min = 0, m.code_max = 300, m.bit_rate_bps = 2;
  EXPECT_DOUBLE_EQ(m.SamplePeriod(), 6.0);
  const double step = 300.0 / 4095;
  const std::vector<double> y = Measure(m, s.t, s.v, 1);
  int checked = 0;
  for (std::size_t k = 0; k < s.t.size(); ++k) {
    const double taken = std::max(0.0, 6.0 * std::floor((s.t[k] - 2.2 - 6.0) / 6.0 + 1e-9));
    const double truth = 150 + 200 * std::sin(0.05 * taken);
    const double coded = std::clamp(truth, 0.0, 300.0);
    ASSERT_NEAR(y[k], coded, 0.5 * step + 1e-9) << "at t = " << s.t[k];
    const double level = y[k] / step;  // on a level of the code
    ASSERT_NEAR(level, std::round(level), 1e-9) << "at t = " << s.t[k];
    ++checked;
  }
  EXPECT_EQ(checked, 6001);
  EXPECT_EQ(m.Quantized(-5), 0.0);
  EXPECT_EQ(m.Quantized(1e6), 300.0);
}

// The two noises of the chapter: S(t) downhole passes the code (a fine code leaves it whole), N(t) at the receiver is
// added to the decoded value; each has its standard deviation, and together their variances add.
TEST(Sensors, DownholeAndReceiverNoisesEachHaveTheirStandardDeviation) {
  Signal s;
  for (int k = 0; k <= 200000; ++k) s.t.push_back(0.01 * k), s.v.push_back(100.0);
  auto spread = [&](const SensorModel& m) {
    const std::vector<double> y = Measure(m, s.t, s.v, 7);
    double sum = 0, sum2 = 0;
    for (double v : y) sum += v - 100, sum2 += (v - 100) * (v - 100);
    const double n = static_cast<double>(y.size()), mean = sum / n;
    return std::sqrt(sum2 / n - mean * mean);
  };
  SensorModel m;
  m.bits = 16, m.code_min = 0, m.code_max = 300;  // a step of 0.0046 rpm
  const double n = static_cast<double>(s.t.size()), tolerance = 4 / std::sqrt(2 * n);  // four standard errors
  m.downhole_noise_std = 2;
  EXPECT_NEAR(spread(m), 2 * std::sqrt(1 + std::pow(300.0 / 65535, 2) / 12 / 4), 2 * tolerance);
  m.downhole_noise_std = 0, m.noise_std = 1.5;
  EXPECT_NEAR(spread(m), 1.5, 1.5 * tolerance);
  m.downhole_noise_std = 2;
  EXPECT_NEAR(spread(m), 2.5, 2.5 * tolerance);
  // A coarse code hides a small downhole noise: 100 rpm is a level of a 4-bit code over [0, 300] (20-rpm steps), and
  // S of 0.5 rpm never reaches the half-way marks 10 rpm away.
  SensorModel coarse;
  coarse.bits = 4, coarse.code_min = 0, coarse.code_max = 300, coarse.downhole_noise_std = 0.5;
  const std::vector<double> y = Measure(coarse, s.t, s.v, 7);
  for (double v : y) ASSERT_EQ(v, 100.0) << "100 rpm is a level of the 4-bit code (5 x 20 rpm)";
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
  try {
    ParseCase(SaldivarWithSensors({{"channels", {{"bit_rpm", {{"window_s", -0.01}}}}}}));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/sensors/channels/bit_rpm/window_s"), std::string::npos) << e.what();
  }
  // A code's fields: range ordered, a bit rate or a hold (not both), and none of them without bits.
  const std::vector<std::pair<nlohmann::json, std::string>> refused{
      {{{"bits", 12}, {"range", {300, 0}}}, "/range"},
      {{{"bits", 12}, {"range", {0, 300}}, {"bit_rate_bps", 2}, {"hold_s", 1}}, "/hold_s"},
      {{{"bit_rate_bps", 2}}, "/bit_rate_bps"},
      {{{"bits", 40}, {"range", {0, 300}}}, "/bits"},
      {{{"bits", 12}}, "/range"}};
  for (const auto& [sensor, field] : refused) {
    try {
      ParseCase(SaldivarWithSensors({{"channels", {{"bit_rpm", sensor}}}}));
      ADD_FAILURE() << "expected an InputError for " << sensor.dump();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("/sensors/channels/bit_rpm" + field), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace drillwave::cases
