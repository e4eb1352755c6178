// The top-drive components of the axial_torsional kind added with the induction motor (chapter eqs. 2.18-2.19) and
// the gear (rigid, or compliant: the rig's two-mass model): steady drilling on the motor's torque-speed curve, the
// free two-mass motion against its closed form, and a rigid gear against the motor referred to the top drive.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/io/json_reader.hpp"
#include "drive_rows.hpp"
#include "equivalent_circuit.hpp"
#include "two_mass_reference.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

constexpr double kOmega = 150 * kPi / 30, kRatio = 8, kMotorInertia = 10, kStiffness = 3e5, kGearDamping = 20;

// The baseline at a constant 150 rpm (steady drilling from t = 0), run for `duration` s at tolerance 1e-9.
nlohmann::json Steady(double duration, double interval) {
  nlohmann::json doc = testing::LoadCase("baseline-150rpm");
  doc["model"]["top"]["speed_rad_s"] = kOmega;
  doc["simulation"]["duration_s"] = duration;
  doc["simulation"]["output_interval_s"] = interval;
  doc["simulation"]["abs_tol"] = doc["simulation"]["rel_tol"] = 1e-9;
  doc["statistics"]["window_s"] = {0, duration};
  doc.erase("expect");
  return doc;
}
nlohmann::json InductionMotorJson() {
  return {{"pole_pairs", 2},
          {"stator_resistance_ohm", 0.01},
          {"rotor_resistance_ohm", 0.01},
          {"stator_leakage_inductance_H", 0.2e-3},
          {"rotor_leakage_inductance_H", 0.2e-3},
          {"magnetizing_inductance_H", 8e-3},
          {"volts_per_hertz_V_per_Hz", 11.5}};
}
const std::vector<double>& Values(const CaseRun& run, const std::string& name) { return run.result.channel(name).values; }
double MaxDeviation(const std::vector<double>& v, double target) {
  double worst = 0;
  for (double x : v) worst = std::max(worst, std::abs(x - target));
  return worst;
}

// Steady drilling's top torque (BASELINE.md, RGD): cutting a^2 eps d0 / 2 + friction a gamma mu a sigma l / 2 + the
// string's viscous drag c_t L Omega, with d0 = (W0 - a sigma l) / (a zeta eps).
double SteadyTopTorque(const nlohmann::json& md) {
  const double a = md["bit"]["radius_m"], eps = md["rock"]["intrinsic_specific_energy_Pa"], zeta = md["rock"]["zeta"];
  const double sigma_l = md["rock"]["sigma_l_N_per_m"], mu = md["rock"]["mu"], gamma = md["rock"]["gamma"];
  const double w0 = md["hoist"]["weight_on_bit_N"], d0 = (w0 - a * sigma_l) / (a * zeta * eps);
  return 0.5 * a * a * eps * d0 + 0.5 * a * gamma * mu * a * sigma_l +
         md["string"]["torsional_damping_Nms_per_rad_m"].get<double>() * md["string"]["length_m"].get<double>() * kOmega;
}

// The run starts on the motor's torque-speed curve: at the supply frequency where the equivalent circuit gives the
// steady top torque (through the gear) at n Omega, and stays there.
TEST(AxialTorsionalTop, InductionMotorDrillsSteadilyOnItsTorqueSpeedCurve) {
  nlohmann::json doc = Steady(2, 0.01);
  doc["model"]["top"]["induction_motor"] = InductionMotorJson();
  doc["model"]["top"]["gear"] = {{"ratio", kRatio}};
  const CaseRun run = RunCase(ParseCase(doc));
  const double torque = SteadyTopTorque(doc["model"]), shaft = kRatio * kOmega;
  const model::InductionMotor m = testing::IllustrativeMachine();
  const double synchronous_hz = m.pole_pairs * shaft / (2 * kPi);
  const double f = testing::Bisect([&](double hz) { return torque / kRatio - testing::EquivalentCircuit(m, hz, shaft).torque; },
                                   synchronous_hz * (1 + 1e-12), synchronous_hz + 1);
  const double current = testing::EquivalentCircuit(m, f, shaft).stator_current;
  const double reported = run.summary.at("steady_supply_frequency_Hz");
  std::printf("[ measured ] supply %.9f Hz (equivalent circuit %.9f Hz, synchronous %.6f Hz), stator %.6f A (circuit "
              "%.6f A), top torque off by %.3g N m, bit speed by %.3g rad/s\n", reported, f, synchronous_hz,
              Values(run, "top_current_A").back(), current, MaxDeviation(Values(run, "top_torque_Nm"), torque),
              MaxDeviation(Values(run, "bit_rpm"), 150) * kPi / 30);
  EXPECT_NEAR(reported, f, 1e-9 * f);
  EXPECT_LT(MaxDeviation(Values(run, "top_torque_Nm"), torque), 1e-6 * torque);
  EXPECT_LT(MaxDeviation(Values(run, "top_current_A"), current), 1e-6 * current);
  EXPECT_LT(MaxDeviation(Values(run, "bit_rpm"), 150), 1e-6 * 150);
}

