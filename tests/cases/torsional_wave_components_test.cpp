// The optional string and bit components of the torsional_wave kind: Kelvin-Voigt damping and the BHA mass unbalance
// (the physics is checked on the network in tests/waves/kelvin_voigt_test.cpp and jeffcott_bit_test.cpp; here what
// the kind builds from its fields, and how it refuses bad input).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "refused_path.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

nlohmann::json Load(const char* name) {
  nlohmann::json doc = testing::LoadCase(name);
  doc.erase("expect");
  return doc;
}
const std::vector<double>& Channel(const CaseRun& run, const std::string& name) {
  for (const auto& c : run.result.channels)
    if (c.name == name) return c.values;
  throw std::runtime_error("no channel " + name);
}
using testing::RefusedPath;

// eta = 0 takes the code path without dashpots: the same trajectory, bit for bit.
TEST(TorsionalWaveKelvinVoigt, ZeroIsTheRunWithoutIt) {
  nlohmann::json plain = Load("saldivar-stickslip");
  plain["simulation"]["duration_s"] = 8;
  plain["statistics"]["window_s"] = {4, 8};
  nlohmann::json zero = plain;
  zero["model"]["string"]["kelvin_voigt_s"] = 0.0;
  const CaseRun a = RunCase(ParseCase(plain)), b = RunCase(ParseCase(zero));
  EXPECT_EQ(Channel(a, "bit_rpm"), Channel(b, "bit_rpm"));
  EXPECT_EQ(Channel(a, "top_torque_Nm"), Channel(b, "top_torque_Nm"));
}

// A pipe given as 16 consecutive parts of the same impedance and wave speed is the one pipe: the junctions scatter
// nothing, so the kind joins them, and the run (with distributed damping, whose sub-sections are laid per section) is
// the one-section run to 1e-6 rpm (the summed travel times round apart). Not joined, the cut put 16 x 20 damping parts
// where there are 20, another discretization of the damping: 0.032 rpm apart.
TEST(TorsionalWaveSections, PartsOfOnePipeAreTheOnePipe) {
  nlohmann::json one = Load("saldivar-stickslip");
  one["simulation"]["duration_s"] = 8;
  one["statistics"]["window_s"] = {4, 8};
  one["model"]["string"]["torsional_damping_Nms_per_rad_m"] = 0.05;
  nlohmann::json parts = one;
  const nlohmann::json pipe = one["model"]["string"]["sections"][0];
  parts["model"]["string"]["sections"] = nlohmann::json::array();
  for (int k = 0; k < 16; ++k) {
    nlohmann::json part = pipe;
    part["length_m"] = pipe["length_m"].get<double>() / 16;
    part["name"] = "part " + std::to_string(k);
    parts["model"]["string"]["sections"].push_back(part);
  }
  const CaseRun a = RunCase(ParseCase(one)), b = RunCase(ParseCase(parts));
  const auto &speed_a = Channel(a, "bit_rpm"), &speed_b = Channel(b, "bit_rpm");
  ASSERT_EQ(speed_a.size(), speed_b.size());
  double worst = 0;
  for (std::size_t i = 0; i < speed_a.size(); ++i) worst = std::max(worst, std::abs(speed_a[i] - speed_b[i]));
  std::printf("[ measured ] 16 parts against one pipe: bit speed within %.2e rpm over 8 s\n", worst);
  EXPECT_LT(worst, 1e-4);

}

// With eta > 0 the string is split into damping_subsections parts with a dashpot eta Z / tau across each: after a
// small top-speed bump on a free-turning bit the first mode dies out faster the larger eta, and the run stays near
// the imposed speed.
TEST(TorsionalWaveKelvinVoigt, DampsTheRingingAfterABump) {
  nlohmann::json doc = Load("saldivar-whirl");
  doc["model"]["bit"].erase("unbalance");
  doc["model"]["top"]["speed_rad_s"] = {{"knots", {{0, 12}, {1, 12.5}, {1.5, 12}}}};
  doc["simulation"]["duration_s"] = 12;
  doc["statistics"]["window_s"] = {8, 12};
  double spread[2];
  for (int with : {0, 1}) {
    doc["model"]["string"]["kelvin_voigt_s"] = with ? 0.05 : 0.0;
    const CaseRun run = RunCase(ParseCase(doc));
    spread[with] = run.summary["bit_speed_max_rad_s"].get<double>() - run.summary["bit_speed_min_rad_s"].get<double>();
  }
  std::printf("[ measured ] bit speed spread over [8, 12] s after the bump: %.3g rad/s without, %.3g with eta = 0.05 s\n",
              spread[0], spread[1]);
  EXPECT_LT(spread[1], 0.5 * spread[0]);
}

