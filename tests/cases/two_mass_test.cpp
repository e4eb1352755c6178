// The two-mass pendulum (kind two_mass, chapter eqs. 2.1-2.4): energy balance recomputed from the sampled output
// channels for every top drive and several bit laws (set-valued with stick phases among them), the steady state
// under a constant torque, and the measured top speed above which stick-slip disappears at W = 97 347 N.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

using testing::LoadCase;

RunResult RunDoc(const nlohmann::json& doc) { return RunCase(ParseCase(doc)).result; }

struct EnergyBudget {
  double work_in, dissipated, stored_change;
};

// Work in = integral of drive torque x top speed; dissipation = integral of c (w_t - w_b)^2 + d_t w_t^2 + d_b w_b^2
// + T_bit w_b; stored = kinetic + spring, the twist taken from the shaft torque. Trapezoidal rule on the samples:
// independent of the integrated energy states the kind carries.
EnergyBudget BudgetFromChannels(const nlohmann::json& doc, const RunResult& r) {
  const auto& m = doc.at("model");
  const double jt = m.at("top").at("inertia_kgm2"), jb = m.at("bit").at("inertia_kgm2"),
               k = m.at("string").at("stiffness_Nm_per_rad"), c = m.at("string").at("damping_Nms_per_rad"),
               dt_ = m.at("top").at("damping_Nms_per_rad"), db = m.at("bit").at("damping_Nms_per_rad");
  constexpr double kRpm = 60.0 / (2.0 * kPi);
  const auto& t = r.time_s;
  const auto& top = r.channel("top_rpm").values;
  const auto& bit = r.channel("bit_rpm").values;
  const auto& shaft = r.channel("top_torque_Nm").values;
  const auto& friction = r.channel("bit_torque_Nm").values;
  const auto& drive = r.channel("drive_torque_Nm").values;
  auto power_in = [&](std::size_t i) { return drive[i] * top[i] / kRpm; };
  auto power_out = [&](std::size_t i) {
    const double wt = top[i] / kRpm, wb = bit[i] / kRpm;
    return c * (wt - wb) * (wt - wb) + dt_ * wt * wt + db * wb * wb + friction[i] * wb;
  };
  auto stored = [&](std::size_t i) {
    const double wt = top[i] / kRpm, wb = bit[i] / kRpm, twist = (shaft[i] - c * (wt - wb)) / k;
    return 0.5 * jt * wt * wt + 0.5 * jb * wb * wb + 0.5 * k * twist * twist;
  };
  EnergyBudget b{0, 0, stored(t.size() - 1) - stored(0)};
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double h = t[i] - t[i - 1];
    b.work_in += 0.5 * h * (power_in(i - 1) + power_in(i));
    b.dissipated += 0.5 * h * (power_out(i - 1) + power_out(i));
  }
  return b;
}

struct Variant {
  const char* name;
  const char* base_case;
  const char* top;       // JSON of the top block, or "" to keep the case's
  const char* friction;  // JSON of the bit friction law, or "" to keep the case's
  const char* bit = "";  // JSON of fields merged into the bit block, or ""
};

class TwoMassEnergy : public ::testing::TestWithParam<Variant> {};

// Replaces the top's drive (type and its fields) and keeps the top's inertia and damper.
void ReplaceDrive(nlohmann::json& doc, nlohmann::json drive) {
  const nlohmann::json& top = doc["model"]["top"];
  for (const char* kept : {"inertia_kgm2", "damping_Nms_per_rad"})
    if (top.contains(kept)) drive[kept] = top[kept];
  doc["model"]["top"] = std::move(drive);
}

