// The optional top-drive and bit components of the axial_torsional kind (Stribeck bit friction, axial coupling off,
// DC motor, BHA mass unbalance) and the start's bottom-hole roughness, each against a closed form or a limit it must
// reach, and each absent-equivalent setting against the plain run.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/bitrock/roughness.hpp"
#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

// The baseline (BASELINE.md nominal point) at a constant set-point, run for `duration` s with statistics over its
// last `window` s.
nlohmann::json Nominal(double rpm, double duration, double window) {
  nlohmann::json doc = testing::LoadCase("baseline-60rpm");
  doc["model"]["top"]["speed_rad_s"] = rpm * kPi / 30;
  doc["simulation"]["duration_s"] = duration;
  doc["statistics"]["window_s"] = {duration - window, duration};
  doc.erase("expect");
  return doc;
}
// The same with the baseline case's 5 % set-point bump at 1-2 s, which starts the instabilities.
nlohmann::json Bumped(double rpm, double duration, double window) {
  nlohmann::json doc = Nominal(rpm, duration, window);
  const double w = rpm * kPi / 30;
  doc["model"]["top"]["speed_rad_s"] = {{"knots", {{0, w}, {1, 1.05 * w}, {2, w}}}};
  return doc;
}

CaseRun RunDoc(const nlohmann::json& doc) { return RunCase(ParseCase(doc)); }
const std::vector<double>& Channel(const CaseRun& run, const std::string& name) {
  for (const auto& c : run.result.channels)
    if (c.name == name) return c.values;
  throw std::runtime_error("no channel " + name);
}
double Get(const CaseRun& run, const char* key) { return run.summary.at(key).get<double>(); }

// Closed forms of steady drilling from the case's own parameters (RGD; BASELINE.md): cutting and friction torque at
// the weight on bit W0 with friction coefficient mu, and the top torque adding the string's viscous drag c_t L w.
struct SteadyClosedForm {
  double cut_torque, contact_force, friction_arm_per_mu, drag_per_speed;
  explicit SteadyClosedForm(const nlohmann::json& doc) {
    const auto& md = doc["model"];
    const double a = md["bit"]["radius_m"], eps = md["rock"]["intrinsic_specific_energy_Pa"];
    const double zeta = md["rock"]["zeta"], sigma_l = md["rock"]["sigma_l_N_per_m"];
    const double w0 = md["hoist"]["weight_on_bit_N"];
    contact_force = a * sigma_l;
    cut_torque = 0.5 * a * a * eps * (w0 - contact_force) / (a * zeta * eps);
    friction_arm_per_mu = 0.5 * a * md["rock"]["gamma"].get<double>();
    drag_per_speed = md["string"]["torsional_damping_Nms_per_rad_m"].get<double>() * md["string"]["length_m"].get<double>();
  }
  double BitTorque(double mu) const { return cut_torque + friction_arm_per_mu * mu * contact_force; }
};

double Stribeck(double mu, double static_mu, double speed, double w) {
  return mu + (static_mu - mu) * std::exp(-std::abs(w) / speed);
}

// --- Stribeck bit friction -------------------------------------------------------------------------------------

TEST(AxialTorsionalStribeck, StaticMuEqualToMuIsTheCoulombRun) {
  nlohmann::json doc = Bumped(60, 15, 10);
  const CaseRun coulomb = RunDoc(doc);
  doc["model"]["rock"]["stribeck"] = {{"static_mu", 0.6}, {"velocity_rad_s", 6.8}};
  const CaseRun stribeck = RunDoc(doc);
  EXPECT_GT(coulomb.summary.at("stick_onsets").get<int>(), 0);  // the comparison goes through sticks and slips
  for (const char* name : {"bit_rpm", "top_torque_Nm", "bit_torque_Nm", "wob_N"})
    EXPECT_EQ(Channel(coulomb, name), Channel(stribeck, name)) << name;
}