// A set-point step from 150 to 160 rpm: the slip-compensated drive under the PI brings the string to the new speed,
// and the top torque to the steady torque there.
TEST(AxialTorsionalTop, InductionMotorFollowsASetPointStep) {
  nlohmann::json doc = Steady(40, 0.01);
  doc["model"]["top"]["induction_motor"] = InductionMotorJson();
  doc["model"]["top"]["gear"] = {{"ratio", kRatio}};
  const double target = 160 * kPi / 30;
  doc["model"]["top"]["speed_rad_s"] = {{"knots", {{1, kOmega}, {2, target}}}};
  const CaseRun run = RunCase(ParseCase(doc));
  const double top = Values(run, "top_rpm").back() * kPi / 30;
  std::printf("[ measured ] 40 s after the step: top %.9f rad/s (set-point %.9f), %d stick onsets\n", top, target,
              run.summary.at("stick_onsets").get<int>());
  EXPECT_NEAR(top, target, 1e-3 * target);
  EXPECT_EQ(run.summary.at("stick_onsets").get<int>(), 0);
}

// Drilling steadily behind a compliant gear: the gear carries the steady top torque wound up by T0 / k, the motor
// turns n times faster.
TEST(AxialTorsionalTop, CompliantGearCarriesTheSteadyTorque) {
  nlohmann::json doc = Steady(2, 0.01);
  doc["model"]["top"]["gear"] = {{"ratio", kRatio}, {"stiffness_Nm_per_rad", kStiffness}, {"damping_Nms_per_rad", kGearDamping}};
  doc["model"]["top"]["motor_inertia_kgm2"] = kMotorInertia;
  const CaseRun run = RunCase(ParseCase(doc));
  const double torque = SteadyTopTorque(doc["model"]);
  EXPECT_LT(MaxDeviation(Values(run, "gear_torque_Nm"), torque), 1e-6 * torque);
  EXPECT_LT(MaxDeviation(Values(run, "motor_rpm"), kRatio * 150), 1e-6 * kRatio * 150);
  EXPECT_LT(MaxDeviation(Values(run, "bit_rpm"), 150), 1e-6 * 150);
}

