// Fitting by features: friction parameters hidden in a "recording" (a simulation written by the runner) are
// recovered from a wrong start; bad input stops before any search.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/diagnosis/fit.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::diagnosis {
namespace {

namespace fs = std::filesystem;

class Fit : public ::testing::Test {
 protected:
  void SetUp() override {
    truth_ = testing::LoadCase("saldivar-stickslip");
    truth_["simulation"]["duration_s"] = 60;
    truth_["simulation"]["output_interval_s"] = 0.01;
    truth_["simulation"]["abs_tol"] = truth_["simulation"]["rel_tol"] = 1e-6;
    truth_["statistics"]["window_s"] = {30, 60};
    dir_ = fs::temp_directory_path() / ("drillwave-fit-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    const cases::Case c = cases::ParseCase(truth_);
    cases::WriteCaseOutputs(c, cases::RunCase(c), dir_.string());
    recording_ = LoadRecording((dir_ / "trajectory.csv").string());
    options_.maps = {{"bit_rpm", "bit_rpm", 1}, {"top_rpm", "top_rpm", 1}, {"bit_torque_Nm", "bit_torque_Nm", 1}};
    options_.window_begin_s = 30;
    options_.window_end_s = 60;
  }
  void TearDown() override { fs::remove_all(dir_); }

  nlohmann::json truth_;
  fs::path dir_;
  Recording recording_;
  FitOptions options_;
};

TEST_F(Fit, RecoversTheStaticFrictionCoefficient) {
  nlohmann::json start = truth_;
  start["model"]["bit"]["friction"]["mu_s"] = 0.7;
  const FitResult r = FitFeatures(start, recording_, {{"/model/bit/friction/mu_s", 0.55, 0.95}}, options_);
  std::printf("[ measured ] mu_s: start 0.7, fitted %.6f (truth 0.8) in %d runs; objective %.3e -> %.3e\n",
              r.fitted[0], r.evaluations, r.objective_start, r.objective_fitted);
  EXPECT_NEAR(r.fitted[0], 0.8, 1e-3);
  EXPECT_LT(r.objective_fitted, 1e-4 * r.objective_start);
  EXPECT_EQ(r.document["model"]["bit"]["friction"]["mu_s"].get<double>(), r.fitted[0]);
}

TEST_F(Fit, RecoversStaticAndKineticFrictionWithTheTorqueLevel) {
  nlohmann::json start = truth_;
  start["model"]["bit"]["friction"]["mu_s"] = 0.7;
  start["model"]["bit"]["friction"]["mu_c"] = 0.45;
  options_.features = {"bit_oscillation_period_s", "stick_fraction", "bit_speed_max", "bit_torque_Nm mean"};
  const FitResult r = FitFeatures(
      start, recording_, {{"/model/bit/friction/mu_s", 0.6, 0.95}, {"/model/bit/friction/mu_c", 0.3, 0.6}}, options_);
  std::printf("[ measured ] (mu_s, mu_c): start (0.7, 0.45), fitted (%.5f, %.5f), truth (0.8, 0.5), %d runs\n",
              r.fitted[0], r.fitted[1], r.evaluations);
  EXPECT_NEAR(r.fitted[0], 0.8, 2e-3);
  EXPECT_NEAR(r.fitted[1], 0.5, 2e-3);
}

TEST_F(Fit, BadInputStopsBeforeTheSearch) {
  EXPECT_THROW(FitFeatures(truth_, recording_, {{"/model/bit/friction/no_such", 0, 1}}, options_), InputError);
  EXPECT_THROW(FitFeatures(truth_, recording_, {{"/model/bit/friction/law", 0, 1}}, options_), InputError);
  FitOptions bad = options_;
  bad.features = {"no_such_feature"};
  try {
    FitFeatures(truth_, recording_, {{"/model/bit/friction/mu_s", 0.55, 0.95}}, bad);
    FAIL() << "an unknown feature was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("stick_fraction"), std::string::npos) << "the message lists the features";
  }
  const FitParameter p = ParseFitParameter("/model/bit/inertia_kgm2:50:150");
  EXPECT_EQ(p.pointer, "/model/bit/inertia_kgm2");
  EXPECT_EQ(p.lower, 50);
  EXPECT_EQ(p.upper, 150);
  for (const char* text : {"model/x:0:1", "/x:1:0", "/x:0", "/x:a:1", "/x:0:inf"})
    EXPECT_THROW(ParseFitParameter(text), InputError) << text;
}

}  // namespace
}  // namespace drillwave::diagnosis