// From steady drilling at 60 rpm the set-point is ramped to 100 rpm: the bit settles where its torque is the
// Stribeck closed form at the new speed (18 % more friction than Coulomb's there). Steady drilling has to be stable
// for that: the axial coupling is off (with it the bit keeps oscillating by 1.3 rad/s at 100 rpm, and at 150-170 rpm
// without Stribeck) and the string more damped (0.5 instead of 0.06 N m s/rad/m: friction falling with speed
// undamps the baseline string, 10.2-10.8 rad/s after 120 s).
TEST(AxialTorsionalStribeck, SteadyBitTorqueIsTheClosedForm) {
  nlohmann::json doc = Nominal(60, 60, 10);
  const double w1 = 2 * kPi, w2 = 100 * kPi / 30;
  doc["model"]["top"]["speed_rad_s"] = {{"knots", {{0, w1}, {1, w1}, {3, w2}}}};
  doc["model"]["rock"]["stribeck"] = {{"static_mu", 1.1}, {"velocity_rad_s", 6.8}};
  doc["model"]["axial_coupling"] = false;
  doc["model"]["string"]["torsional_damping_Nms_per_rad_m"] = 0.5;
  const CaseRun run = RunDoc(doc);
  const SteadyClosedForm cf(doc);
  const double expected = cf.BitTorque(Stribeck(0.6, 1.1, 6.8, w2)), coulomb = cf.BitTorque(0.6);
  const double measured = Get(run, "bit_torque_mean_Nm");
  std::printf("[ measured ] Stribeck at 100 rpm: mean bit torque %.4f N m, closed form %.4f (%+.2e), Coulomb %.4f; "
              "bit speed %.6f..%.6f rad/s\n", measured, expected, measured / expected - 1, coulomb,
              Get(run, "bit_speed_min_rad_s"), Get(run, "bit_speed_max_rad_s"));
  EXPECT_NEAR(measured, expected, 1e-7 * expected);
  EXPECT_NEAR(Get(run, "bit_speed_min_rad_s"), w2, 1e-5 * w2);
  EXPECT_NEAR(Get(run, "bit_speed_max_rad_s"), w2, 1e-5 * w2);
}

// 2200 m, 70 kN, 100 rpm: after the set-point bump the Coulomb baseline oscillates without sticking (the bit between
// 8.9 and 12.1 rad/s, still at 120 s); the friction that falls with speed (static 1.1, 6.8 rad/s) makes the same
// point stick and slip.
TEST(AxialTorsionalStribeck, CreatesStickSlipWhereCoulombDrillsSmoothly) {
  nlohmann::json doc = Bumped(100, 60, 30);
  doc["model"]["string"]["length_m"] = 2200;
  doc["model"]["hoist"]["weight_on_bit_N"] = 70000;
  const CaseRun coulomb = RunDoc(doc);
  doc["model"]["rock"]["stribeck"] = {{"static_mu", 1.1}, {"velocity_rad_s", 6.8}};
  const CaseRun stribeck = RunDoc(doc);
  std::printf("[ measured ] 2200 m, 70 kN, 100 rpm: Coulomb %d stick onsets, bit %.3f..%.3f rad/s; Stribeck %d, "
              "stick fraction %.3f, period %.3f s\n", coulomb.summary.at("stick_onsets").get<int>(),
              Get(coulomb, "bit_speed_min_rad_s"), Get(coulomb, "bit_speed_max_rad_s"),
              stribeck.summary.at("stick_onsets").get<int>(), Get(stribeck, "stick_fraction"),
              Get(stribeck, "stick_slip_period_s"));
  EXPECT_EQ(coulomb.summary.at("stick_onsets").get<int>(), 0);
  EXPECT_GT(Get(coulomb, "bit_speed_min_rad_s"), 8.0);
  EXPECT_GE(stribeck.summary.at("stick_onsets").get<int>(), 5);
}

