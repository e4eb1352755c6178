// The virtual downhole sensor (issue 34): the continuation is exact on a lossless string, the estimators recover the
// bit of drillwave's own runs from their top signals, and the observer forgets a wrong start.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <memory>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/diagnosis/recording.hpp"
#include "drillwave/diagnosis/sidecar.hpp"
#include "drillwave/estimation/estimate.hpp"
#include "drillwave/estimation/estimate_report.hpp"
#include "drillwave/estimation/follow.hpp"
#include "drillwave/estimation/hybrid_observer.hpp"
#include "drillwave/estimation/lumped_observer.hpp"
#include "drillwave/estimation/metrics.hpp"
#include "drillwave/estimation/recording_estimate.hpp"
#include "drillwave/estimation/smoothing.hpp"
#include "drillwave/estimation/wave_continuation.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace es = drillwave::estimation;

namespace {

using drillwave::kPi;
using drillwave::kRadPerSecondPerRpm;

std::vector<double> Rad(const std::vector<double>& rpm) {
  std::vector<double> w(rpm);
  for (double& v : w) v *= kRadPerSecondPerRpm;
  return w;
}

// Two smooth waves at the top of a lossless uniform string: the bottom's speed and torque are known in closed form.
TEST(WaveContinuation, LosslessStringGivesTheBottomFromTheTopOneTravelTimeLater) {
  const double z = 300, tau = 0.6, dt = 0.002;
  auto down = [](double t) { return 5 + std::sin(2 * t) + 0.3 * std::cos(7 * t); };
  auto up = [](double t) { return 1 + 0.5 * std::sin(3 * t + 1); };
  std::vector<double> t, v, f;
  for (int i = 0; i <= 5000; ++i) {
    t.push_back(i * dt);
    v.push_back(down(t.back()) + up(t.back()));
    f.push_back(z * (down(t.back()) - up(t.back())));
  }
  const std::vector<es::WavePiece> pieces(4, es::WavePiece{z, tau / 4, 0});
  const es::WaveEnd end = es::ContinueDownward(t, v, f, pieces);
  double worst = 0;
  int finite = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(end.velocity[i])) continue;
    ++finite;
    // At the bottom the down-going wave left the top tau earlier, the up-going one reaches the top tau later.
    worst = std::max(worst, std::abs(end.velocity[i] - (down(t[i] - tau) + up(t[i] + tau))));
    worst = std::max(worst, std::abs(end.force[i] / z - (down(t[i] - tau) - up(t[i] + tau))));
  }
  EXPECT_GT(finite, 4000);                         // all but the first and last travel time (and a sample or two)
  EXPECT_TRUE(std::isnan(end.velocity[100]));      // 0.2 s < tau: not available
  EXPECT_LT(worst, 1e-5);                          // cubic interpolation of waves of 7 rad/s sampled at 500 Hz
}

TEST(WaveContinuation, AShuntDashpotTakesItsTorqueFromASteadyRotation) {
  std::vector<double> t, v, f;
  for (int i = 0; i < 400; ++i) t.push_back(0.01 * i), v.push_back(6), f.push_back(5000);
  const es::WaveEnd end = es::ContinueDownward(t, v, f, {{300, 0.2, 60}, {300, 0.2, 60}});
  EXPECT_NEAR(end.velocity[200], 6, 1e-9);  // uniform speed down a rotating string
  EXPECT_NEAR(end.force[200], 5000 - 2 * 60 * 6, 1e-6);  // the steady torque less c L w
}

TEST(Metrics, StuckScoresCountSamples) {
  const std::vector<double> t{0, 1, 2, 3, 4, 5};
  const std::vector<double> measured{0, 0, 5, 5, 0, 5}, estimate{0, 5, 5, 0, 0, NAN};
  const std::vector<char> stuck{1, 0, 0, 1, 1, 0};
  const es::StuckScore s = es::ScoreStuck(t, estimate, stuck, measured, 1.0, 0, 10);
  EXPECT_EQ(s.samples, 5u);  // the NaN estimate is left out
  EXPECT_EQ(s.true_positive, 2u);
  EXPECT_EQ(s.false_positive, 1u);
  EXPECT_EQ(s.false_negative, 1u);
  EXPECT_NEAR(s.f1, 4.0 / 6.0, 1e-12);
  const auto events = es::StuckEvents({0, 1, 2, 3, 4, 5, 6}, {1, 1, 0, 1, 1, 0, 0});
  ASSERT_EQ(events.size(), 1u);  // one free sample inside a stick is noise across the threshold
  EXPECT_EQ(events[0].end_s, 4);
}

