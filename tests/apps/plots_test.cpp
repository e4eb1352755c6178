// The tool's figures as a reader meets them: every axis names its quantity and unit, a swept parameter by its name
// rather than its JSON pointer (issue 40).
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace {

namespace fs = std::filesystem;

using drillwave::test_support::Outcome;
using drillwave::test_support::RunTool;

std::string Contents(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class Plots : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = drillwave::test_support::ScratchFolder("plots");
    std::ifstream in(std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/saldivar-stickslip.json");
    nlohmann::json doc = nlohmann::json::parse(in);
    doc["simulation"]["duration_s"] = 4;
    doc["statistics"]["window_s"] = {2, 4};
    case_ = (dir_ / "case.json").string();
    std::ofstream(case_) << doc.dump();
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
  std::string case_;
};

TEST_F(Plots, TheRunsAxesCarryTheirUnits) {
  const Outcome o = RunTool("run " + case_ + " -o " + (dir_ / "run").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::string svg = Contents(dir_ / "run" / "plot.svg");
  EXPECT_NE(svg.find(">top speed, bit speed [rpm]<"), std::string::npos) << svg.substr(0, 2000);
  EXPECT_NE(svg.find(">top torque, bit torque [N m]<"), std::string::npos);
  EXPECT_NE(svg.find(">time [s]<"), std::string::npos);
}

TEST_F(Plots, ASweepsAxisIsTheParametersNameAndUnitNotItsPointer) {
  const Outcome o = RunTool("sweep " + case_ + " -p /model/bit/inertia_kgm2 -v 80,90 -j 1 -o " + (dir_ / "sweep").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::string svg = Contents(dir_ / "sweep" / "bifurcation.svg");
  EXPECT_NE(svg.find(">bit inertia [kg m²]<"), std::string::npos) << svg.substr(0, 2000);
  EXPECT_EQ(svg.find(">/model/bit/inertia_kgm2<"), std::string::npos);
}

}  // namespace