TEST(AxialTorsionalStribeck, RejectsAStaticCoefficientBelowMu) {
  nlohmann::json doc = Nominal(60, 1, 1);
  doc["model"]["rock"]["stribeck"] = {{"static_mu", 0.5}, {"velocity_rad_s", 6.8}};
  try {
    ParseCase(doc);
    ADD_FAILURE() << "accepted static_mu < mu";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/model/rock/stribeck/static_mu"), std::string::npos) << e.what();
  }
}

// --- Axial coupling off ----------------------------------------------------------------------------------------

// Without axial dynamics (and on homogeneous rock) the weight on bit is W0 and the depth of cut the steady one
// throughout, and after the set-point bump the torsion settles to the closed form: bit torque T_c + T_f, top torque
// that plus c_t L w.
TEST(AxialTorsionalUncoupled, HoldsTheWeightOnBitAndSettlesToTheClosedForm) {
  nlohmann::json doc = Bumped(60, 120, 10);
  doc["model"]["axial_coupling"] = false;
  const CaseRun run = RunDoc(doc);
  const SteadyClosedForm cf(doc);
  const double w0 = doc["model"]["hoist"]["weight_on_bit_N"], depth = Get(run, "steady_depth_of_cut_m");
  for (double wob : Channel(run, "wob_N")) ASSERT_EQ(wob, w0);
  for (double d : Channel(run, "depth_of_cut_m")) ASSERT_EQ(d, depth);
  const double torque = Get(run, "bit_torque_mean_Nm"), expected = cf.BitTorque(0.6);
  const auto& top = Channel(run, "top_torque_Nm");
  const double top_expected = expected + cf.drag_per_speed * 2 * kPi;
  std::printf("[ measured ] uncoupled, 60 rpm after the bump: bit torque %.6f (closed form %.6f, %+.1e), top torque "
              "%.6f (%.6f, %+.1e), bit speed %.6f..%.6f rad/s, %d stick onsets\n", torque, expected,
              torque / expected - 1, top.back(), top_expected, top.back() / top_expected - 1,
              Get(run, "bit_speed_min_rad_s"), Get(run, "bit_speed_max_rad_s"),
              run.summary.at("stick_onsets").get<int>());
  EXPECT_EQ(run.summary.at("stick_onsets").get<int>(), 0);
  EXPECT_NEAR(torque, expected, 1e-9 * expected);
  EXPECT_NEAR(top.back(), top_expected, 1e-5 * top_expected);
  EXPECT_NEAR(Get(run, "bit_speed_min_rad_s"), 2 * kPi, 1e-4);
  EXPECT_NEAR(Get(run, "bit_speed_max_rad_s"), 2 * kPi, 1e-4);
}

// On rock whose strength s(z) varies (BASELINE.md: 0.5-1.5 % over 2 mm of drilled depth) the held weight is still
// W0 and the depth of cut follows the rock: W0 = s (a zeta eps d + a sigma l), so every sample's torque on bit is
// s (a^2 eps d / 2 + a gamma mu a sigma l / 2) with s read from its depth of cut. Its swing is only the contact's
// share of the strength's (a constant depth of cut would pass the whole deviation to the torque: 2.5 times as much
// at this point, and 2-3 times the first torsional mode's response the independent simulator shows, dev rec06).
TEST(AxialTorsionalUncoupled, OnHeterogeneousRockTheWeightIsHeldAndTheDepthOfCutFollowsTheStrength) {
  nlohmann::json doc = Nominal(60, 20, 15);
  doc["model"]["axial_coupling"] = false;
  doc["model"]["rock"]["strength_heterogeneity"] = {{"std", 0.01}, {"correlation_m", 0.002}, {"seed", 3}};
  const CaseRun run = RunDoc(doc);
  const auto& md = doc["model"];
  const double a = md["bit"]["radius_m"], eps = md["rock"]["intrinsic_specific_energy_Pa"];
  const double zeta = md["rock"]["zeta"], contact = a * md["rock"]["sigma_l_N_per_m"].get<double>();
  const double arm = 0.5 * a * md["rock"]["gamma"].get<double>() * md["rock"]["mu"].get<double>();
  const double w0 = md["hoist"]["weight_on_bit_N"];
  const auto &depth = Channel(run, "depth_of_cut_m"), &torque = Channel(run, "bit_torque_Nm");
  const auto &bit = Channel(run, "bit_rpm"), &wob = Channel(run, "wob_N");
  double worst = 0, depth_min = INFINITY, depth_max = 0;
  for (std::size_t i = 0; i < depth.size(); ++i) {
    ASSERT_EQ(wob[i], w0);
    if (!(bit[i] > 1)) continue;  // sliding forward and cutting
    const double s = w0 / (a * zeta * eps * depth[i] + contact);
    const double expected = s * (0.5 * a * a * eps * depth[i] + arm * contact);
    worst = std::max(worst, std::abs(torque[i] / expected - 1));
    depth_min = std::min(depth_min, depth[i]), depth_max = std::max(depth_max, depth[i]);
  }
  const double steady = Get(run, "steady_depth_of_cut_m");
  std::printf("[ measured ] uncoupled on 1 %% heterogeneous rock: depth of cut %.4g..%.4g m (steady %.4g), torque on "
              "bit against the held-weight closed form within %.1e\n", depth_min, depth_max, steady, worst);
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(depth_min, 0.99 * steady);  // the rock's 1 % moves the depth of cut by more than that
  EXPECT_GT(depth_max, 1.01 * steady);
}

