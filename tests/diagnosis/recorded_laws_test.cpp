// What the diagnosis loop reads off a recording before any fit: the top drive's law (drive_law.hpp) — a PI law's gains
// from noisy speed error and torque, none where the speed error is noise, the law of drillwave's own soft-drive run from
// its channels — and the telemetry delay of its bit speed behind the virtual sensor's estimate; and the proposals that
// start from them.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>
#include <string>
#include <vector>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/diagnosis/drive_law.hpp"
#include "drillwave/diagnosis/effects.hpp"
#include "json_case.hpp"
#include "prepared_recording.hpp"

namespace drillwave::diagnosis {
namespace {

// A stick-slip-like speed error: a 0.3-Hz oscillation with its harmonics (a cycle of sticking and slipping is far from
// a sine), sampled at 100 Hz for 60 s.
struct Signals {
  std::vector<double> time_s, error, torque;
};
Signals PiLawSignals(double kp, double ki, double error_noise, double torque_noise, unsigned seed) {
  Signals s;
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  const double dt = 0.01, w = 2 * kPi * 0.3;
  double integral = 0;
  for (int i = 0; i <= 6000; ++i) {
    const double t = i * dt;
    const double e = std::sin(w * t) + 0.4 * std::sin(2 * w * t + 0.5) + 0.2 * std::sin(3 * w * t + 1.0);
    integral += e * dt;
    s.time_s.push_back(t);
    s.error.push_back(e + error_noise * normal(rng));
    s.torque.push_back(5000 + kp * e + ki * integral + torque_noise * normal(rng));
  }
  return s;
}

TEST(DriveLaw, ReadsAPiLawsGainsAtTheTorquesOscillation) {
  const double kp = 400, ki = 5000;
  const Signals s = PiLawSignals(kp, ki, 0.1, 200, 3);
  const DriveLaw law = IdentifyDriveLaw(s.time_s, s.error, s.torque, 0, 60);
  std::printf("[ measured ] %.3g Hz, kp %.4g, ki %.4g, coherence %.4f over %d segments\n", law.frequency_hz,
              law.proportional, law.integral, law.coherence, law.segments);
  EXPECT_NEAR(law.frequency_hz, 0.3, 0.026);
  ASSERT_TRUE(law.Identified());
  EXPECT_NEAR(law.proportional, kp, 0.05 * std::hypot(kp, ki / (2 * kPi * 0.3)));
  EXPECT_NEAR(law.integral, ki, 0.05 * ki);
  EXPECT_NEAR(law.Stiffness(), std::hypot(kp, ki / (2 * kPi * 0.3)), 0.05 * law.Stiffness());
  EXPECT_LT(law.LogStiffnessStd(), 0.1);
}

// A motor's armature behind the PI, T' = (PI(e) - T) / tau: the law's phase reads the PI's less atan(w tau).
TEST(DriveLaw, ReadsAnArmaturesLagBehindThePiInThePhase) {
  const double kp = 400, ki = 5000, tau = 0.1;
  const Signals pi = PiLawSignals(kp, ki, 0.05, 0, 3);
  std::vector<double> lagged(pi.torque.size());
  lagged[0] = pi.torque[0];
  const double dt = pi.time_s[1] - pi.time_s[0];
  for (std::size_t i = 1; i < lagged.size(); ++i)  // exact for a torque linear over the step's end
    lagged[i] = lagged[i - 1] + (1 - std::exp(-dt / tau)) * (pi.torque[i] - lagged[i - 1]);
  const DriveLaw plain = IdentifyDriveLaw(pi.time_s, pi.error, pi.torque, 0, 60);
  const DriveLaw law = IdentifyDriveLaw(pi.time_s, pi.error, lagged, 0, 60);
  ASSERT_TRUE(law.Identified());
  const double w = 2 * kPi * law.frequency_hz;
  std::printf("[ measured ] phase %.2f deg without the armature, %.2f with it (PI %.2f, lag atan(w tau) %.2f)\n",
              plain.Phase() * 180 / kPi, law.Phase() * 180 / kPi, std::atan2(-ki / w, kp) * 180 / kPi,
              std::atan(w * tau) * 180 / kPi);
  EXPECT_NEAR(plain.Phase(), std::atan2(-ki / w, kp), 0.02);
  // The discrete lag is half a sample later than the continuous one: w dt / 2 = 0.5 degrees at 0.3 Hz.
  EXPECT_NEAR(plain.Phase() - law.Phase(), std::atan(w * tau), 0.02);
  EXPECT_LT(law.PhaseStd(), 0.05);
}

// A soft speed loop driving a DC motor: torque (1 + s tau) = PI(e) + K^2 / R e. Read at every coherent frequency of
// the stick-slip's lines, a PI behind a lag recovers tau, the loop's kp with the back-EMF damping added, and ki, and
// the F-test finds the lag; the same loop without the armature reads a PI and no lag.
TEST(DriveLaw, FitsAPiBehindAnArmatureAtEveryCoherentFrequency) {
  const double kp = 600, ki = 10000, back_emf = 20000, tau = 0.11;
  const Signals pi = PiLawSignals(kp + back_emf, ki, 0.05, 200, 11);
  std::vector<double> lagged(pi.torque.size());
  lagged[0] = pi.torque[0];
  const double dt = pi.time_s[1] - pi.time_s[0];
  for (std::size_t i = 1; i < lagged.size(); ++i)
    lagged[i] = lagged[i - 1] + (1 - std::exp(-dt / tau)) * (pi.torque[i] - lagged[i - 1]);
  const DriveLaw law = IdentifyDriveLaw(pi.time_s, pi.error, lagged, 0, 60);
  const LaggedPi fit = FitLaggedPi(law);
  std::printf("[ measured ] %d coherent bins: kp %.5g, ki %.5g, tau %.4g s, F %.3g, p %.2g\n", fit.bins,
              fit.proportional, fit.integral, fit.lag_s, fit.f_statistic, fit.p_value);
  ASSERT_GE(fit.bins, 3);
  EXPECT_NEAR(fit.lag_s, tau, 0.1 * tau);  // measured 0.105 s
  EXPECT_NEAR(fit.proportional, kp + back_emf, 0.05 * (kp + back_emf));
  EXPECT_NEAR(fit.integral, ki, 0.1 * ki);
  EXPECT_LT(fit.p_value, 1e-6);

  const LaggedPi plain = FitLaggedPi(IdentifyDriveLaw(pi.time_s, pi.error, pi.torque, 0, 60));
  std::printf("[ measured ] without the armature: tau %.4g s, F %.3g, p %.2g\n", plain.lag_s, plain.f_statistic,
              plain.p_value);
  EXPECT_GT(plain.p_value, 0.01);
  EXPECT_LT(plain.lag_s, 0.01);
  EXPECT_EQ(FitLaggedPi(DriveLaw{}).bins, 0);  // nothing read, nothing fitted
}

// A stiff drive holds the top's speed within the speed channel's noise: the torque oscillates, the speed error is
// noise, and no law is claimed.
TEST(DriveLaw, ASpeedErrorOfNoiseGivesNoLaw) {
  Signals s = PiLawSignals(1e5, 2e5, 0, 200, 5);
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (double& e : s.error) e = 0.16 * normal(rng);
  const DriveLaw law = IdentifyDriveLaw(s.time_s, s.error, s.torque, 0, 60);
  EXPECT_LT(law.coherence, 0.5);
  EXPECT_FALSE(law.Identified());
}

TEST(DriveLaw, AWindowShorterThanTwoSegmentsOrUnevenSeriesGiveNone) {
  const Signals s = PiLawSignals(400, 5000, 0.1, 200, 3);
  EXPECT_EQ(IdentifyDriveLaw(s.time_s, s.error, s.torque, 0, 25).segments, 0);
  std::vector<double> shorter = s.torque;
  shorter.pop_back();
  EXPECT_EQ(IdentifyDriveLaw(s.time_s, s.error, shorter, 0, 60).segments, 0);
  EXPECT_FALSE(DriveLaw{}.Identified());
}

// drillwave's coupled string behind a soft PI (BASELINE.md's string at 60 rpm, kp 400 N m s/rad, ki 5000 N m/rad).
nlohmann::json SoftDriveString() {
  nlohmann::json doc = testing::LoadCase("baseline-60rpm");
  doc["model"]["top"]["kp_Nms_per_rad"] = 400;
  doc["model"]["top"]["ki_Nm_per_rad"] = 5000;
  doc["model"]["top"]["speed_rad_s"] = {{"knots", {{0, 2 * kPi}, {90, 2 * kPi}}}};
  doc["simulation"]["duration_s"] = 90;
  return doc;
}

// Its top speed (with 1 % noise) and drive torque as a recording would have them: 100 Hz from 30 s of the run on,
// the torque in kN m, the recording's clock starting at the run's 30 s.
Recording RecordedAsTheSynthetics(const cases::RunResult& run) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  Recording r;
  r.names = {"top_rpm", "top_torque_kNm"};
  r.channels.resize(2);
  for (std::size_t i = 0; i < run.time_s.size(); ++i) {
    if (run.time_s[i] < 30 || std::abs(std::remainder(run.time_s[i], 0.01)) > 1e-9) continue;
    r.time_s.push_back(run.time_s[i] - 30);
    r.channels[0].push_back(run.channel("top_rpm").values[i] + 0.6 * normal(rng));
    r.channels[1].push_back(1e-3 * run.channel("top_torque_Nm").values[i]);
  }
  r.sample_interval_s = 0.01;
  return r;
}

// The drive's gains come back from its channels; the law is the drive torque's, not the string's (which adds the
// top's inertia, J_td w' = 2500 w' N m, and would read ki about 2500 w^2 lower).
TEST(DriveLaw, ReadsTheSoftDriveOfAStringRunFromItsChannels) {
  const nlohmann::json doc = SoftDriveString();
  const Recording r = RecordedAsTheSynthetics(cases::RunCase(cases::ParseCase(doc)).result);
  ASSERT_GT(r.time_s.size(), 5000u);
  std::vector<double> error;
  for (double rpm : r.channels[0]) error.push_back(2 * kPi - rpm * kRadPerSecondPerRpm);
  std::vector<double> torque_Nm;
  for (double kNm : r.channels[1]) torque_Nm.push_back(1e3 * kNm);
  const DriveLaw law = IdentifyDriveLaw(r.time_s, error, torque_Nm, 0, 60);
  std::printf("[ measured ] string run: %.3g Hz, kp %.4g, ki %.4g, coherence %.4f\n", law.frequency_hz,
              law.proportional, law.integral, law.coherence);
  ASSERT_TRUE(law.Identified());
  const double w = 2 * kPi * law.frequency_hz, stiffness = std::hypot(400.0, 5000 / w);
  EXPECT_NEAR(law.Stiffness(), stiffness, 0.1 * stiffness);
  EXPECT_NEAR(law.integral, 5000, 500);

  // The diagnosis loop reads the same law on its fit window, through its channel maps and the model's time offset.
  LoopOptions o;
  o.maps = {ParseChannelMap("top_rpm=top_rpm"), ParseChannelMap("top_torque_kNm=top_torque_Nm*0.001")};
  o.model_time_offset_s = 30;
  o.fit_begin_s = 0, o.fit_end_s = 30, o.held_out_begin_s = 30, o.held_out_end_s = 60;
  const DriveLaw read = loop_internal::PrepareRecording(doc, r, o).fit.drive;
  ASSERT_TRUE(read.Identified()) << read.coherence;
  EXPECT_NEAR(read.Stiffness(), stiffness, 0.1 * stiffness);
}

// The soft drive's proposal reads the recorded law: where it is identified and softer than the case's PI, its gains are
// the fit's first values and its distance in standard deviations the evidence; a law like the case's, or one not
// identified, leaves the SoftSpeed tuning (kp = Z, ki = J_td w1^2) and no evidence from the law; the case's own law
// read off the recording refutes a soft drive.
// The proposal `name` of baseline-60rpm for a recording whose drive law reads `law`.
Effect ProposalFor(const DriveLaw& law, const std::string& name) {
  const nlohmann::json doc = testing::LoadCase("baseline-60rpm");
  FeatureSet recording;
  recording.drive = law;
  for (const Effect& e : ProposeEffects(doc, FeatureSet{}, recording))
    if (e.name == name) return e;
  ADD_FAILURE() << "no " << name << " proposed";
  return {};
}
Effect SoftDriveProposal(const DriveLaw& law) { return ProposalFor(law, "soft_topdrive"); }

TEST(SoftDriveProposal, StartsFromTheRecordedLawWhereItIsSofterThanTheCases) {
  DriveLaw soft{0.3, 400, 5000, 0.98, 4, {}};
  const Effect e = SoftDriveProposal(soft);
  ASSERT_EQ(e.parameters.size(), 2u);
  EXPECT_DOUBLE_EQ(e.parameters[0].start, 400);
  EXPECT_DOUBLE_EQ(e.parameters[1].start, 5000);
  EXPECT_TRUE(e.Proposed()) << e.strength;
  EXPECT_NE(e.evidence.find("read off the recording"), std::string::npos) << e.evidence;
  EXPECT_TRUE(e.refuted.empty());

  // BASELINE.md's pipe and top: Z = 299 N m s/rad, w1 = pi c / 2 L at 2000 m, J_td = 2500 kg m^2.
  const double c = std::sqrt(80769e6 / 7850), w1 = kPi * c / (2 * 2000);
  for (const DriveLaw& other : {DriveLaw{0.3, 1e5, 2e5, 0.98, 4, {}}, DriveLaw{0.3, 400, 5000, 0.5, 4, {}}}) {
    const Effect plain = SoftDriveProposal(other);
    EXPECT_NEAR(plain.parameters[0].start, 299.1, 0.5);
    EXPECT_NEAR(plain.parameters[1].start, 2500 * w1 * w1, 1e-6 * 2500 * w1 * w1);
    EXPECT_EQ(plain.strength, 0);
  }
  // The case's own law read off the recording measures the drive: a soft one is refuted, not fitted; a law not read
  // (coherence 0.5) refutes nothing.
  EXPECT_FALSE(SoftDriveProposal(DriveLaw{0.3, 1e5, 2e5, 0.98, 4, {}}).refuted.empty());
  EXPECT_TRUE(SoftDriveProposal(DriveLaw{0.3, 400, 5000, 0.5, 4, {}}).refuted.empty());
}

// The DC motor's proposal reads the lag of the recorded law behind the case's PI: where the law is the case's drive
// but later by a lag, the lag in standard deviations is the evidence and tan(lag) / w the first armature time constant;
// the case's own law, a soft drive's law or one not identified give no evidence from the law.
Effect DcMotorProposal(const DriveLaw& law) { return ProposalFor(law, "dc_motor"); }

TEST(DcMotorProposal, StartsFromTheLagOfTheRecordedLawBehindTheCasesPi) {
  const nlohmann::json doc = testing::LoadCase("baseline-60rpm");
  const double kp = doc["model"]["top"]["kp_Nms_per_rad"], ki = doc["model"]["top"]["ki_Nm_per_rad"];
  const double f = 0.3, w = 2 * kPi * f, tau = 0.08;
  const std::complex<double> h = std::complex<double>(kp, -ki / w) / std::complex<double>(1, w * tau);
  const Effect lagged = DcMotorProposal(DriveLaw{f, h.real(), -w * h.imag(), 0.99, 4, {}});  // 4.2 std
  ASSERT_EQ(lagged.parameters.size(), 2u);
  EXPECT_NEAR(lagged.parameters[0].start, tau, 1e-9);
  EXPECT_TRUE(lagged.Proposed()) << lagged.strength;
  EXPECT_NE(lagged.evidence.find("lags the case's PI"), std::string::npos) << lagged.evidence;
  for (const DriveLaw& other : {DriveLaw{f, kp, ki, 0.98, 4, {}}, DriveLaw{f, 400, 5000, 0.98, 4, {}},
                                DriveLaw{f, h.real(), -w * h.imag(), 0.5, 4, {}}}) {
    const Effect plain = DcMotorProposal(other);
    EXPECT_DOUBLE_EQ(plain.parameters[0].start, 0.1);
    EXPECT_EQ(plain.strength, 0);
  }
}

// BASELINE.md's string sticking and slipping at 60 rpm, recorded from its 30 s on at 100 Hz with its bit speed late by
// `delay_s` (telemetry), prepared as the loop prepares a recording.
loop_internal::PreparedRecording PreparedWithDelayedBit(double delay_s, nlohmann::json* case_document) {
  nlohmann::json doc = testing::LoadCase("baseline-60rpm");
  doc["model"]["top"]["speed_rad_s"] = {{"knots", {{0, 2 * kPi}, {100, 2 * kPi}}}};
  doc["simulation"]["duration_s"] = 100;
  const cases::RunResult run = cases::RunCase(cases::ParseCase(doc)).result;
  Recording r;
  r.names = {"top_rpm", "top_torque_kNm", "bit_rpm"};
  r.channels.resize(3);
  const auto late = static_cast<std::size_t>(std::lround(delay_s / run.time_s[1]));
  for (std::size_t i = late; i < run.time_s.size(); ++i) {
    if (run.time_s[i] < 30 || std::abs(std::remainder(run.time_s[i], 0.01)) > 1e-9) continue;
    r.time_s.push_back(run.time_s[i] - 30);
    r.channels[0].push_back(run.channel("top_rpm").values[i]);
    r.channels[1].push_back(1e-3 * run.channel("top_torque_Nm").values[i]);
    r.channels[2].push_back(run.channel("bit_rpm").values[i - late]);
  }
  r.sample_interval_s = 0.01;
  LoopOptions o;
  o.maps = {ParseChannelMap("top_rpm=top_rpm"), ParseChannelMap("top_torque_kNm=top_torque_Nm*0.001"),
            ParseChannelMap("bit_rpm=bit_rpm")};
  o.model_time_offset_s = 30;
  o.fit_begin_s = 5, o.fit_end_s = 37.5, o.held_out_begin_s = 37.5, o.held_out_end_s = 70;
  *case_document = doc;
  return loop_internal::PrepareRecording(doc, r, o);
}

// The bit speed 3 s late reads 3 s late, and the telemetry delay's fit starts there; on time it reads no delay.
TEST(TelemetryLag, TheLoopReadsTheBitSpeedsDelayBehindTheVirtualSensor) {
  nlohmann::json doc;
  const loop_internal::PreparedRecording late = PreparedWithDelayedBit(3.0, &doc);
  const estimation::TelemetryLag& lag = late.fit.telemetry;
  std::printf("[ measured ] lag %.3f s, correlation %.4f (%.4f without delay)\n", lag.lag_s, lag.correlation,
              lag.correlation_at_zero);
  ASSERT_TRUE(lag.found);
  EXPECT_NEAR(lag.lag_s, 3.0, 0.015);
  for (const Effect& e : ProposeEffects(doc, FeatureSet{}, late.fit))
    if (e.name == "sensor_delay") {
      EXPECT_NEAR(e.parameters[0].start, lag.lag_s, 1e-12);
      EXPECT_TRUE(e.Proposed());
    }
  const loop_internal::PreparedRecording on_time = PreparedWithDelayedBit(0.0, &doc);
  EXPECT_FALSE(on_time.fit.telemetry.found) << on_time.fit.telemetry.lag_s;
}

// Behind a soft speed loop the law is not the case's PI, so no lag behind it can be read at one frequency; at several,
// the PI behind a lag (FitLaggedPi) is the proposal's evidence and its lag the first armature time constant.
TEST(DcMotorProposal, ReadsAnArmatureBehindASoftLoopAtSeveralFrequencies) {
  const double p = 20600, i = 10000, tau = 0.12;
  DriveLaw law{0.3, 0, 0, 0.98, 4, {}};
  for (int k = 1; k <= 8; ++k) {
    const double f = 0.1 * k, w = 2 * kPi * f;
    const double scatter = 1 + 0.01 * std::sin(3.0 * k);  // 1 %, under the bins' own 2.5 % spread
    law.coherent.push_back({f, scatter * std::complex<double>(p, -i / w) / std::complex<double>(1, w * tau), 0.98});
  }
  const std::complex<double> peak = law.coherent[2].h;
  law.proportional = peak.real(), law.integral = -2 * kPi * 0.3 * peak.imag();
  const Effect e = DcMotorProposal(law);
  std::printf("[ measured ] %s (strength %.3g)\n", e.evidence.c_str(), e.strength);
  EXPECT_TRUE(e.Proposed()) << e.strength;
  EXPECT_NEAR(e.parameters[0].start, tau, 0.005);
  EXPECT_NE(e.evidence.find("frequencies"), std::string::npos) << e.evidence;
  for (DriveLawBin& b : law.coherent) b.h = std::complex<double>(p, -i / (2 * kPi * b.frequency_hz));  // no lag
  EXPECT_EQ(DcMotorProposal(law).strength, 0);
}

}  // namespace
}  // namespace drillwave::diagnosis