// A telemetry delay is the lag at which the measured channel correlates best with the estimate, where it explains most
// of their mismatch: an irregular motion delayed by 2.5 s (with 10 % noise and a gain error the correlation ignores)
// reads 2.5 s; the same motion undelayed, and a periodic motion a period on, read no delay.
TEST(Metrics, ATelemetryLagIsTheBestCorrelationsWhereItExplainsTheMismatch) {
  std::vector<double> t, estimate, measured, periodic, periodic_measured;
  const double dt = 0.01;
  for (int i = 0; i <= 6000; ++i) t.push_back(i * dt);
  auto motion = [](double x) { return std::sin(1.3 * x) + 0.7 * std::sin(2.9 * x + 1) + 0.5 * std::sin(0.41 * x); };
  for (double x : t) {
    estimate.push_back(motion(x));
    measured.push_back(1.2 * motion(x - 2.5) + 0.1 * std::sin(97 * x));
    periodic.push_back(std::sin(2 * kPi * x / 1.5));
    periodic_measured.push_back(periodic.back() + 0.05 * std::sin(97 * x));
  }
  const es::TelemetryLag late = es::ReadTelemetryLag(t, estimate, measured, 5, 50, 8);
  EXPECT_TRUE(late.found);
  EXPECT_NEAR(late.lag_s, 2.5, 0.011);
  EXPECT_GT(late.correlation, 0.95);
  EXPECT_FALSE(es::ReadTelemetryLag(t, estimate, estimate, 5, 50, 8).found);
  const es::TelemetryLag period = es::ReadTelemetryLag(t, periodic, periodic_measured, 5, 50, 8);
  EXPECT_FALSE(period.found) << period.lag_s;
  // A lag past the window's end is not read, and a peak on the search's edge is no delay.
  const es::TelemetryLag past_the_end = es::ReadTelemetryLag(t, estimate, measured, 57, 60, 8);
  EXPECT_FALSE(past_the_end.found) << past_the_end.lag_s << " " << past_the_end.correlation;
  const es::TelemetryLag edge = es::ReadTelemetryLag(t, estimate, measured, 5, 50, 2);
  EXPECT_FALSE(edge.found) << edge.lag_s << " " << edge.correlation;
}

// A coupled run's surface channels as the estimator reads them.
es::SurfaceSignals SurfaceOf(const drillwave::cases::RunResult& run) {
  es::SurfaceSignals s;
  s.time_s = run.time_s;
  s.top_speed_rad_s = Rad(run.channel("top_rpm").values);
  s.top_torque_Nm = run.channel("top_torque_Nm").values;
  s.hook_load_N = run.channel("hookload_N").values;
  return s;
}

// drillwave's own coupled run (the baseline at 60 rpm sticks and slips from about 9 s): its top signals give its bit.
TEST(WaveStringEstimate, RecoversTheBitOfDrillwavesOwnCoupledRun) {
  nlohmann::json doc = drillwave::testing::LoadCase("baseline-60rpm");
  doc["simulation"]["duration_s"] = 40;
  doc["statistics"]["window_s"] = {0, 40};
  const auto run = drillwave::cases::RunCase(drillwave::cases::ParseCase(doc));
  const es::SurfaceSignals s = SurfaceOf(run.result);
  const es::EstimatorModel model = es::EstimatorModelFromCase(doc);
  const es::BitEstimate e = es::EstimateBit(model, s, {});
  const std::vector<double> bit = Rad(run.result.channel("bit_rpm").values);
  const es::SeriesError speed = es::CompareSeries(e.time_s, e.bit_speed_rad_s, bit, 10, 40);
  // Exact up to the lumping of the distributed damping (here at the pieces' middles, in the model at their ends), the
  // interpolation, the top inertia's torque taken as a time advance and the smoothing over 0.08 s, which rounds the
  // stick's corners. Measured: 2.09 rpm, 3.3 % of the mean (more than these alone explain: not yet found); bound 5 %.
  EXPECT_GT(speed.samples, 2500u);
  EXPECT_LT(speed.rms, 0.05 * speed.measured_mean) << "RMS " << speed.rms / kRadPerSecondPerRpm << " rpm";
  const es::StuckScore stuck = es::ScoreStuck(e.time_s, e.bit_speed_rad_s, e.stuck, bit, e.stuck_threshold_rad_s, 10, 40);
  EXPECT_GT(stuck.measured_stuck, 200u);  // it does stick
  EXPECT_GT(stuck.f1, 0.9);
  EXPECT_NEAR(e.latency_s, 2000 / std::sqrt(80769e6 / 7850) + 0.025 + 0.08, 0.02);
  const es::SeriesError torque = es::CompareSeries(e.time_s, e.bit_torque_Nm, run.result.channel("bit_torque_Nm").values, 10, 40);
  // The torque needs the bit's acceleration, a derivative of the continued speed: measured 715 N m, 13 % of the mean.
  EXPECT_LT(torque.rms, 0.2 * torque.measured_mean) << "torque RMS " << torque.rms << " N m";
}