TEST(TorsionalWaveComponents, BadInputNamesTheField) {
  nlohmann::json doc = Load("saldivar-stickslip");
  doc["model"]["string"]["kelvin_voigt_s"] = -0.1;
  EXPECT_EQ(RefusedPath(doc), "/model/string/kelvin_voigt_s");
  doc["model"]["string"]["kelvin_voigt_s"] = 1e305;
  EXPECT_EQ(RefusedPath(doc), "/model/string/kelvin_voigt_s");
  doc["model"]["string"]["kelvin_voigt_s"] = 10.5;  // beyond the stated [0, 10] s (1e17 s gave a spurious root)
  EXPECT_EQ(RefusedPath(doc), "/model/string/kelvin_voigt_s");
  doc["model"]["string"]["kelvin_voigt_s"] = 10;
  EXPECT_EQ(RefusedPath(doc), "");
  // A massless bit with smooth friction closes the dashpots' node system (tests/waves/kelvin_voigt_test.cpp): accepted,
  // and linearized.
  doc = Load("saldivar-stickslip");
  doc["model"]["string"]["kelvin_voigt_s"] = 0.02;
  doc["model"]["bit"]["inertia_kgm2"] = 0;
  doc["model"]["bit"]["friction"] = {{"law", "viscous"}, {"c_Nms_per_rad", 50}};
  EXPECT_EQ(RefusedPath(doc, true), "");

  doc = Load("saldivar-whirl");
  doc["model"]["bit"]["unbalance"]["lateral_mass_kg"] = 0;
  EXPECT_EQ(RefusedPath(doc), "/model/bit/unbalance/lateral_mass_kg");
  doc = Load("saldivar-whirl");
  doc["model"]["bit"]["unbalance"]["eccentricty_m"] = 0.1;
  EXPECT_EQ(RefusedPath(doc), "/model/bit/unbalance/eccentricty_m");
  doc = Load("saldivar-whirl");
  doc["model"]["bit"]["inertia_kgm2"] = 0;
  EXPECT_EQ(RefusedPath(doc), "/model/bit/inertia_kgm2");

}

// The soft-torque family of tops (waves::TorqueFeedback). The SoftSpeed tuning is the PI with kp = Z of the top
// section, ki = J (2 pi / P)^2, and a z_torque top's default impedance is that Z: the runs with those gains written
// out are the same run (to rounding of the gains). Bad values and combinations are refused with their paths.
TEST(TorsionalWaveSoftTorque, TuningsAreTheGainsTheyStand) {
  nlohmann::json tuned = Load("saldivar-soft-torque");
  tuned["simulation"]["duration_s"] = 8;
  tuned["statistics"]["window_s"] = {4, 8};
  nlohmann::json& top = tuned["model"]["top"];
  const auto& pipe = tuned["model"]["string"]["sections"][0];
  const double z = pipe["polar_moment_m4"].get<double>() *
                   std::sqrt(pipe["shear_modulus_Pa"].get<double>() * pipe["density_kg_m3"].get<double>());
  const double period = 2.5, omega = 2 * kPi / period, inertia = top["inertia_kgm2"].get<double>();
  top.erase("kp_Nms_per_rad"), top.erase("ki_Nm_per_rad");
  top["tuning_period_s"] = period;
  nlohmann::json explicit_gains = tuned;
  explicit_gains["model"]["top"].erase("tuning_period_s");
  explicit_gains["model"]["top"]["kp_Nms_per_rad"] = z;
  explicit_gains["model"]["top"]["ki_Nm_per_rad"] = inertia * omega * omega;
  nlohmann::json z_default = Load("saldivar-z-torque");
  z_default["simulation"] = tuned["simulation"];
  z_default["statistics"] = tuned["statistics"];
  nlohmann::json z_explicit = z_default;
  z_explicit["model"]["top"]["impedance_Nms_per_rad"] = z;
  for (const auto& [a, b] : {std::pair{tuned, explicit_gains}, std::pair{z_default, z_explicit}}) {
    const CaseRun run_a = RunCase(ParseCase(a)), run_b = RunCase(ParseCase(b));
    const std::vector<double>& x = Channel(run_a, "bit_rpm");
    const std::vector<double>& y = Channel(run_b, "bit_rpm");
    ASSERT_EQ(x.size(), y.size());
    double worst = 0;
    for (std::size_t i = 0; i < x.size(); ++i) worst = std::max(worst, std::abs(x[i] - y[i]));
    std::printf("[ measured ] %s: largest bit-speed difference to the gains written out %.2e rpm\n",
                a["model"]["top"]["type"].get<std::string>().c_str(), worst);
    EXPECT_LT(worst, 1e-4);
  }
}