// BASELINE.md: the regenerative axial-torsional coupling is what makes the baseline unstable. At its nominal point
// (60 rpm) the coupled model sticks and slips; without the coupling the same bump dies out.
TEST(AxialTorsionalUncoupled, TheCouplingMakesTheNominalPointStickAndSlip) {
  nlohmann::json doc = Bumped(60, 40, 10);
  const CaseRun coupled = RunDoc(doc);
  doc["model"]["axial_coupling"] = false;
  const CaseRun uncoupled = RunDoc(doc);
  std::printf("[ measured ] 60 rpm over [30, 40] s: coupled %d stick onsets, stick fraction %.3f; uncoupled %d, bit "
              "speed %.6f..%.6f rad/s\n", coupled.summary.at("stick_onsets").get<int>(), Get(coupled, "stick_fraction"),
              uncoupled.summary.at("stick_onsets").get<int>(), Get(uncoupled, "bit_speed_min_rad_s"),
              Get(uncoupled, "bit_speed_max_rad_s"));
  EXPECT_GE(coupled.summary.at("stick_onsets").get<int>(), 2);
  EXPECT_EQ(uncoupled.summary.at("stick_onsets").get<int>(), 0);
}

// --- DC motor --------------------------------------------------------------------------------------------------

nlohmann::json Motor(double inductance) {
  return {{"motor_constant_Nm_per_A", 50.0}, {"resistance_ohm", 0.05}, {"inductance_H", inductance}};
}

TEST(AxialTorsionalMotor, HoldsTheSteadyCurrent) {
  nlohmann::json doc = Nominal(60, 2, 2);
  doc["model"]["top"]["motor"] = Motor(0.005);
  const CaseRun run = RunDoc(doc);
  const SteadyClosedForm cf(doc);
  const double expected = (cf.BitTorque(0.6) + cf.drag_per_speed * 2 * kPi) / 50;
  const auto& current = Channel(run, "top_current_A");
  const auto [lo, hi] = std::minmax_element(current.begin(), current.end());
  std::printf("[ measured ] steady current %.10f..%.10f A, closed form T0 / K = %.10f A\n", *lo, *hi, expected);
  EXPECT_NEAR(*lo, expected, 1e-9 * expected);
  EXPECT_NEAR(*hi, expected, 1e-9 * expected);
}