TEST(Smoothing, APolynomialFitsSlopeIsExactUpToItsOrder) {
  const double dt = 0.01;
  std::vector<double> quartic, x4_slope;
  for (int i = 0; i < 400; ++i) {
    const double t = i * dt;
    quartic.push_back(1 - 2 * t + 0.5 * t * t - 0.3 * std::pow(t, 3) + 0.07 * std::pow(t, 4));
    x4_slope.push_back(-2 + t - 0.9 * t * t + 0.28 * std::pow(t, 3));
  }
  const es::Smoothed fit = es::SmoothPolynomial(quartic, dt, 50, 4);
  const es::Smoothed line = es::SmoothPolynomial(quartic, dt, 50, 2);
  const es::Smoothed reference = es::SmoothQuadratic(quartic, dt, 50);
  double worst = 0, quadratic_worst = 0;
  for (std::size_t i = 50; i + 50 < quartic.size(); ++i) {
    EXPECT_NEAR(fit.value[i], quartic[i], 1e-9);
    worst = std::max(worst, std::abs(fit.derivative[i] - x4_slope[i]));
    quadratic_worst = std::max(quadratic_worst, std::abs(line.derivative[i] - x4_slope[i]));
    EXPECT_NEAR(line.value[i], reference.value[i], 1e-9);  // the quadratic is Savitzky-Golay's closed form
    EXPECT_NEAR(line.derivative[i], reference.derivative[i], 1e-9);
  }
  EXPECT_LT(worst, 1e-8);
  EXPECT_GT(quadratic_worst, 1e-3);  // a quadratic's slope misses the cubic and quartic terms
  EXPECT_NEAR(line.derivative_noise_gain, reference.derivative_noise_gain, 1e-9);
  EXPECT_GT(fit.derivative_noise_gain, line.derivative_noise_gain);  // the price: more noise for the same window
}

// A soft drive (tuned PI with the kp and ki of train rec18's, 1.26 and 28 times the pipe's impedance) that the
// estimator's case does not know: the top inertia's torque comes from the measured speed's slope.
TEST(WaveStringEstimate, FollowsTheBitBehindASoftDriveTheCaseDoesNotKnow) {
  nlohmann::json doc = drillwave::testing::LoadCase("baseline-60rpm");
  doc["simulation"]["duration_s"] = 60;
  doc["statistics"]["window_s"] = {0, 60};
  nlohmann::json soft = doc;
  soft["model"]["top"]["kp_Nms_per_rad"] = 376.0;
  soft["model"]["top"]["ki_Nm_per_rad"] = 8309.0;
  const auto run = drillwave::cases::RunCase(drillwave::cases::ParseCase(soft));
  const es::SurfaceSignals s = SurfaceOf(run.result);
  const es::BitEstimate e = es::EstimateBit(es::EstimatorModelFromCase(doc), s, {});
  ASSERT_FALSE(e.notes.empty());
  EXPECT_NE(e.notes.front().find("soft drive"), std::string::npos) << e.notes.front();
  const std::vector<double> bit = Rad(run.result.channel("bit_rpm").values);
  const es::SeriesError speed = es::CompareSeries(e.time_s, e.bit_speed_rad_s, bit, 15, 60);
  const es::StuckScore stuck = es::ScoreStuck(e.time_s, e.bit_speed_rad_s, e.stuck, bit, e.stuck_threshold_rad_s, 15, 60);
  EXPECT_GT(stuck.measured_stuck, 50u);  // it does stick (101 samples)
  // Measured: 5.72 rpm (9.5 % of the mean), stuck F1 0.896; with a quadratic's slope over +-4 J_b / Z as before,
  // 6.35 rpm (10.6 %) and 0.788.
  EXPECT_LT(speed.rms, 0.1 * speed.measured_mean) << "RMS " << speed.rms / kRadPerSecondPerRpm << " rpm";
  EXPECT_GT(stuck.f1, 0.85);
}