// Behind an actuator delay the set-point's knots are breakpoints again one delay later (the ramp's end at 2 s, at
// 2.05 s): stepped onto once each, although 2.05 - 0.05 rounds below 2.
TEST(TorsionalWaveSoftTorque, DelayedSetPointKnotsAreSteppedOntoOnce) {
  nlohmann::json doc = Load("saldivar-z-torque");
  doc["model"]["top"]["actuator_delay_s"] = 0.05;
  doc["simulation"]["duration_s"] = 4;
  doc["statistics"]["window_s"] = {3, 4};
  const CaseRun run = RunCase(ParseCase(doc));
  const int breakpoints = run.summary["breakpoints"].get<int>();
  std::printf("[ measured ] Z-Torque top with a 50 ms delay, 4 s from rest: %d breakpoints, %d steps\n", breakpoints,
              run.summary["steps"].get<int>());
  EXPECT_LT(breakpoints, 30);
  ASSERT_FALSE(run.result.time_s.empty());
  EXPECT_NEAR(run.result.time_s.back(), 4.0, 1e-9);
}

TEST(TorsionalWaveSoftTorque, BadInputNamesTheField) {
  auto with = [](const char* name, const char* key, const nlohmann::json& value) {
    nlohmann::json doc = Load(name);
    doc["model"]["top"][key] = value;
    return doc;
  };
  EXPECT_EQ(RefusedPath(with("saldivar-soft-torque", "feedback_gain_rad_per_Nms", -1e-3)),
            "/model/top/feedback_gain_rad_per_Nms");
  EXPECT_EQ(RefusedPath(with("saldivar-soft-torque", "feedback_time_constant_s", 0)),
            "/model/top/feedback_time_constant_s");
  EXPECT_EQ(RefusedPath(with("saldivar-soft-torque", "tuning_period_s", 2.5)), "/model/top/kp_Nms_per_rad");
  EXPECT_EQ(RefusedPath(with("saldivar-z-torque", "impedance_Nms_per_rad", 0)), "/model/top/impedance_Nms_per_rad");
  EXPECT_EQ(RefusedPath(with("saldivar-z-torque", "feedback_gain_rad_per_Nms", 1e-3)),
            "/model/top/feedback_gain_rad_per_Nms");  // z_torque's gain is 1 / Z
  nlohmann::json doc = Load("saldivar-soft-torque");
  doc["model"]["top"].erase("feedback_time_constant_s");  // needed with a gain
  EXPECT_EQ(RefusedPath(doc), "/model/top/feedback_time_constant_s");
  doc["model"]["top"].erase("feedback_gain_rad_per_Nms");  // without feedback: a PI top drive
  EXPECT_EQ(RefusedPath(doc, true), "");
  doc = with("saldivar-z-torque", "gear", {{"ratio", 8}, {"stiffness_Nm_per_rad", 3e5}});
  doc["model"]["top"]["motor_inertia_kgm2"] = 10;
  EXPECT_EQ(RefusedPath(doc), "/model/top/gear");
  EXPECT_EQ(RefusedPath(Load("saldivar-z-torque"), true), "");
  // The actuator delay: in [0, 10] s, on a PI top without Kelvin-Voigt damping (the delayed controller reads the
  // string torque from the arriving wave alone).
  EXPECT_EQ(RefusedPath(with("saldivar-z-torque", "actuator_delay_s", -0.05)), "/model/top/actuator_delay_s");
  EXPECT_EQ(RefusedPath(with("saldivar-z-torque", "actuator_delay_s", 11)), "/model/top/actuator_delay_s");
  EXPECT_EQ(RefusedPath(with("saldivar-z-torque", "actuator_delay_s", 0.1), true), "");
  doc = with("saldivar-z-torque", "actuator_delay_s", 0.1);
  doc["model"]["string"]["kelvin_voigt_s"] = 0.01;
  EXPECT_EQ(RefusedPath(doc), "/model/top");
  doc = Load("saldivar-stickslip");  // a dissipative top has no controller to delay
  doc["model"]["top"]["actuator_delay_s"] = 0.1;
  EXPECT_EQ(RefusedPath(doc), "/model/top/actuator_delay_s");
}