// La -> 0: K I = u_PI + K^2 / R (Omega_ref - w_top), the PI drive with kp + K^2 / R. The bit speeds through the bump
// and the first stick-slip cycles approach that run about linearly in La (measured: 14.8, 1.53, 0.22 rpm).
TEST(AxialTorsionalMotor, SmallInductanceTendsToThePiWithAddedDamping) {
  nlohmann::json doc = Bumped(60, 8, 8);
  doc["simulation"]["abs_tol"] = doc["simulation"]["rel_tol"] = 1e-7;
  nlohmann::json pi = doc;
  pi["model"]["top"]["kp_Nms_per_rad"] = doc["model"]["top"]["kp_Nms_per_rad"].get<double>() + 50 * 50 / 0.05;
  const CaseRun pi_run = RunDoc(pi);
  const auto& reference = Channel(pi_run, "bit_rpm");
  std::vector<double> errors;
  for (double la : {1e-3, 1e-4, 1e-5}) {
    doc["model"]["top"]["motor"] = Motor(la);
    const CaseRun run = RunDoc(doc);
    const auto& bit = Channel(run, "bit_rpm");
    double worst = 0;
    for (std::size_t i = 0; i < bit.size(); ++i) worst = std::max(worst, std::abs(bit[i] - reference[i]));
    errors.push_back(worst);
    std::printf("[ measured ] La %.0e H (La/R %.0e s): largest bit speed difference to the PI with kp + K^2/R over "
                "8 s: %.3e rpm\n", la, la / 0.05, worst);
  }
  EXPECT_LT(errors[2], 0.5);  // of a bit speed that swings 0-155 rpm
  EXPECT_LT(errors[1], 0.2 * errors[0]);
  EXPECT_LT(errors[2], 0.2 * errors[1]);
}

// The PI switched off (kp = ki = 0) leaves a voltage K Omega_ref that holds no current: from its steady value the
// current decays as exp(-t R / La), while the top drive (made heavy) keeps its speed.
TEST(AxialTorsionalMotor, CurrentDecaysWithTimeConstantLaOverR) {
  nlohmann::json doc = Nominal(60, 0.5, 0.5);
  doc["model"]["top"]["motor"] = Motor(0.005);
  doc["model"]["top"]["kp_Nms_per_rad"] = 0;
  doc["model"]["top"]["ki_Nm_per_rad"] = 0;
  doc["model"]["top"]["inertia_kgm2"] = 1e12;
  doc["simulation"]["output_interval_s"] = 0.001;
  const CaseRun run = RunDoc(doc);
  const auto& current = Channel(run, "top_current_A");
  const double tau = 0.005 / 0.05;
  double worst = 0;
  for (std::size_t i = 0; i < run.result.time_s.size(); ++i)
    worst = std::max(worst, std::abs(current[i] / current[0] - std::exp(-run.result.time_s[i] / tau)));
  // The time constant read from the decay between 0.1 and 0.4 s.
  const std::size_t i1 = 100, i2 = 400;
  const double fitted = (run.result.time_s[i2] - run.result.time_s[i1]) / std::log(current[i1] / current[i2]);
  std::printf("[ measured ] current decay: time constant %.8f s (La/R %.8f s, %+.1e), largest deviation from "
              "exp(-t R/La) %.2e of I0\n", fitted, tau, fitted / tau - 1, worst);
  EXPECT_NEAR(fitted, tau, 1e-4 * tau);
  EXPECT_LT(worst, 1e-4);
}

// --- BHA mass unbalance ----------------------------------------------------------------------------------------

nlohmann::json Unbalance(double natural_frequency, double damping_ratio, double unbalance_mass) {
  const double mass = 2000, total = mass + unbalance_mass;
  const double stiffness = total * natural_frequency * natural_frequency;
  return {{"lateral_mass_kg", mass}, {"lateral_stiffness_N_per_m", stiffness},
          {"lateral_damping_Ns_per_m", 2 * damping_ratio * natural_frequency * total},
          {"unbalance_mass_kg", unbalance_mass}, {"eccentricity_m", 0.05}};
}