// The same soft drive, now known to the case (as a diagnosis fits it: kp 376 N m s/rad on the 2500 kg m^2 top). Its
// J / kp, 6.6 s, is no short lag against the string's 0.75-s travel time, so the motor torque advanced by it is not the
// string's: the top inertia's torque is read from the speed's slope, as for a drive the case does not know. (Read as a
// stiff drive's lag, dev rec05's diagnosed case, kp 95, gave 102 rpm RMS and stuck F1 0.06 against 5.3 and 0.894.)
TEST(WaveStringEstimate, ADriveWhoseLagIsLongerThanTheTravelTimeIsReadAsSoft) {
  nlohmann::json soft = drillwave::testing::LoadCase("baseline-60rpm");
  soft["simulation"]["duration_s"] = 60;
  soft["statistics"]["window_s"] = {0, 60};
  soft["model"]["top"]["kp_Nms_per_rad"] = 376.0;
  soft["model"]["top"]["ki_Nm_per_rad"] = 8309.0;
  const auto run = drillwave::cases::RunCase(drillwave::cases::ParseCase(soft));
  const es::BitEstimate e = es::EstimateBit(es::EstimatorModelFromCase(soft), SurfaceOf(run.result), {});
  ASSERT_FALSE(e.notes.empty());
  EXPECT_NE(e.notes.front().find("not short against the string's travel time"), std::string::npos) << e.notes.front();
  const std::vector<double> bit = Rad(run.result.channel("bit_rpm").values);
  const es::SeriesError speed = es::CompareSeries(e.time_s, e.bit_speed_rad_s, bit, 15, 60);
  const es::StuckScore stuck = es::ScoreStuck(e.time_s, e.bit_speed_rad_s, e.stuck, bit, e.stuck_threshold_rad_s, 15, 60);
  EXPECT_LT(speed.rms, 0.1 * speed.measured_mean) << "RMS " << speed.rms / kRadPerSecondPerRpm << " rpm";
  EXPECT_GT(stuck.f1, 0.85);
}

// A two-mass pendulum as the rig's diagnosis fits it (droop drive, Stribeck friction), in stick-slip.
nlohmann::json RigLikeCase() {
  return nlohmann::json::parse(R"({
    "name": "rig-like", "model": {"kind": "two_mass",
      "string": {"stiffness_Nm_per_rad": 2.9, "damping_Nms_per_rad": 0.06},
      "top": {"type": "top_drive", "inertia_kgm2": 2.2e-4, "kp_Nms_per_rad": 0.6, "ki_Nm_per_rad": 0,
              "speed_rad_s": 12.33},
      "bit": {"inertia_kgm2": 0.0026, "nominal_weight_on_bit_N": 570,
              "friction": {"law": "stribeck", "W_N": 570, "R_m": 1, "mu_c": 0.00243, "mu_s": 0.00513,
                           "gamma_b": 1, "nu_f_rad_s": 5.26, "c_b_Nms_per_rad": 0}}},
    "simulation": {"duration_s": 10, "output_interval_s": 0.001, "abs_tol": 1e-8, "rel_tol": 1e-8},
    "statistics": {"window_s": [0, 10]}})");
}

TEST(LumpedObserver, ConvergesFromAWrongStartToTheSimulatedBit) {
  const nlohmann::json doc = RigLikeCase();
  const auto run = drillwave::cases::RunCase(drillwave::cases::ParseCase(doc));
  es::SurfaceSignals s;
  s.time_s = run.result.time_s;
  s.top_speed_rad_s = Rad(run.result.channel("top_rpm").values);
  const std::vector<double> bit = Rad(run.result.channel("bit_rpm").values);
  const es::EstimatorModel model = es::EstimatorModelFromCase(doc);
  es::LumpedObserverOptions o;
  o.initial_bit_speed_rad_s = bit[0] + 10;  // 95 rpm off
  o.initial_twist_rad = 0.5;
  o.smoothing_lag_s = 0;  // the filter alone, so that the start's error shows
  const es::BitEstimate e = es::EstimateLumped(model.lumped, s, 0.05 * 12.33, o);
  EXPECT_GT(std::abs(e.bit_speed_rad_s[1] - bit[1]), 5.0);  // it does start wrong
  const es::SeriesError late = es::CompareSeries(e.time_s, e.bit_speed_rad_s, bit, 2, 10);
  // Noise-free top speed and the exact model: what is left is the filter's discretisation (explicit sub-steps of the
  // stick-slip switching against the solver's located events): within 2 % of the mean bit speed.
  EXPECT_LT(late.rms, 0.02 * late.measured_mean) << "RMS " << late.rms / kRadPerSecondPerRpm << " rpm";
  int stuck_samples = 0;
  for (double w : bit) stuck_samples += std::abs(w) < 0.05 * 12.33;
  EXPECT_GT(stuck_samples, 100);  // the run sticks
  const es::StuckScore stuck = es::ScoreStuck(e.time_s, e.bit_speed_rad_s, e.stuck, bit, 0.05 * 12.33, 2, 10);
  EXPECT_GT(stuck.f1, 0.8);
}