// The PI gains at 0: the motor loses the steady torque T0 at t = 0. Until the first wave comes back up the undamped
// string (2 L / c = 1.247 s) the top sees the string as a dashpot of its impedance Z = J sqrt(G rho), and the motor,
// gear and top drive follow the two-mass system's exact response to a torque step -T0 on the motor.
TEST(AxialTorsionalTop, CompliantGearFreeMotionIsTheTwoMassSolution) {
  nlohmann::json doc = Steady(1.2, 1e-3);
  auto& md = doc["model"];
  md["string"]["torsional_damping_Nms_per_rad_m"] = 0.0;
  md["top"]["kp_Nms_per_rad"] = md["top"]["ki_Nm_per_rad"] = 0.0;
  md["top"]["gear"] = {{"ratio", kRatio}, {"stiffness_Nm_per_rad", kStiffness}, {"damping_Nms_per_rad", kGearDamping}};
  md["top"]["motor_inertia_kgm2"] = kMotorInertia;
  const CaseRun run = RunCase(ParseCase(doc));
  const auto& s = md["string"];
  const double od = s["outer_diameter_m"], id = s["inner_diameter_m"];
  const double z = kPi / 32 * (std::pow(od, 4) - std::pow(id, 4)) *
                   std::sqrt(s["shear_modulus_Pa"].get<double>() * s["density_kg_m3"].get<double>());
  const double t0 = SteadyTopTorque(md);
  const testing::TwoMassOnDashpot rig{kRatio * kRatio * kMotorInertia, kStiffness, kGearDamping,
                                      md["top"]["inertia_kgm2"].get<double>(), z};
  const std::vector<double>& t = run.result.time_s;
  double worst = 0, swing = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const Eigen::Vector3d y = rig.Response(t[k], Eigen::Vector3d::Zero(), -t0);  // deviation from steady drilling
    worst = std::max({worst, std::abs(Values(run, "top_rpm")[k] * kPi / 30 - (kOmega + y(2))),
                      std::abs(Values(run, "motor_rpm")[k] * kPi / 30 / kRatio - (kOmega + y(0))),
                      std::abs(Values(run, "gear_torque_Nm")[k] - (t0 + rig.GearTorque(y))) / z});
    swing = std::max(swing, std::abs(y(0)));
  }
  std::printf("[ measured ] largest deviation from the two-mass solution %.3g rad/s (motor speed swings by %.3g "
              "rad/s; mode %.4f rad/s, undamped closed form %.4f)\n", worst, swing, rig.DampedFrequency(),
              rig.UndampedFrequency());
  EXPECT_GT(swing, 0.1);
  EXPECT_LT(worst, 1e-6 * kOmega);
}

// A DC motor of constant K behind a rigid gear of ratio n is a motor of constant n K on a top drive heavier by
// n^2 J_m, through a set-point bump that makes the bit stick and slip.
TEST(AxialTorsionalTop, RigidGearIsTheMotorReferredToTheTopDrive) {
  nlohmann::json geared = testing::LoadCase("baseline-60rpm");
  geared.erase("expect");
  geared["simulation"]["duration_s"] = 15;
  geared["statistics"]["window_s"] = {5, 15};
  nlohmann::json referred = geared;
  geared["model"]["top"]["motor"] = {{"motor_constant_Nm_per_A", 50}, {"resistance_ohm", 0.05}, {"inductance_H", 0.005}};
  geared["model"]["top"]["gear"] = {{"ratio", kRatio}};
  geared["model"]["top"]["motor_inertia_kgm2"] = kMotorInertia;
  referred["model"]["top"]["motor"] = {{"motor_constant_Nm_per_A", 50 * kRatio}, {"resistance_ohm", 0.05}, {"inductance_H", 0.005}};
  referred["model"]["top"]["inertia_kgm2"] = geared["model"]["top"]["inertia_kgm2"].get<double>() + kRatio * kRatio * kMotorInertia;
  const CaseRun a = RunCase(ParseCase(geared)), b = RunCase(ParseCase(referred));
  EXPECT_GT(a.summary.at("stick_onsets").get<int>(), 0);
  for (const char* name : {"top_rpm", "bit_rpm", "top_torque_Nm", "top_current_A"}) {
    ASSERT_EQ(Values(a, name).size(), Values(b, name).size());
    for (std::size_t k = 0; k < Values(a, name).size(); ++k)
      EXPECT_NEAR(Values(a, name)[k], Values(b, name)[k], 1e-9 * (1 + std::abs(Values(b, name)[k]))) << name;
  }
}

