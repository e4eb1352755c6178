// `drillwave compare-controllers`: the Saldivar string's stiff PI top drive (J 500 kg m^2, kp = ki = 5000) at 4 rad/s,
// where its steady rotation is unstable (+0.333 1/s) and the bit sticks and slips, against SoftSpeed and Z-Torque
// taking over at 20 s (three 20-s windows after it). A law whose operating point is not unstable (stable, or marginal:
// the inertial top reflects the string's highest harmonics without loss) must leave a lower median severity.
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli_support.hpp"

namespace {

namespace fs = std::filesystem;

using drillwave::test_support::Outcome;
using drillwave::test_support::RunTool;

// The rows of controllers.csv as column name -> text.
std::vector<std::map<std::string, std::string>> ReadRows(const fs::path& csv) {
  std::ifstream in(csv);
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream split(line);
    for (std::string cell; std::getline(split, cell, ',');) cells.push_back(cell);
    if (header.empty()) {
      header = cells;
      continue;
    }
    std::map<std::string, std::string> row;
    for (std::size_t k = 0; k < header.size() && k < cells.size(); ++k) row[header[k]] = cells[k];
    rows.push_back(row);
  }
  return rows;
}

class CompareControllers : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = drillwave::test_support::ScratchFolder("controllers"); }
  void TearDown() override { fs::remove_all(dir_); }
  static std::string Case(const char* name) {
    return std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/" + name + ".json";
  }
  fs::path dir_;
};

TEST_F(CompareControllers, WritesTheTableAndAStableLawSticksLessThanTheUnstableStiffPi) {
  const fs::path out = dir_ / "out";
  const Outcome o = RunTool("compare-controllers " + Case("saldivar-z-torque") +
                            " --set /model/top/speed_rad_s/knots/1/1=4 --handover 20 -o " + out.string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  for (const char* f : {"controllers.csv", "controllers.md", "controllers.svg", "case.json"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto rows = ReadRows(out / "controllers.csv");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].at("law"), "stiff PI");
  EXPECT_EQ(rows[0].at("verdict"), "unstable");
  EXPECT_EQ(rows[0].at("time_to_suppress_s"), "not suppressed");
  const double stiff = std::stod(rows[0].at("severity"));
  int better = 0;
  for (const auto& row : rows) {
    std::printf("[ measured ] %s: %s, rightmost Re s %s 1/s, severity %s, torque std %s N m (%s %% less), time to "
                "suppress %s\n", row.at("law").c_str(), row.at("verdict").c_str(), row.at("rightmost_re_per_s").c_str(),
                row.at("severity").c_str(), row.at("top_torque_std_Nm").c_str(),
                row.at("torque_std_reduction_pct").c_str(), row.at("time_to_suppress_s").c_str());
    if (row.at("verdict") == "unstable") continue;
    EXPECT_LT(std::stod(row.at("severity")), stiff) << row.at("law");
    ++better;
  }
  EXPECT_GE(better, 1) << "no law stabilizes the stiff PI's operating point";
  std::ifstream md(out / "controllers.md");
  const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("| Z-Torque |"), std::string::npos) << text;
}

// A dissipative top has no stiff PI to compare with unless one is given; bad options exit 2 naming them and write
// nothing.
TEST_F(CompareControllers, NeedsAStiffPiAndRefusesBadOptions) {
  const fs::path out = dir_ / "out";
  const std::string dissipative = Case("saldivar-stickslip");
  const std::string pi = dissipative + " --stiff-pi ";
  for (const auto& [args, named] : std::vector<std::pair<std::string, std::string>>{
           {dissipative, "/model/top/type"},
           {pi + "500,5000", "--stiff-pi"},
           {pi + "500,5000,5000 --after 10", "--after"},
           {pi + "500,5000,5000 --handover 0", "--handover"},
           {pi + "0,5000,5000 --handover 20", "/model/top/inertia_kgm2"}}) {
    const Outcome o = RunTool("compare-controllers " + args + " -o " + out.string());
    EXPECT_EQ(o.exit_code, 2) << args << ": " << o.output;
    EXPECT_NE(o.output.find(named), std::string::npos) << args << ": " << o.output;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
  const Outcome o = RunTool("compare-controllers " + pi + "500,5000,5000 --handover 20 --after 20 -o " + out.string());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(ReadRows(out / "controllers.csv").size(), 3u);
}

}  // namespace