// The rig's pendulum as `drillwave diagnose json-cases/ufrj-rig.json ... --fit-window 2,20` fits it (fitted-case.json,
// rounded): a droop drive (kp 0.2204 N m s/rad towards 18.30 rad/s, no integral action), Stribeck friction (static
// 3.447 N m, kinetic 1.888 N m at 570 N).
nlohmann::json FittedRigCase(double duration_s) {
  nlohmann::json doc = nlohmann::json::parse(R"({
    "name": "ufrj-rig-fitted", "model": {"kind": "two_mass",
      "string": {"stiffness_Nm_per_rad": 2.9, "damping_Nms_per_rad": 0.06},
      "top": {"type": "top_drive", "inertia_kgm2": 0.001, "kp_Nms_per_rad": 0.2204, "ki_Nm_per_rad": 0,
              "speed_rad_s": 18.30, "damping_Nms_per_rad": 0},
      "bit": {"inertia_kgm2": 0.0026, "nominal_weight_on_bit_N": 570, "damping_Nms_per_rad": 0,
              "friction": {"law": "stribeck", "W_N": 570, "R_m": 1, "mu_c": 0.0033115, "mu_s": 0.0060467,
                           "gamma_b": 1, "nu_f_rad_s": 5, "c_b_Nms_per_rad": 0}}},
    "simulation": {"output_interval_s": 0.001, "abs_tol": 1e-8, "rel_tol": 1e-8}})");
  doc["simulation"]["duration_s"] = duration_s;
  doc["statistics"]["window_s"] = {0, duration_s};
  return doc;
}

struct OwnRun {
  es::SurfaceSignals surface;
  std::vector<double> bit_speed_rad_s;
};

OwnRun RunTwoMass(const nlohmann::json& doc) {
  const auto run = drillwave::cases::RunCase(drillwave::cases::ParseCase(doc));
  OwnRun r;
  r.surface.time_s = run.result.time_s;
  r.surface.top_speed_rad_s = Rad(run.result.channel("top_rpm").values);
  r.bit_speed_rad_s = Rad(run.result.channel("bit_rpm").values);
  return r;
}

// drillwave's own run of the fitted rig sticks and slips; the hybrid observer, started 95 rpm and 0.5 rad (1.45 N m)
// wrong, finds its bit, the stuck phases included, from the top speed alone.
TEST(HybridObserver, RecoversTheStuckPhasesOfDrillwavesOwnRigRunFromAWrongStart) {
  const nlohmann::json doc = FittedRigCase(12);
  const OwnRun run = RunTwoMass(doc);
  const es::EstimatorModel model = es::EstimatorModelFromCase(doc);
  ASSERT_TRUE(es::HasInvertibleDrive(model.lumped));
  const double threshold = 0.05 * 8.0;  // about 5 % of the run's median top speed, the rule of EstimateBit
  es::HybridObserverOptions o;
  o.initial_bit_speed_rad_s = run.bit_speed_rad_s[0] + 10;
  o.initial_twist_rad = 0.5;
  const es::BitEstimate e = es::EstimateHybrid(model.lumped, run.surface, threshold, o);
  const es::SeriesError start = es::CompareSeries(e.time_s, e.bit_speed_rad_s, run.bit_speed_rad_s, 0, 0.05);
  const es::SeriesError late = es::CompareSeries(e.time_s, e.bit_speed_rad_s, run.bit_speed_rad_s, 2, 12);
  EXPECT_GT(start.rms, 2.0) << "it does start wrong";
  // Exact top speed and model: what is left is the low-pass (three boxes of 23 ms round the stops' corners where
  // the regime does not take over) and the release, which waits for the inverted speed to pass the stuck threshold.
  // Measured: 3.1 rpm, 4.8 % of the mean; F1 0.907 (21 % of the samples stuck).
  EXPECT_LT(late.rms, 0.06 * late.measured_mean) << "RMS " << late.rms / kRadPerSecondPerRpm << " rpm of " << late.measured_mean / kRadPerSecondPerRpm;
  const es::StuckScore stuck = es::ScoreStuck(e.time_s, e.bit_speed_rad_s, e.stuck, run.bit_speed_rad_s, threshold, 2, 12);
  EXPECT_GT(stuck.measured_stuck, 1000u) << "the run sticks";
  EXPECT_GT(stuck.f1, 0.88) << "precision " << stuck.precision << " recall " << stuck.recall;
}