TEST(AxialTorsionalUnbalance, ZeroUnbalanceMassIsThePlainRun) {
  nlohmann::json doc = Bumped(60, 15, 10);
  const CaseRun plain = RunDoc(doc);
  doc["model"]["bit"]["unbalance"] = Unbalance(10, 0.05, 0);
  const CaseRun with = RunDoc(doc);
  for (const char* name : {"bit_rpm", "top_torque_Nm", "bit_torque_Nm", "wob_N"})
    EXPECT_EQ(Channel(plain, name), Channel(with, name)) << name;
  for (double r : Channel(with, "lateral_displacement_m")) ASSERT_EQ(r, 0.0);
}

// The bit made heavy (J_b = 1e6 kg m^2) turns at the imposed 150 rpm; the whirl settles to the radius
// m e W^2 / sqrt((k - (M + m) W^2)^2 + (c W)^2), largest where W is the natural frequency sqrt(k / (M + m)).
TEST(AxialTorsionalUnbalance, SteadyWhirlIsTheClosedFormAndPeaksAtTheNaturalFrequency) {
  const double w = 150 * kPi / 30, zeta = 0.05, m = 10, e = 0.05, total = 2010;
  std::vector<double> amplitudes;
  for (double ratio : {0.8, 0.95, 1.0, 1.05, 1.25}) {  // natural frequency / bit speed
    nlohmann::json doc = Nominal(150, 16, 2);
    doc["model"]["bit"]["inertia_kgm2"] = 1e6;
    doc["model"]["bit"]["unbalance"] = Unbalance(ratio * w, zeta, m);
    const CaseRun run = RunDoc(doc);
    const double wn = ratio * w, k = total * wn * wn, c = 2 * zeta * wn * total;
    const double expected = m * e * w * w / std::hypot(k - total * w * w, c * w);
    const double mean = Get(run, "whirl_amplitude_mean_m"), peak = Get(run, "whirl_amplitude_max_m");
    std::printf("[ measured ] w_n / W = %.2f: whirl radius %.8f..%.8f m, closed form %.8f (%+.1e); bit speed "
                "%.6f..%.6f rad/s\n", ratio, mean, peak, expected, mean / expected - 1, Get(run, "bit_speed_min_rad_s"),
                Get(run, "bit_speed_max_rad_s"));
    EXPECT_NEAR(mean, expected, 1e-3 * expected) << ratio;
    EXPECT_NEAR(peak, expected, 2e-3 * expected) << ratio;
    EXPECT_NEAR(Get(run, "steady_whirl_amplitude_m"), expected, 1e-12 * expected);
    amplitudes.push_back(mean);
  }
  EXPECT_EQ(std::max_element(amplitudes.begin(), amplitudes.end()) - amplitudes.begin(), 2);
}

// --- Bottom-hole roughness (BASELINE.md's start: the exact steady state plus a tiny roughness) ---------------------