// The sliding-mode top's fields: its gains follow from the surface and the layer, so a PI's are refused; each of the
// three > 0 and the filter's time constant required (its command is Z-Torque's); behind a compliant gear refused as
// Z-Torque is (it reads the string torque at a top driven directly).
TEST(TorsionalWaveSlidingMode, BadInputNamesTheField) {
  auto with = [](const char* key, const nlohmann::json& value) {
    nlohmann::json doc = Load("saldivar-sliding-mode");
    doc["model"]["top"][key] = value;
    return doc;
  };
  EXPECT_EQ(RefusedPath(Load("saldivar-sliding-mode"), true), "");
  EXPECT_EQ(RefusedPath(with("kp_Nms_per_rad", 5000)), "/model/top/kp_Nms_per_rad");
  for (const char* key : {"surface_corner_rad_s", "reaching_rate_rad_s2", "boundary_layer_rad_s",
                          "feedback_time_constant_s", "impedance_Nms_per_rad"}) {
    EXPECT_EQ(RefusedPath(with(key, 0)), std::string("/model/top/") + key);
    if (std::string(key) == "impedance_Nms_per_rad") continue;  // optional: the top section's Z
    nlohmann::json doc = Load("saldivar-sliding-mode");
    doc["model"]["top"].erase(key);
    EXPECT_EQ(RefusedPath(doc), std::string("/model/top/") + key);
  }
  nlohmann::json doc = with("gear", {{"ratio", 8}, {"stiffness_Nm_per_rad", 3e5}});
  doc["model"]["top"]["motor_inertia_kgm2"] = 10;
  EXPECT_EQ(RefusedPath(doc), "/model/top/gear");
}

// The kind's whirl: the mean radius over the window against m e w^2 / sqrt((k - (M + m) w^2)^2 + (c w)^2) at the
// window's mean bit speed, from the case's own fields.
TEST(TorsionalWaveUnbalance, WhirlRadiusIsTheClosedForm) {
  const nlohmann::json doc = Load("saldivar-whirl");
  const CaseRun run = RunCase(ParseCase(doc));
  const auto& u = doc["model"]["bit"]["unbalance"];
  const double big_m = u["lateral_mass_kg"], k = u["lateral_stiffness_N_per_m"], c = u["lateral_damping_Ns_per_m"];
  const double m = u["unbalance_mass_kg"], e = u["eccentricity_m"];
  const double w = run.summary["bit_speed_mean_rad_s"].get<double>();
  const double closed = m * e * w * w / std::sqrt(std::pow(k - (big_m + m) * w * w, 2) + std::pow(c * w, 2));
  const double mean = run.summary["whirl_amplitude_mean_m"].get<double>();
  std::printf("[ measured ] bit %.6f rad/s: whirl radius %.7g m vs closed form %.7g (%+.2e)\n", w, mean, closed,
              mean / closed - 1);
  EXPECT_NEAR(mean, closed, 1e-5 * closed);
  EXPECT_NEAR(run.summary["whirl_amplitude_max_m"].get<double>(), closed, 1e-4 * closed);
  EXPECT_EQ(Channel(run, "lateral_displacement_m").size(), run.result.time_s.size());
}

}  // namespace
}  // namespace drillwave::cases