// The real rig from its top speed alone (issue 34's target: <= 15 rpm, F1 >= 0.8 on 20-30 s). The figures measured
// with these settings, chosen on 0-20 s (README, docs/results.md), with a margin.
TEST(UfrjRig, TopSpeedAloneGivesTheBitOnTheLast10Seconds) {
  const std::string file = std::string(DRILLWAVE_SHARED_DIR) + "/recordings/ufrj-rig/rig-0-30s.csv";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " is absent (the rig's recording is not in the repository)";
  const auto rec = drillwave::diagnosis::LoadRecording(file);
  const es::SurfaceSignals s = es::SignalsFromRecording(rec, es::ParseSurfaceChannels("top_rpm", rec));
  const es::BitEstimate e = es::EstimateBit(es::EstimatorModelFromCase(FittedRigCase(30)), s, {});
  const nlohmann::json late = es::EstimateSummary(rec, e, {20, 30})["errors"];
  const nlohmann::json fit = es::EstimateSummary(rec, e, {2, 20})["errors"];
  EXPECT_LT(late["bit_rpm"]["rms"].get<double>(), 12.5) << late.dump();        // measured 10.5 rpm
  EXPECT_GT(late["stuck"]["f1"].get<double>(), 0.85) << late.dump();           // measured 0.89
  EXPECT_LT(fit["bit_rpm"]["rms"].get<double>(), 11.5) << fit.dump();          // measured 9.7 rpm
  EXPECT_GT(fit["stuck"]["f1"].get<double>(), 0.70) << fit.dump();             // measured 0.75
  EXPECT_LT(e.latency_s, 0.4);
}

// A recording written in pieces (lines cut anywhere) and read as it grows: every estimate is given out within the
// latency and a stretch of it, and equals the batch estimate (the observer forgets the sliding window's start within
// its warm-up: measured 4e-12 rad/s RMS apart).
TEST(Follow, AFileWrittenInPiecesGivesTheBatchEstimateWithinTheLatency) {
  const OwnRun run = RunTwoMass(FittedRigCase(12));
  std::ostringstream text;
  text << "time_s,top_rpm,bit_rpm\n";
  text.precision(12);
  for (std::size_t i = 0; i < run.surface.time_s.size(); ++i)
    text << run.surface.time_s[i] << "," << run.surface.top_speed_rad_s[i] / kRadPerSecondPerRpm << ","
         << run.bit_speed_rad_s[i] / kRadPerSecondPerRpm << "\n";
  const std::string all = text.str();
  const std::string path = (std::filesystem::temp_directory_path() / "drillwave-follow-test.csv").string();
  std::ofstream(path, std::ios::trunc).close();
  es::GrowingCsv csv(path);
  const es::EstimatorModel model = es::EstimatorModelFromCase(FittedRigCase(12));
  std::unique_ptr<es::LiveEstimator> live;
  std::vector<es::EstimateRow> given;
  std::ofstream writer(path, std::ios::app);
  double worst_wait = 0;
  for (std::size_t at = 0, piece = 0; at < all.size(); ++piece) {
    const std::size_t length = std::min(all.size() - at, std::size_t{4000 + 997 * (piece % 7)});  // cuts mid-line
    writer << all.substr(at, length) << std::flush;
    at += length;
    std::vector<std::vector<double>> rows;
    EXPECT_TRUE(csv.Read(rows, 0));
    if (!live && !csv.names().empty()) {
      drillwave::diagnosis::Recording header;
      header.names = csv.names();
      live = std::make_unique<es::LiveEstimator>(model, es::EstimateOptions{}, csv.names(),
                                                 es::ParseSurfaceChannels("top_rpm", header));
    }
    if (!live || rows.empty()) continue;
    const double newest = rows.back()[0];
    for (const es::EstimateRow& r : live->Push(rows)) given.push_back(r);
    if (!given.empty() && live->latency_s() > 0) worst_wait = std::max(worst_wait, newest - given.back().time_s);
  }
  const std::size_t before_end = given.size();
  for (const es::EstimateRow& r : live->Finish()) given.push_back(r);
  std::remove(path.c_str());
  ASSERT_EQ(given.size(), run.surface.time_s.size());
  EXPECT_GT(before_end, given.size() - 600) << "all but the last latency and stretch given out while reading";
  // A piece is up to 10 000 characters, about 0.2 s of this recording: the newest row given out is at most the
  // latency, a stretch (0.1 s) and a piece behind the newest row read.
  EXPECT_LT(worst_wait, live->latency_s() + 0.1 + 0.25);
  es::EstimateOptions fixed;
  fixed.stuck_threshold_rad_s = live->stuck_threshold_rad_s();
  const es::BitEstimate batch = es::EstimateBit(model, run.surface, fixed);
  double sum2 = 0;
  std::size_t count = 0, agree = 0;
  for (std::size_t i = 0; i < given.size(); ++i) {
    EXPECT_DOUBLE_EQ(given[i].time_s, run.surface.time_s[i]);
    if (!std::isfinite(batch.bit_speed_rad_s[i])) continue;
    sum2 += std::pow(given[i].bit_speed_rad_s - batch.bit_speed_rad_s[i], 2);
    agree += given[i].stuck == (batch.stuck[i] != 0);
    ++count;
  }
  ASSERT_GT(count, 11000u);
  EXPECT_LT(std::sqrt(sum2 / static_cast<double>(count)), 1e-3) << "live against batch [rad/s]";
  EXPECT_EQ(agree, count);
}

