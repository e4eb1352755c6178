// The wave-cancelling top (model::WaveCancellation, issue 35): the drive reads the up-going torsional wave w arriving
// at the top and turns it at v = w + d, which absorbs w and injects d = setpoint / 2 + k * integral(setpoint - v). Its
// reflection against the closed form and the stiff PI's, its fields in both kinds with a top, and the Saldivar string's
// stick-slip under it against the stiff PI's. Its linearization: tests/analysis/network_stability_test.cpp and
// axial_torsional_stability_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/waves/network_simulation.hpp"
#include "json_case.hpp"
#include "refused_path.hpp"

namespace drillwave::cases {
namespace {

using testing::RefusedPath;

const waves::Section kPipe = waves::Section::Torsional(1172, 79.3e9, 8000, 1.19e-5);  // the Saldivar pipe
constexpr double kCorner = 0.2;  // k of the slow speed loop [1/s]

// The torque pulse the bit sends up the string: a triangle of 1 kN m over [0.1, 0.3] s.
double Pulse(double t) { return 1000 * std::max(0.0, 1 - std::abs(t - 0.2) / 0.1); }

waves::Node TopAtRest(double kp, double ki) {
  waves::Node top;
  top.name = "top";
  top.drive = waves::Drive::kPiSpeedController;
  top.inertia = 500;
  top.pi = {kp, ki};
  top.setpoint = model::Schedule(0.0);
  return top;
}
waves::Node WaveCancellingTop() {
  waves::Node top = TopAtRest(5000, 2 * kPipe.impedance * kCorner);
  top.law.wave_cancellation.impedance = kPipe.impedance;
  return top;
}

// The pipe at rest between `top` and a massless bit driven by the pulse: with nothing coming down, the bit's balance
// Z (2 D - v) + u = 0 sends up U = D + u / Z, so the wave arriving at the top is w(t) = u(t - tau) / Z until what the
// top sends down has come back (3 tau).
waves::Network PulseString(const waves::Node& top) {
  waves::Node bit;
  bit.name = "bit";
  bit.drive = waves::Drive::kTorque;
  bit.setpoint = model::Schedule({{0.0, 0.0}, {0.1, 0.0}, {0.2, Pulse(0.2)}, {0.3, 0.0}});
  waves::Network net;
  net.sections = {kPipe};
  net.nodes = {top, bit};
  return net;
}

// The waves at the top over [0, 3 tau): arriving w and leaving D from the top's speed v and the torque T it feeds into
// the string, T = Z (D - w), v = D + w.
struct TopWaves {
  std::vector<double> time, arriving, leaving;
};
TopWaves RunPulse(const waves::Node& top) {
  const waves::Network net = PulseString(top);
  waves::NetworkRunOptions options;
  options.t_end_s = 3 * kPipe.travel_time_s;
  options.output_interval_s = 1e-4;
  options.integrator.abs_tol = options.integrator.rel_tol = 1e-11;
  const waves::NetworkTrajectory tr = waves::SimulateNetwork(net, options).trajectory;
  TopWaves out;
  for (std::size_t i = 0; i < tr.time_s.size(); ++i) {
    if (tr.time_s[i] >= options.t_end_s - 1e-9) break;
    const double v = tr.top_speed_rad_s[i], torque_per_z = tr.top_torque_nm[i] / kPipe.impedance;
    out.time.push_back(tr.time_s[i]);
    out.arriving.push_back(0.5 * (v - torque_per_z));
    out.leaving.push_back(0.5 * (v + torque_per_z));
  }
  return out;
}

double LargestOf(const std::vector<double>& values) {
  double largest = 0;
  for (double v : values) largest = std::max(largest, std::abs(v));
  return largest;
}

// An up-going pulse reaches the top (set-point 0, free massless bit below). The wave the law sends down is its own
// d alone: with the set-point 0, d' = -k (w + d) (v = w + d exactly), which integrated from the closed-form arrival
// w = u(t - tau) / Z gives the slow loop's answer to the pulse; the leaving wave D differs from it by less than 1e-6
// of the pulse, nothing of the pulse is reflected. The stiff PI (kp = ki = 5000) sends most of it back inverted (its
// impedance J s + kp + ki / s is many Z at the pulse's frequencies: a nearly fixed end).
TEST(WaveCancellation, AnArrivingPulseIsNotReflected) {
  const TopWaves wave = RunPulse(WaveCancellingTop()), stiff = RunPulse(TopAtRest(5000, 5000));
  const double tau = kPipe.travel_time_s, pulse = Pulse(0.2) / kPipe.impedance;
  double arrival_error = 0, reflected = 0, injected = 0, d = 0, t = 0;
  const double h = 1e-6;  // RK4 on d' = -k (w + d), w piecewise linear: exact to rounding away from its kinks
  auto rate = [&](double at, double dv) { return -kCorner * (Pulse(at - tau) / kPipe.impedance + dv); };
  for (std::size_t i = 0; i < wave.time.size(); ++i) {
    for (; t + 0.5 * h < wave.time[i]; t += h) {
      const double k1 = rate(t, d), k2 = rate(t + h / 2, d + h / 2 * k1), k3 = rate(t + h / 2, d + h / 2 * k2);
      d += h / 6 * (k1 + 2 * k2 + 2 * k3 + rate(t + h, d + h * k3));
    }
    arrival_error = std::max(arrival_error, std::abs(wave.arriving[i] - Pulse(wave.time[i] - tau) / kPipe.impedance));
    reflected = std::max(reflected, std::abs(wave.leaving[i] - d));
    injected = std::max(injected, std::abs(d));
  }
  const double stiff_reflected = LargestOf(stiff.leaving) / LargestOf(stiff.arriving);
  std::printf("[ measured ] pulse of %.4f rad/s arriving at the top: arrival within %.1e of u(t - tau) / Z; wave "
              "cancellation (k = %.2f 1/s): leaving wave - closed-form d %.2e of the pulse, d itself up to %.2e of it; "
              "stiff PI: leaving wave up to %.4f of the pulse\n",
              pulse, arrival_error / pulse, kCorner, reflected / pulse, injected / pulse, stiff_reflected);
  EXPECT_GT(wave.time.size(), 10000u);
  EXPECT_LT(arrival_error, 1e-6 * pulse);
  EXPECT_LT(reflected, 1e-6 * pulse);
  EXPECT_GT(stiff_reflected, 0.5);
}

nlohmann::json SaldivarCase() {
  nlohmann::json doc = testing::LoadCase("saldivar-wave-cancellation");
  doc.erase("expect");
  return doc;
}
// The case with the same drive as the stiff PI of saldivar-z-torque.json (kp = ki = 5000).
nlohmann::json StiffPi(nlohmann::json doc) {
  nlohmann::json& top = doc["model"]["top"];
  top.erase("speed_loop_corner_rad_s");
  top.update({{"type", "top_drive"}, {"ki_Nm_per_rad", 5000}});
  return doc;
}
nlohmann::json AtSpeed(nlohmann::json doc, double speed) {
  doc["model"]["top"]["speed_rad_s"]["knots"][1][1] = speed;
  return doc;
}

// The Saldivar string (json-cases/saldivar-wave-cancellation.json) from rest to 10 rad/s and to 4 rad/s, where the
// stiff PI's steady rotation is unstable: the stiff PI sticks and slips over the window, the wave-cancelling top drills
// smoothly at the set-point. Handed over at 20 s of the stiff PI's stick-slip at 4 rad/s (as compare-controllers does)
// it ends it too.
TEST(WaveCancellation, SuppressesTheSaldivarStickSlipThatTheStiffPiKeepsUp) {
  for (double speed : {10.0, 4.0}) {
    const nlohmann::json wave = AtSpeed(SaldivarCase(), speed);
    const nlohmann::json summary = RunCase(ParseCase(wave)).summary;
    const nlohmann::json stiff = RunCase(ParseCase(StiffPi(wave))).summary;
    std::printf("[ measured ] Saldivar string at %.0f rad/s over [40, 80] s: stiff PI stick fraction %.3f, severity "
                "%.3f; wave cancellation stick fraction %.3f, severity %.2e, mean bit speed %.5f rad/s\n", speed,
                stiff["stick_fraction"].get<double>(), stiff["stick_slip_severity"].get<double>(),
                summary["stick_fraction"].get<double>(), summary["stick_slip_severity"].get<double>(),
                summary["bit_speed_mean_rad_s"].get<double>());
    EXPECT_GT(stiff["stick_fraction"].get<double>(), 0.1) << speed;
    EXPECT_EQ(summary["stick_fraction"].get<double>(), 0.0) << speed;
    EXPECT_LT(summary["stick_slip_severity"].get<double>(), 0.01) << speed;
    EXPECT_NEAR(summary["bit_speed_mean_rad_s"].get<double>(), speed, 2e-3 * speed);
  }
  nlohmann::json handed = AtSpeed(SaldivarCase(), 4);
  handed["model"]["top"]["handover"] = {{"time_s", 20}, {"kp_Nms_per_rad", 5000}, {"ki_Nm_per_rad", 5000}};
  const CaseRun run = RunCase(ParseCase(handed));
  const std::vector<double>& stuck = run.result.channel("bit_stuck").values;
  double last_stick = 0;
  for (std::size_t i = 0; i < stuck.size(); ++i)
    if (stuck[i] > 0.5) last_stick = run.result.time_s[i];
  std::printf("[ measured ] handed over at 20 s at 4 rad/s: last stick ends at %.2f s; stick fraction over [40, 80] s "
              "%.3f\n", last_stick, run.summary["stick_fraction"].get<double>());
  EXPECT_GT(last_stick, 10.0);  // the stiff PI stuck before the handover
  EXPECT_LT(last_stick, 40.0);
  EXPECT_EQ(run.summary["stick_fraction"].get<double>(), 0.0);
  // Low-passed (tf 0.1 s, corner 10 rad/s against the stick-slip mode's 2.4 rad/s), its filter followed the wave
  // before the handover: the same end.
  handed["model"]["top"]["wave_filter_time_constant_s"] = 0.1;
  const nlohmann::json filtered = RunCase(ParseCase(handed)).summary;
  std::printf("[ measured ] the same, low-passed at tf 0.1 s: stick fraction over [40, 80] s %.3f, severity %.2e\n",
              filtered["stick_fraction"].get<double>(), filtered["stick_slip_severity"].get<double>());
  EXPECT_EQ(filtered["stick_fraction"].get<double>(), 0.0);
}

nlohmann::json WithTop(nlohmann::json doc, const nlohmann::json& fields) {
  doc["model"]["top"].update(fields);
  return doc;
}

TEST(WaveCancellation, BadInputNamesTheFieldInTheTorsionalWaveKind) {
  const nlohmann::json doc = SaldivarCase();
  EXPECT_EQ(RefusedPath(doc, true), "");
  nlohmann::json missing = doc;
  missing["model"]["top"].erase("speed_loop_corner_rad_s");
  EXPECT_EQ(RefusedPath(missing), "/model/top/speed_loop_corner_rad_s");
  EXPECT_EQ(RefusedPath(WithTop(doc, {{"speed_loop_corner_rad_s", 0}})), "/model/top/speed_loop_corner_rad_s");
  EXPECT_EQ(RefusedPath(WithTop(doc, {{"kp_Nms_per_rad", 0}})), "/model/top/kp_Nms_per_rad");
  EXPECT_EQ(RefusedPath(WithTop(doc, {{"ki_Nm_per_rad", 100}})), "/model/top/ki_Nm_per_rad");  // it is 2 Z k
  EXPECT_EQ(RefusedPath(WithTop(doc, {{"feedback_time_constant_s", 5}})), "/model/top/feedback_time_constant_s");
  EXPECT_EQ(RefusedPath(WithTop(doc, {{"torque_limit_Nm", -1}})), "/model/top/torque_limit_Nm");
  EXPECT_EQ(RefusedPath(WithTop(doc, {{"actuator_delay_s", 11}})), "/model/top/actuator_delay_s");
  EXPECT_EQ(RefusedPath(WithTop(doc, {{"torque_limit_Nm", 5e4}, {"actuator_delay_s", 0.02}}), true), "");
  EXPECT_EQ(RefusedPath(WithTop(doc, {{"wave_filter_time_constant_s", -0.1}})),
            "/model/top/wave_filter_time_constant_s");
  EXPECT_EQ(RefusedPath(WithTop(doc, {{"wave_filter_time_constant_s", 0.3}, {"actuator_delay_s", 0.1}}), true), "");
  EXPECT_EQ(RefusedPath(WithTop(doc, {{"handover", {{"time_s", 0}, {"kp_Nms_per_rad", 1}, {"ki_Nm_per_rad", 1}}}})),
            "/model/top/handover/time_s");
  // It reads the string torque and the arriving wave at a top driven directly, next to no Kelvin-Voigt dashpot.
  nlohmann::json geared = WithTop(doc, {{"gear", {{"ratio", 8}, {"stiffness_Nm_per_rad", 3e5}}},
                                        {"motor_inertia_kgm2", 10}});
  EXPECT_EQ(RefusedPath(geared), "/model/top/gear");
  nlohmann::json rigid = WithTop(doc, {{"gear", {{"ratio", 8}}}, {"motor_inertia_kgm2", 10}});
  EXPECT_EQ(RefusedPath(rigid, true), "");
  nlohmann::json kelvin_voigt = doc;
  kelvin_voigt["model"]["string"]["kelvin_voigt_s"] = 0.01;
  EXPECT_EQ(RefusedPath(kelvin_voigt), "/model/top/type");
}

nlohmann::json CoupledBaseline() {
  nlohmann::json doc = testing::LoadCase("baseline-60rpm");
  doc.erase("expect");
  doc["model"]["top"].erase("ki_Nm_per_rad");
  doc["model"]["top"].update({{"type", "wave_cancellation"}, {"speed_loop_corner_rad_s", kCorner}});
  return doc;
}

// The coupled baseline (json-cases/baseline-60rpm.json: its stiff PI, kp 1e5 and ki 2e5, sticks and slips, stick
// fraction 0.15-0.3 by its expect block) under the wave cancellation with the same kp: the bit no longer sticks and
// the severity is Z-Torque's (baseline-z-torque.json: below 0.3), though the unstable axial root stays.
TEST(WaveCancellation, EndsTheCoupledBaselinesStickSlip) {
  const nlohmann::json summary = RunCase(ParseCase(CoupledBaseline())).summary;
  std::printf("[ measured ] baseline-60rpm under the wave cancellation (k = %.1f 1/s): stick fraction %.3f, severity "
              "%.3f, mean bit speed %.4f rad/s\n", kCorner, summary["stick_fraction"].get<double>(),
              summary["stick_slip_severity"].get<double>(), summary["bit_speed_mean_rad_s"].get<double>());
  EXPECT_EQ(summary["stick_fraction"].get<double>(), 0.0);
  EXPECT_LT(summary["stick_slip_severity"].get<double>(), 0.3);
  EXPECT_NEAR(summary["bit_speed_mean_rad_s"].get<double>(), 2 * kPi, 0.01 * 2 * kPi);
}

// The same law behind a 100 ms actuator delay, its pull onto the law's speed softened to kp = 5000 N m s/rad: exact, it
// sends down up to twice the wave that arrives (|e^{-i w delta} - 1| <= 2) and the string's fast waves grow without
// bound; low-passed at tf = 0.2 s (its corner 5 rad/s, above the stick-slip mode's 2 rad/s: period 2.8-3.5 s) the top
// reflects them as a stiff top does and the bit turns without sticking. (tf 0.05 and 0.1 s: the fast waves still grow
// into a violent bit speed, -353 to 413 and -5.6 to 21.7 rad/s; tf 0.4 s, a corner of 2.5 rad/s at the stick-slip
// mode: sticking again, fraction 0.14.)
TEST(WaveCancellation, FilteredItEndsTheCoupledBaselinesStickSlipBehindADelay) {
  const nlohmann::json exact = WithTop(CoupledBaseline(), {{"actuator_delay_s", 0.1}, {"kp_Nms_per_rad", 5000}});
  // The exact law's bit runs away (it reached 3.7e8 rad/s by 60 s before runs were stopped at 100 times the
  // set-point): the run stops with the time and state where it left physics.
  std::string runaway;
  double runaway_at = 0;
  try {
    RunCase(ParseCase(exact));
  } catch (const NumericalError& e) {
    runaway = e.what(), runaway_at = e.time();
  }
  const nlohmann::json f = RunCase(ParseCase(WithTop(exact, {{"wave_filter_time_constant_s", 0.2}}))).summary;
  std::printf(
      "[ measured ] baseline-60rpm under the wave cancellation behind 100 ms (kp 5000): exact, stopped at %.2f s: "
      "%s; filtered (tf 0.2 s) %.2f to %.2f rad/s, stick fraction %.3f, severity %.3f\n",
      runaway_at, runaway.c_str(), f["bit_speed_min_rad_s"].get<double>(), f["bit_speed_max_rad_s"].get<double>(),
      f["stick_fraction"].get<double>(), f["stick_slip_severity"].get<double>());
  EXPECT_NE(runaway.find("runaway: the bit turns at"), std::string::npos) << runaway;
  EXPECT_EQ(f["stick_fraction"].get<double>(), 0.0);
  EXPECT_GT(f["bit_speed_min_rad_s"].get<double>(), 0.5 * kPi);
  EXPECT_LT(f["bit_speed_max_rad_s"].get<double>(), 3 * kPi);
}

TEST(WaveCancellation, BadInputNamesTheFieldInTheAxialTorsionalKind) {
  const nlohmann::json doc = CoupledBaseline();
  EXPECT_EQ(RefusedPath(doc, true), "");
  EXPECT_EQ(RefusedPath(WithTop(doc, {{"speed_loop_corner_rad_s", -1}})), "/model/top/speed_loop_corner_rad_s");
  EXPECT_EQ(RefusedPath(WithTop(doc, {{"ki_Nm_per_rad", 2e5}})), "/model/top/ki_Nm_per_rad");
  EXPECT_EQ(RefusedPath(WithTop(doc, {{"actuator_delay_s", 0.02}}), true), "");
  EXPECT_EQ(RefusedPath(WithTop(doc, {{"wave_filter_time_constant_s", "0.1"}})),
            "/model/top/wave_filter_time_constant_s");
  const nlohmann::json motor = {{"motor_constant_Nm_per_A", 10}, {"resistance_ohm", 0.01}, {"inductance_H", 1e-3}};
  EXPECT_EQ(RefusedPath(WithTop(doc, {{"motor", motor}})), "/model/top/type");  // behind a motor: no law
  nlohmann::json kelvin_voigt = doc;
  kelvin_voigt["model"]["string"]["kelvin_voigt_s"] = 0.02;
  EXPECT_EQ(RefusedPath(kelvin_voigt), "/model/top/type");
}

}  // namespace
}  // namespace drillwave::cases
