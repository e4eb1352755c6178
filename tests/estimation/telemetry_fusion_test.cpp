// Delayed telemetry fused into an estimate (estimation/telemetry_fusion.hpp) against its closed form: a constant
// error of the estimate decays as exp(-(t - d) / T) once the first telemetry sample arrives at the delay d; the fast
// motion the telemetry reports late is not copied into the estimate; nothing the telemetry reports after t changes
// the estimate at t (it runs live). And on an independent recording with a telemetry delay, the weight on bit of a
// model at the wrong operating point loses most of its bias.
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/diagnosis/recording.hpp"
#include "drillwave/estimation/recording_estimate.hpp"
#include "drillwave/estimation/telemetry_fusion.hpp"
#include "json_case.hpp"

namespace drillwave::estimation {
namespace {

constexpr double kDt = 0.01, kDelay = 3.0, kTimeConstant = 20.0, kBias = 5.0;

// A bit speed with a stick-slip-like oscillation (period 4 s), the estimate kBias off, the telemetry kDelay late.
struct Signals {
  std::vector<double> truth, estimate, telemetry;
};
Signals Make(std::size_t n) {
  Signals s;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * kDt;
    const auto bit = [](double time) { return 6 + 5 * std::sin(2 * kPi * time / 4); };
    s.truth.push_back(bit(t));
    s.estimate.push_back(bit(t) + kBias);
    s.telemetry.push_back(t >= kDelay ? bit(t - kDelay) : std::nan(""));
  }
  return s;
}

TEST(TelemetryFusion, AConstantErrorDecaysAtTheLowPasssRateAfterTheDelay) {
  const std::size_t n = 12000;  // 120 s
  const Signals s = Make(n);
  const std::vector<double> fused = FuseDelayedTelemetry(s.estimate, s.telemetry, kDt, {kDelay, kTimeConstant});
  double worst = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * kDt;
    // The innovation is exactly -kBias from the delay on; the low-pass reaches it as 1 - exp(-(samples) dt / T).
    const double samples = t + 1e-9 >= kDelay ? std::floor((t - kDelay) / kDt + 1e-6) + 1 : 0;
    const double expected = kBias * std::exp(-samples * kDt / kTimeConstant);
    worst = std::max(worst, std::abs(fused[i] - s.truth[i] - expected));
  }
  std::printf("[ measured ] fused error against its closed form: largest difference %.1e (bias %.0f, T %.0f s)\n",
              worst, kBias, kTimeConstant);
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(std::abs(fused.back() - s.truth.back()), kBias * std::exp(-(120 - kDelay - 0.01) / kTimeConstant) * 1.01);
}

TEST(TelemetryFusion, TheEstimateAtATimeReadsNoLaterTelemetry) {
  const std::size_t n = 6000;
  Signals s = Make(n);
  const std::vector<double> fused = FuseDelayedTelemetry(s.estimate, s.telemetry, kDt, {kDelay, kTimeConstant});
  for (std::size_t i = 4000; i < n; ++i) s.telemetry[i] += 100;  // what arrives after 40 s
  const std::vector<double> changed = FuseDelayedTelemetry(s.estimate, s.telemetry, kDt, {kDelay, kTimeConstant});
  for (std::size_t i = 0; i < 4000; ++i) ASSERT_EQ(fused[i], changed[i]) << i;
  EXPECT_NE(fused[4000], changed[4000]);
}

TEST(TelemetryFusion, TheFastMotionIsNotCopied) {
  // An estimate that misses the oscillation (a constant 6) is corrected only by the oscillation's low-passed part:
  // the first-order filter passes 1 / sqrt(1 + (w T)^2) of it, w = 2 pi / 4 s (read over the last 50 s of 200, when
  // the start's transient has decayed to 1e-4).
  const std::size_t n = 20000;
  Signals s = Make(n);
  for (double& v : s.estimate) v = 6;
  const std::vector<double> fused = FuseDelayedTelemetry(s.estimate, s.telemetry, kDt, {kDelay, kTimeConstant});
  double swing = 0;
  for (std::size_t i = 15000; i < n; ++i) swing = std::max(swing, std::abs(fused[i] - 6));
  const double w = 2 * kPi / 4, passed = 5 / std::sqrt(1 + w * w * kTimeConstant * kTimeConstant);
  EXPECT_NEAR(swing, passed, 0.01 * passed);
}

TEST(TelemetryFusion, BadOptionsNameTheField) {
  const std::vector<double> x(10, 1.0);
  try {
    FuseDelayedTelemetry(x, x, kDt, {-1, kTimeConstant});
    FAIL() << "a negative delay was accepted";
  } catch (const ParameterError& e) {
    EXPECT_EQ(e.json_path(), "telemetry_delay_s");
  }
  try {
    FuseDelayedTelemetry(x, x, kDt, {1, 0});
    FAIL() << "a time constant of 0 was accepted";
  } catch (const ParameterError& e) {
    EXPECT_EQ(e.json_path(), "innovation_time_constant_s");
  }
}

// The independent simulator's train rec06 (a telemetry delay of about 3.7 s on bit_rpm and wob_kN), estimated with
// the baseline case as it is, not moved to the recording's operating point by the sidecar: its weight on bit is
// 45 kN low on average. Fused with the telemetry, the bias at the telemetry's delay falls by more than half; the bit
// speed, whose error is the wrong operating point's fast motion, is not made worse.
TEST(TelemetryFusion, RemovesMostOfAWrongOperatingPointsWeightOnBitBias) {
  const std::string file = std::string(DRILLWAVE_SHARED_DIR) + "/recordings/synthetic-train/rec06.csv";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " is absent (the workplace's recordings)";
  const auto rec = diagnosis::LoadRecording(file);
  const BitEstimate surface =
      EstimateBit(EstimatorModelFromCase(testing::LoadCase("baseline-60rpm")),
                  SignalsFromRecording(rec, ParseSurfaceChannels("top_rpm,top_torque_kNm,hookload_kN", rec)), {});
  BitEstimate fused = surface;
  FuseTelemetry(rec, "bit_rpm,wob_kN", {}, true, fused);
  const nlohmann::json before = EstimateSummary(rec, surface, {}).at("errors");
  const nlohmann::json after = EstimateSummary(rec, fused, {}).at("errors");
  const double bias_before = before.at("wob_N_at_downhole_delay").at("bias").get<double>();
  const double bias_after = after.at("wob_N_at_downhole_delay").at("bias").get<double>();
  const double speed_before = before.at("bit_rpm_at_downhole_delay").at("rms").get<double>();
  const double speed_after = after.at("bit_rpm_at_downhole_delay").at("rms").get<double>();
  std::printf("[ measured ] train rec06 without its sidecar: weight on bit bias at the telemetry's delay %.0f -> %.0f "
              "N, rms %.0f -> %.0f N; bit speed rms %.2f -> %.2f rpm\n", bias_before, bias_after,
              before.at("wob_N_at_downhole_delay").at("rms").get<double>(),
              after.at("wob_N_at_downhole_delay").at("rms").get<double>(), speed_before, speed_after);
  EXPECT_LT(bias_before, -20e3);
  EXPECT_LT(std::abs(bias_after), 0.5 * std::abs(bias_before));
  EXPECT_LT(speed_after, 1.01 * speed_before);
}

}  // namespace
}  // namespace drillwave::estimation