// report.html reads estimate.json's content: its errors, the delay found, the events (counted, summed, the longest)
// and the severity windows; a recording without downhole channels says there is nothing to score against.
TEST(EstimateReport, ShowsTheSummarysErrorsEventsAndSeverity) {
  const nlohmann::json summary = {
      {"method", "downward continuation"},
      {"latency_s", 0.75},
      {"stuck_rule", "below 5 %"},
      {"stuck_threshold_rpm", 3.5},
      {"notes", {"a note <with> markup"}},
      {"stuck_events", {{{"stick_begin_s", 2.0}, {"stick_end_s", 3.25}}, {{"stick_begin_s", 7.0}, {"stick_end_s", 7.5}}}},
      {"severity_definition", "(max - min) / (2 mean)"},
      {"severity_windows", {{{"begin_s", 0.0}, {"end_s", 5.0}, {"severity", 1.25}, {"stuck_fraction", 0.25}}}},
      {"errors",
       {{"bit_rpm", {{"channel", "bit_rpm"}, {"rms", 6.125}, {"rms_percent_of_mean", 8.61}, {"bias", -0.5},
                     {"measured_mean", 71.2}, {"samples", 9000}}},
        {"stuck", {{"precision", 0.9}, {"recall", 0.8}, {"f1", 0.847}, {"measured_stuck_fraction", 0.2}}},
        {"bit_rpm_at_downhole_delay", {{"delay_s", 2.1}, {"rms", 16.3}, {"rms_percent_of_mean", 27.1}, {"stuck_f1", 0.69}}},
        {"window_s", {0.0, 110.0}}}}};
  drillwave::io::Figure figure;
  figure.title = "estimate";
  figure.panels.push_back({"bit speed [rpm]", {{"estimate", {0, 1, 2}, {60, 61, 62}}}});
  std::ostringstream page;
  es::WriteEstimateHtml("rec04", summary, figure, page);
  const std::string html = page.str();
  for (const char* text : {"rec04", "6.125 rpm", "8.61 %", "F1 0.847", "by 2.1 s", "16.3 rpm", "2 stuck episodes",
                           "1.75 s stuck in all", "the longest 1.25 s", "<td>1.25</td>", "&lt;with&gt;", "<svg"})
    EXPECT_NE(html.find(text), std::string::npos) << text;
  nlohmann::json bare = summary;
  bare["errors"] = nlohmann::json::object();
  bare["stuck_events"] = nlohmann::json::array();
  std::ostringstream plain;
  es::WriteEstimateHtml("rig", bare, figure, plain);
  EXPECT_NE(plain.str().find("holds no downhole channel"), std::string::npos);
  EXPECT_NE(plain.str().find("never sticks"), std::string::npos);
}

TEST(EstimatorModel, RefusesKindsWithoutAnEstimatorNamingTheField) {
  const nlohmann::json doc = {{"model", {{"kind", "two_disc"}}}};
  try {
    es::EstimatorModelFromCase(doc);
    FAIL() << "no error";
  } catch (const drillwave::InputError& e) {
    EXPECT_EQ(e.json_path(), "/model/kind");
  }
}

