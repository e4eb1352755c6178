// The optional string and bit components of the torsional_wave kind: Kelvin-Voigt damping and the BHA mass unbalance
// (the physics is checked on the network in tests/waves/kelvin_voigt_test.cpp and jeffcott_bit_test.cpp; here what
// the kind builds from its fields, and how it refuses bad input).
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "refused_path.hpp"

namespace drillwave::cases {
namespace {

nlohmann::json Load(const char* name) {
  nlohmann::json doc = io::LoadJsonFile(std::string(DRILLWAVE_SOURCE_DIR) + "/json-cases/" + name + ".json");
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