// The coupled kind's linearization holds the top drive as the component its run uses (dynamics::TopDrive): the rows
// of the drive's own states (the PI's integral, a DC motor's current commanded as torque, an induction motor's
// fluxes, a compliant gear's motor speed and twist) are the component's rates differentiated by central differences
// about its steady start, for those states and the top drive's speed.
double WorstTopRowDifference(const nlohmann::json& doc, const dynamics::TopDriveParts& parts, int& compared) {
  const auto points = ParseCase(doc).model->Linearize();
  EXPECT_EQ(points.size(), 1u);
  if (points.empty()) return 1.0;
  const LinearizedOperatingPoint& p = points.front();
  auto index = [&](const std::string& name) {
    const auto it = std::find(p.state_names.begin(), p.state_names.end(), "torsion_top_" + name);
    return it == p.state_names.end() ? -1 : static_cast<int>(it - p.state_names.begin());
  };
  dynamics::TopDrive::Slots slots;
  slots.integral = index("speed_error_integral_rad");
  slots.current = index("current_A");
  slots.flux = index("stator_flux_d_Wb");
  slots.motor_speed = index("motor_speed_referred_rad_s");
  const int speed = index("speed_rad_s");
  EXPECT_GE(slots.integral, 0);
  EXPECT_GE(speed, 0);
  if (slots.integral < 0 || speed < 0) return 1.0;
  const double top_torque = p.steady_state.at("top_torque_Nm");
  const dynamics::TopDrive drive(parts, slots, kOmega, top_torque);
  std::vector<double> x(p.system.dimension(), 0.0);
  drive.SteadyStart(top_torque, x);
  x[speed] = kOmega;
  return testing::WorstDriveRowDifference(p.system, drive, slots, speed, x, compared);
}

TEST(AxialTorsionalTop, LinearizationsDriveRowsAreTheComponentsRatesDifferentiated) {
  const nlohmann::json base = Steady(2, 0.01);
  const model::Schedule setpoint(kOmega);
  const model::PiController pi{base["model"]["top"]["kp_Nms_per_rad"].get<double>(),
                               base["model"]["top"]["ki_Nm_per_rad"].get<double>()};
  const model::TopDriveLaw law;
  const model::InductionMotor machine = testing::IllustrativeMachine();
  auto parts_of = [&](model::Drive drive) {
    dynamics::TopDriveParts parts;
    parts.drive = drive, parts.setpoint = &setpoint, parts.pi = &pi, parts.law = &law, parts.induction = &machine;
    return parts;
  };
  struct Kind {
    std::string name;
    nlohmann::json doc;
    dynamics::TopDriveParts parts;
  };
  std::vector<Kind> kinds;
  kinds.push_back({"DC motor commanding torque", base, parts_of(model::Drive::kDcMotorSpeed)});
  kinds.back().doc["model"]["top"]["motor"] = {
      {"motor_constant_Nm_per_A", 50}, {"resistance_ohm", 0.05}, {"inductance_H", 0.005}};
  kinds.back().parts.dc = {50, 0.05, 0.005, 0};
  kinds.back().parts.dc_torque_command = true;
  kinds.push_back({"induction motor through a gear", base, parts_of(model::Drive::kInductionMotorSpeed)});
  kinds.back().doc["model"]["top"]["induction_motor"] = InductionMotorJson();
  kinds.back().doc["model"]["top"]["gear"] = {{"ratio", kRatio}};
  kinds.back().parts.gear.ratio = kRatio;
  kinds.push_back({"PI behind a compliant gear", base, parts_of(model::Drive::kPiSpeedController)});
  kinds.back().doc["model"]["top"]["gear"] = {
      {"ratio", kRatio}, {"stiffness_Nm_per_rad", kStiffness}, {"damping_Nms_per_rad", kGearDamping}};
  kinds.back().doc["model"]["top"]["motor_inertia_kgm2"] = kMotorInertia;
  kinds.back().parts.gear = {kRatio, kStiffness, kGearDamping, kMotorInertia};
  for (const Kind& k : kinds) {
    int compared = 0;
    const double worst = WorstTopRowDifference(k.doc, k.parts, compared);
    std::printf("[ measured ] coupled kind, %s: %d entries, largest difference %.3g of the row's largest\n",
                k.name.c_str(), compared, worst);
    EXPECT_LT(worst, 1e-6) << k.name;
    EXPECT_GE(compared, 4) << k.name;
  }
}

}  // namespace
}  // namespace drillwave::cases