TEST(SurfaceChannels, RefusesDownholeChannelsAndUnknownUnits) {
  drillwave::diagnosis::Recording r;
  r.names = {"top_rpm", "bit_rpm", "top_torque_kNm", "mystery"};
  r.channels.assign(4, {1, 2, 3});
  r.time_s = {0, 1, 2};
  for (const std::string bad : {"top_rpm,bit_rpm", "top_rpm,mystery", "top_torque_kNm", "top_rpm,top_rpm", "nope"}) {
    try {
      es::ParseSurfaceChannels(bad, r);
      FAIL() << bad;
    } catch (const drillwave::InputError& e) {
      SUCCEED();
    }
  }
  const es::SurfaceChannels c = es::ParseSurfaceChannels("top_rpm,top_torque_kNm", r);
  EXPECT_EQ(c.top_torque, "top_torque_kNm");
}

// The independent simulator's recording rec03 (stick-slip at 105 rpm), surface channels only.
// The estimate of a synthetic recording of ../shared from its surface channels, with the baseline case at its sidecar's
// operating point, as `drillwave estimate` makes it; null where the recording is absent.
nlohmann::json EstimateSynthetic(const std::string& set, const std::string& name) {
  const std::string dir = std::string(DRILLWAVE_SHARED_DIR) + "/recordings/" + set + "/";
  if (!std::filesystem::exists(dir + name + ".csv")) return nullptr;
  nlohmann::json doc = drillwave::testing::LoadCase("baseline-60rpm");
  const nlohmann::json sidecar = drillwave::io::LoadJsonFile(dir + name + ".json");
  doc = drillwave::diagnosis::CaseFromSidecar(sidecar, doc, drillwave::diagnosis::kSidecarWarmupS);
  const auto rec = drillwave::diagnosis::LoadRecording(dir + name + ".csv");
  const es::SurfaceSignals s =
      es::SignalsFromRecording(rec, es::ParseSurfaceChannels("top_rpm,top_torque_kNm,hookload_kN", rec));
  const es::BitEstimate e = es::EstimateBit(
      es::EstimatorModelFromCase(doc, 1000 * sidecar.at("hookload_setpoint_kN").get<double>()), s, {});
  return es::EstimateSummary(rec, e, {});
}

TEST(SyntheticRecordings, Rec03MeetsTheIssuesTargets) {
  const nlohmann::json j = EstimateSynthetic("synthetic", "rec03");
  if (j.is_null()) GTEST_SKIP() << "../shared/recordings/synthetic/rec03.csv is absent";
  EXPECT_LT(j["errors"]["bit_rpm"]["rms_percent_of_mean"].get<double>(), 10);
  EXPECT_GT(j["errors"]["stuck"]["f1"].get<double>(), 0.9);
}

// Dev rec05 hides a soft drive. The independent simulator's string is not drillwave's, and around each stop the
// estimate swings to -4 to -6 rpm while the recorded bit is held (0 +- 1 rpm): counted as turning back, 583 of its
// 3 047 stuck samples were missed, 408 of them in the first and last tenth of their stick (F1 0.894, precision 0.9996).
TEST(SyntheticRecordings, Rec05sStopsAreStuckThoughTheEstimateSwingsBelowZero) {
  const nlohmann::json j = EstimateSynthetic("synthetic", "rec05");
  if (j.is_null()) GTEST_SKIP() << "../shared/recordings/synthetic/rec05.csv is absent";
  const nlohmann::json& stuck = j["errors"]["stuck"];
  std::printf("[ measured ] dev rec05: stuck F1 %.3f (precision %.4f, recall %.3f)\n", stuck["f1"].get<double>(),
              stuck["precision"].get<double>(), stuck["recall"].get<double>());
  EXPECT_GT(stuck["f1"].get<double>(), 0.9);
  EXPECT_GT(stuck["precision"].get<double>(), 0.99);  // what is flagged is stuck: the rule adds no false stops
}

// Train rec18 hides a soft drive (and an unbalance): before the top inertia's torque came from a quartic's slope over
// the travel time, a quadratic's over +-4 J_b / Z flattened it: bit-speed RMS 19.3 rpm (16 %), stuck F1 0.25.
TEST(SyntheticRecordings, TrainRec18sSoftDriveMeetsTheIssuesTargets) {
  const nlohmann::json j = EstimateSynthetic("synthetic-train", "rec18");
  if (j.is_null()) GTEST_SKIP() << "../shared/recordings/synthetic-train/rec18.csv is absent";
  EXPECT_LT(j["errors"]["bit_rpm"]["rms_percent_of_mean"].get<double>(), 10);  // measured 7.5 %
  EXPECT_GT(j["errors"]["stuck"]["f1"].get<double>(), 0.85);                   // measured 0.912
}

}  // namespace
