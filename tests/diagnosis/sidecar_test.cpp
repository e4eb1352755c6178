// The case a synthetic recording's sidecar turns into (diagnosis::CaseFromSidecar): its start is BASELINE.md's, the
// exact steady state at the first set-point plus a tiny bottom-hole roughness, and no disturbance in the inputs.
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/diagnosis/sidecar.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::diagnosis {
namespace {

nlohmann::json Sidecar() {
  return {{"recording", "recXX"},
          {"duration_s", 40.0},
          {"wob_target_kN", 100.0},
          {"well", {{"measured_depth_m", 1800.0}, {"mud_density_kg_m3", 1200.0}}},
          {"rpm_setpoint_schedule", {{0.0, 60.0}, {20.0, 60.0}, {30.0, 90.0}}}};
}
nlohmann::json Baseline() {
  return testing::LoadCase("baseline-60rpm");
}

TEST(CaseFromSidecar, StartsFromSteadyDrillingOverATinyBottomRoughnessWithSteadyInputs) {
  const nlohmann::json doc = CaseFromSidecar(Sidecar(), Baseline(), kSidecarWarmupS);
  const double w60 = 2 * kPi, w90 = 3 * kPi;
  const nlohmann::json expected_knots = {{0.0, w60}, {30.0, w60}, {50.0, w60}, {60.0, w90}};
  const nlohmann::json& knots = doc["model"]["top"]["speed_rad_s"]["knots"];
  ASSERT_EQ(knots.size(), expected_knots.size()) << knots.dump();
  for (std::size_t i = 0; i < knots.size(); ++i) {
    EXPECT_DOUBLE_EQ(knots[i][0].get<double>(), expected_knots[i][0].get<double>()) << i;
    EXPECT_NEAR(knots[i][1].get<double>(), expected_knots[i][1].get<double>(), 1e-12) << i;
  }
  const nlohmann::json& roughness = doc["model"]["rock"]["bottom_roughness"];
  EXPECT_EQ(roughness["rms_m"].get<double>(), kSidecarStartRoughnessM);
  EXPECT_EQ(roughness["seed"].get<int>(), kSidecarStartSeed);
  EXPECT_EQ(doc["simulation"]["duration_s"].get<double>(), 70.0);
  EXPECT_NO_THROW(cases::ParseCase(doc));
}

TEST(CaseFromSidecar, KeepsTheCasesOwnRoughness) {
  nlohmann::json base = Baseline();
  base["model"]["rock"]["bottom_roughness"] = {{"rms_m", 2e-6}, {"seed", 17}, {"modes", 5}};
  const nlohmann::json doc = CaseFromSidecar(Sidecar(), base, kSidecarWarmupS);
  EXPECT_EQ(doc["model"]["rock"]["bottom_roughness"], base["model"]["rock"]["bottom_roughness"]);
}

}  // namespace
}  // namespace drillwave::diagnosis