// Each (value of rock/<key>, field path) is refused by ParseCase with an InputError naming that path.
template <std::size_t N>
void ExpectEachRefusedNaming(const char* key, const std::pair<nlohmann::json, std::string> (&bad)[N]) {
  for (const auto& [field, path] : bad) {
    nlohmann::json doc = Nominal(60, 1, 1);
    doc["model"]["rock"][key] = field;
    try {
      ParseCase(doc);
      ADD_FAILURE() << "accepted " << field.dump();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

nlohmann::json Roughness(double rms, int seed) { return {{"rms_m", rms}, {"seed", seed}}; }

// Without roughness nothing disturbs the unstable equilibrium: a field of rms 0 is the smooth start to the byte, and
// it holds the steady state to rounding.
TEST(AxialTorsionalRoughness, ZeroRoughnessIsTheSmoothStartAndStaysSteady) {
  nlohmann::json doc = Nominal(60, 2, 2);
  doc["simulation"]["abs_tol"] = doc["simulation"]["rel_tol"] = 1e-9;
  const CaseRun smooth = RunDoc(doc);
  doc["model"]["rock"]["bottom_roughness"] = Roughness(0, 9);
  const CaseRun zero = RunDoc(doc);
  for (const char* name : {"bit_rpm", "top_torque_Nm", "wob_N", "depth_of_cut_m"})
    EXPECT_EQ(Channel(smooth, name), Channel(zero, name)) << name;
  std::printf("[ measured ] roughness 0 for 2 s: bit speed %.12f..%.12f rad/s\n", Get(zero, "bit_speed_min_rad_s"),
              Get(zero, "bit_speed_max_rad_s"));
  EXPECT_NEAR(Get(zero, "bit_speed_min_rad_s"), 2 * kPi, 1e-7);
  EXPECT_NEAR(Get(zero, "bit_speed_max_rad_s"), 2 * kPi, 1e-7);
  EXPECT_EQ(zero.summary.at("events").get<int>(), 0);
}

// The first blade pass cuts the rough bottom: at t = 0 the bit is at U = 0 and the previous blade passed at angle
// -2 pi / n over the steady helix displaced by h, so d(0) = d0 - n h(-2 pi / n) per revolution.
TEST(AxialTorsionalRoughness, TheFirstBladePassCutsTheRoughBottom) {
  constexpr double kRms = 1e-5;
  constexpr int kBlades = 5;
  nlohmann::json doc = Nominal(60, 0.1, 0.1);
  ASSERT_EQ(doc["model"]["bit"]["blades"].get<int>(), kBlades);
  for (int seed : {1, 2, 3}) {
    doc["model"]["rock"]["bottom_roughness"] = Roughness(kRms, seed);
    const CaseRun run = RunDoc(doc);
    const double d0 = Get(run, "steady_depth_of_cut_m");
    const double h = bitrock::BottomRoughness(kRms, seed, 20).Depth(-2 * kPi / kBlades);  // 20: the default modes
    const double d = Channel(run, "depth_of_cut_m").front();
    std::printf("[ measured ] seed %d: depth of cut at t = 0 %.12f m, steady %.12f, closed form %.12f\n", seed, d, d0,
                d0 - kBlades * h);
    EXPECT_NEAR(d, d0 - kBlades * h, 1e-10);
    EXPECT_GT(std::abs(d - d0), 1e-8);
  }
}

// The same seed, the same run; another seed, another run (the roughness is the only disturbance).
TEST(AxialTorsionalRoughness, ASeedReproducesARunAndAnotherSeedDoesNot) {
  nlohmann::json doc = Nominal(60, 5, 5);
  doc["model"]["rock"]["bottom_roughness"] = Roughness(1e-5, 4);
  const CaseRun first = RunDoc(doc), again = RunDoc(doc);
  doc["model"]["rock"]["bottom_roughness"]["seed"] = 5;
  const CaseRun other = RunDoc(doc);
  for (const char* name : {"bit_rpm", "top_torque_Nm", "wob_N", "depth_of_cut_m"}) {
    EXPECT_EQ(Channel(first, name), Channel(again, name)) << name;
    EXPECT_NE(Channel(first, name), Channel(other, name)) << name;
  }
}

TEST(AxialTorsionalRoughness, RefusesAnAmplitudeBeyondAMillimetreAndANegativeSeed) {
  const std::pair<nlohmann::json, std::string> bad[] = {
      {Roughness(2e-3, 1), "/model/rock/bottom_roughness/rms_m"},
      {Roughness(-1e-6, 1), "/model/rock/bottom_roughness/rms_m"},
      {Roughness(1e-5, -1), "/model/rock/bottom_roughness/seed"},
      {{{"rms_m", 1e-5}}, "/model/rock/bottom_roughness/seed"}};
  ExpectEachRefusedNaming("bottom_roughness", bad);
}

// The rock's strength heterogeneity (rock/strength_heterogeneity) drives the coupled run: with 1 % the channels
// differ from homogeneous rock, with std 0 they are the same to the byte, and bad values are refused by name.
nlohmann::json Heterogeneity(double std, int seed) {
  return {{"std", std}, {"correlation_m", 2e-3}, {"seed", seed}};
}

TEST(AxialTorsionalHeterogeneity, OnePercentChangesTheRunAndZeroIsHomogeneousRockToTheByte) {
  nlohmann::json doc = Nominal(60, 2, 2);
  const CaseRun homogeneous = RunDoc(doc);
  doc["model"]["rock"]["strength_heterogeneity"] = Heterogeneity(0, 9);
  const CaseRun zero = RunDoc(doc);
  doc["model"]["rock"]["strength_heterogeneity"] = Heterogeneity(0.01, 9);
  const CaseRun rough = RunDoc(doc);
  for (const char* name : {"bit_rpm", "top_torque_Nm", "wob_N", "depth_of_cut_m"}) {
    EXPECT_EQ(Channel(homogeneous, name), Channel(zero, name)) << name;
    EXPECT_NE(Channel(homogeneous, name), Channel(rough, name)) << name;
  }
  const auto& w0 = Channel(homogeneous, "wob_N");
  const auto& w1 = Channel(rough, "wob_N");
  double largest = 0;
  for (std::size_t i = 0; i < std::min(w0.size(), w1.size()); ++i) largest = std::max(largest, std::abs(w1[i] - w0[i]));
  std::printf("[ measured ] 1 %% heterogeneity, 2 s: largest weight-on-bit change %.1f N of %.0f N\n", largest,
              w0.front());
}

// Both drilling kinds linearize about the mean rock: with 1 % heterogeneity the linear system is the homogeneous one
// to the bit, and the steady state says what became of the heterogeneity (a forcing and a gain modulation along the
// drilled depth, outside the time-invariant part).
TEST(AxialTorsionalHeterogeneity, LinearizationIsAboutTheMeanRockAndSaysSo) {
  for (const char* name : {"baseline-coupled-stability", "rgd-lumped"}) {
    nlohmann::json doc = testing::LoadCase(name);
    doc.erase("expect");
    const auto homogeneous = ParseCase(doc).model->Linearize();
    doc["model"]["rock"]["strength_heterogeneity"] = Heterogeneity(0.01, 9);
    const auto heterogeneous = ParseCase(doc).model->Linearize();
    ASSERT_EQ(homogeneous.size(), 1u) << name;
    ASSERT_EQ(heterogeneous.size(), 1u) << name;
    const auto &a = homogeneous[0].system, &b = heterogeneous[0].system;
    EXPECT_EQ(a.a0, b.a0) << name;
    ASSERT_EQ(a.delays.size(), b.delays.size()) << name;
    for (std::size_t k = 0; k < a.delays.size(); ++k) {
      EXPECT_EQ(a.delays[k].tau, b.delays[k].tau) << name;
      EXPECT_EQ(a.delays[k].retarded, b.delays[k].retarded) << name;
      EXPECT_EQ(a.delays[k].neutral, b.delays[k].neutral) << name;
    }
    EXPECT_FALSE(homogeneous[0].steady_state.contains("rock_strength_heterogeneity")) << name;
    ASSERT_TRUE(heterogeneous[0].steady_state.contains("rock_strength_heterogeneity")) << name;
    EXPECT_EQ(heterogeneous[0].steady_state["rock_strength_heterogeneity"]["strength_std"], 0.01) << name;
  }
}

TEST(AxialTorsionalHeterogeneity, RefusesBadValuesNamingTheField) {
  const std::pair<nlohmann::json, std::string> bad[] = {
      {Heterogeneity(0.3, 1), "/model/rock/strength_heterogeneity/std"},
      {Heterogeneity(-0.01, 1), "/model/rock/strength_heterogeneity/std"},
      {{{"std", 0.01}, {"correlation_m", 0}, {"seed", 1}}, "/model/rock/strength_heterogeneity/correlation_m"},
      {Heterogeneity(0.01, -1), "/model/rock/strength_heterogeneity/seed"},
      {{{"std", 0.01}, {"seed", 1}}, "/model/rock/strength_heterogeneity/correlation_m"}};
  ExpectEachRefusedNaming("strength_heterogeneity", bad);
}

}  // namespace
}  // namespace drillwave::cases