TEST_P(TwoMassEnergy, WorkInEqualsDissipationPlusStoredEnergy) {
  const Variant& v = GetParam();
  nlohmann::json doc = LoadCase(v.base_case);
  if (*v.top) ReplaceDrive(doc, nlohmann::json::parse(v.top));
  if (*v.friction) doc["model"]["bit"]["friction"] = nlohmann::json::parse(v.friction);
  if (*v.bit) doc["model"]["bit"].update(nlohmann::json::parse(v.bit));
  doc.erase("expect");
  doc["simulation"]["abs_tol"] = doc["simulation"]["rel_tol"] = 1e-9;  // the bound below is the integrator's at 1e-9
  doc["simulation"]["duration_s"] = 120;
  doc["simulation"]["output_interval_s"] = 1e-3;
  doc["statistics"]["window_s"] = {60, 120};
  const RunResult r = RunDoc(doc);
  const EnergyBudget b = BudgetFromChannels(doc, r);
  const double residual = b.work_in - b.dissipated - b.stored_change;
  const double integrated = r.summary.at("energy_balance_residual_max_J").get<double>();
  std::printf("[ measured ] %-24s work in %.6e J, dissipated %.6e J, stored change %.6e J; residual from samples "
              "%.2e (relative %.1e), integrated %.1e J; %d stick onsets in [60, 120] s\n",
              v.name, b.work_in, b.dissipated, b.stored_change, residual, residual / b.work_in, integrated,
              r.summary.at("stick_onsets").get<int>());
  EXPECT_GT(b.work_in, 0);
  EXPECT_LT(std::abs(residual), 2e-5 * b.work_in);
  EXPECT_LT(integrated, 1e-8 * b.work_in);
}

INSTANTIATE_TEST_SUITE_P(
    DrivesAndLaws, TwoMassEnergy,
    ::testing::Values(
        // Prescribed top speed, set-valued Stribeck bit: stick-slip (Navarro-Lopez parameter set).
        Variant{"prescribed_stribeck", "two-mass-stickslip", "", ""},
        // PI top, set-valued Coulomb bit with a weight-on-bit step.
        Variant{"pi_coulomb_wob_step", "two-mass-pi-coulomb", "", ""},
        // Torque top, set-valued Stribeck bit: stuck until the shaft torque passes W R mu_s = 12 115 N m, then free.
        Variant{"torque_stribeck", "two-mass-stickslip", R"({"type": "torque", "torque_Nm": {"knots": [[0, 0], [5, 12500]]}})",
                ""},
        // PI top, smooth laws (chapter eqs. 2.29, 2.30) and the humped set-valued law scaled up to drill-string size.
        Variant{"pi_sqrt_regularized", "two-mass-pi-coulomb", "",
                R"({"law": "sqrt_regularized", "amplitude_Nm": 9000, "alpha": 1, "epsilon_rad_s": 0.5})"},
        Variant{"pi_humped", "two-mass-pi-coulomb", "",
                R"({"law": "humped", "T_sl_Nm": 9000, "T_1_Nm": -4000, "omega_1_s_per_rad": 0.5, "T_2_Nm": 1000,
                    "omega_2_s_per_rad": 5, "b_l_Nms_per_rad": 100})"},
        // The UFRJ rig's laws (issue 32): a droop drive whose torque limit acts in the stick phases, friction that
        // falls linearly with speed, and the same under a normal load that follows the torque on bit.
        Variant{"rig_torque_limit_linear", "ufrj-rig",
                R"({"type": "top_drive", "kp_Nms_per_rad": 0.22, "ki_Nm_per_rad": 0, "speed_rad_s": 18.3,
                    "torque_limit_Nm": 3.0})",
                R"({"law": "linear_weakening", "T_s_Nm": 2.9, "T_0_Nm": 2.75, "weakening_Nms_per_rad": 0.09})"},
        // (Its load raises the break-away torque to 2.9 x 444 / 396 = 3.25 N m: a limit of 3.0 would stall it.)
        Variant{"rig_normal_load", "ufrj-rig",
                R"({"type": "top_drive", "kp_Nms_per_rad": 0.22, "ki_Nm_per_rad": 0, "speed_rad_s": 18.3,
                    "torque_limit_Nm": 3.5})",
                R"({"law": "linear_weakening", "T_s_Nm": 2.9, "T_0_Nm": 2.75, "weakening_Nms_per_rad": 0.09})",
                R"({"normal_load": {"torque_gain_N_per_Nm": 60, "reference_torque_Nm": 2.1,
                                    "time_constant_s": 0.02}})"}),
    [](const ::testing::TestParamInfo<Variant>& info) { return std::string(info.param.name); });

