// The step budget of compare-controllers' runs (controller_comparison.hpp): a law's run that takes more steps than
// the budget is recorded as failed, not run on until memory runs out; under actuator delays the budget is
// kDelayedWorkFactor times the costliest nominal run's steps.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "drillwave/cases/controller_comparison.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

nlohmann::json SaldivarZTorque() {
  nlohmann::json doc = testing::LoadCase("saldivar-z-torque");
  doc["model"]["top"]["speed_rad_s"]["knots"][1][1] = 4;
  return doc;
}

ControllerComparisonSpec Spec() {
  ControllerComparisonSpec spec;
  spec.handover_s = 20, spec.after_s = 20, spec.tuning_period_s = 2.7;
  return spec;
}

TEST(ControllerBudget, ARunOverItsStepBudgetIsRecordedAsFailed) {
  ControllerComparisonSpec spec = Spec();
  const ControllerComparison free = CompareControllers(SaldivarZTorque(), spec);
  for (const ControllerResult& r : free.laws) {
    EXPECT_TRUE(r.run_failure.empty()) << r.law << ": " << r.run_failure;
    EXPECT_GT(r.steps, 100) << r.law;
  }
  spec.max_steps = 100;
  const ControllerComparison tight = CompareControllers(SaldivarZTorque(), spec);
  for (const ControllerResult& r : tight.laws) {
    EXPECT_NE(r.run_failure.find("step budget exhausted"), std::string::npos) << r.law << ": " << r.run_failure;
    EXPECT_EQ(r.steps, 0) << r.law;
  }
}

TEST(ControllerBudget, DelayedRunsMayTakeTenTimesTheCostliestNominalRunsSteps) {
  const ControllerComparisonSpec spec = Spec();
  ControllerComparison nominal = CompareControllers(SaldivarZTorque(), spec);
  long costliest = 0;
  for (const ControllerResult& r : nominal.laws) costliest = std::max(costliest, r.steps);
  // The nominal runs' own steps: no delayed run of a 50-ms delay needs ten times them (Z-Torque's grows without
  // bound, a blow-up the budget leaves as it is).
  for (const ControllerComparison& c : CompareUnderActuatorDelays(SaldivarZTorque(), spec, nominal, {0.05}))
    for (const ControllerResult& r : c.laws) {
      EXPECT_EQ(r.run_failure.find("step budget"), std::string::npos) << r.law << ": " << r.run_failure;
      EXPECT_LT(r.steps, kDelayedWorkFactor * costliest) << r.law;
    }
  // Nominal runs said to have taken 10 steps: the delayed ones stop at 100, and the report says so, not "blew up".
  for (ControllerResult& r : nominal.laws) r.steps = 10;
  ControllerStudies studies;
  studies.delays = CompareUnderActuatorDelays(SaldivarZTorque(), spec, nominal, {0, 0.05});
  for (const ControllerResult& r : studies.delays.back().laws)
    EXPECT_NE(r.run_failure.find("max_steps = 100 "), std::string::npos) << r.law << ": " << r.run_failure;
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / ("drillwave-budget-" + std::to_string(::getpid()));
  WriteControllerComparison(SaldivarZTorque(), nominal, out.string(), studies);
  std::ifstream md(out / "controllers.md");
  const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("| run stopped (step budget) |"), std::string::npos) << text;
  EXPECT_NE(text.find("- SoftSpeed at 0.05 s delay: step budget exhausted (max_steps = 100 "), std::string::npos);
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace drillwave::cases