TEST(TwoMass, SteadyStateUnderConstantTorqueWithViscousBit) {
  // Constant top torque T, viscous bit c_v: both inertias end at w = T / (d_top + d_bit + c_v), twist (T - d_top w) / k.
  nlohmann::json doc = LoadCase("two-mass-stickslip");
  ReplaceDrive(doc, {{"type", "torque"}, {"torque_Nm", 5000.0}});
  doc["model"]["bit"]["friction"] = {{"law", "viscous"}, {"c_Nms_per_rad", 25.0}};
  doc["simulation"]["duration_s"] = 300;
  doc["statistics"]["window_s"] = {250, 300};
  const RunResult r = RunDoc(doc);
  const double w = 5000.0 / (425 + 50 + 25);
  const double shaft = 5000.0 - 425 * w;
  EXPECT_NEAR(r.summary.at("bit_speed_min_rad_s").get<double>(), w, 1e-7 * w);
  EXPECT_NEAR(r.summary.at("bit_speed_max_rad_s").get<double>(), w, 1e-7 * w);
  EXPECT_NEAR(r.channel("top_torque_Nm").values.back(), shaft, 1e-7 * shaft);
  EXPECT_NEAR(r.channel("bit_torque_Nm").values.back(), 25 * w, 1e-7 * 25 * w);
}

TEST(TwoMass, StickSlipDisappearsAboveTheMeasuredTopSpeed) {
  // Navarro-Lopez parameter set, W = 97 347 N, top speed ramped from rest in 2 s: stick-slip persists up to
  // 10.7892 rad/s and is gone from 10.7894 rad/s on (bisection on stick onsets in [150, 300] s).
  nlohmann::json doc = LoadCase("two-mass-stickslip");
  auto onsets_at = [&](double speed) {
    doc["model"]["top"]["speed_rad_s"]["knots"][1][1] = speed;
    return RunDoc(doc).summary.at("stick_onsets").get<int>();
  };
  EXPECT_GT(onsets_at(10.7892), 10);
  EXPECT_EQ(onsets_at(10.7894), 0);
}

TEST(TwoMass, SmoothRotationCoexistsWithStickSlipBelowTheThreshold) {
  // Coming down from smooth rotation at 12 rad/s, the bit keeps turning smoothly at 6 rad/s, where a start from rest
  // ends in stick-slip: the equilibrium is linearly stable for c + d_bit + T'(w) > 0, i.e. w > 4.12 rad/s.
  nlohmann::json doc = LoadCase("two-mass-stickslip");
  doc["model"]["top"]["speed_rad_s"] = {{"knots", {{0, 0}, {2, 12}, {60, 12}, {100, 6}}}};
  doc["statistics"]["window_s"] = {200, 300};
  const RunResult from_above = RunDoc(doc);
  EXPECT_EQ(from_above.summary.at("stick_onsets").get<int>(), 0);
  EXPECT_NEAR(from_above.summary.at("bit_speed_min_rad_s").get<double>(), 6, 1e-3);
  doc["model"]["top"]["speed_rad_s"] = {{"knots", {{0, 0}, {2, 6}}}};
  EXPECT_GT(RunDoc(doc).summary.at("stick_onsets").get<int>(), 10);
}

TEST(TwoMass, AFrictionSmoothingTooSmallToIntegrateIsRefused) {
  // tanh(w / 1e-300) asked for 1e8 evaluations within 0.01 s; 0 is the exact set-valued law.
  nlohmann::json doc = LoadCase("two-mass-stickslip");
  for (double eps : {1e-300, 1e-7}) {
    doc["model"]["friction_smoothing_rad_s"] = eps;
    try {
      ParseCase(doc);
      ADD_FAILURE() << "accepted " << eps;
    } catch (const InputError& e) {
      EXPECT_EQ(e.json_path(), "/model/friction_smoothing_rad_s");
    }
  }
  doc["model"]["friction_smoothing_rad_s"] = 1e-6;
  EXPECT_NO_THROW(ParseCase(doc));
}

}  // namespace
}  // namespace drillwave::cases
