// `drillwave compare-controllers`: the Saldivar string's stiff PI top drive (J 500 kg m^2, kp = ki = 5000) at 4 rad/s,
// where its steady rotation is unstable (+0.333 1/s) and the bit sticks and slips, against SoftSpeed, Z-Torque and the
// wave cancellation taking over at 20 s (three 20-s windows after it). A law whose operating point is not unstable
// (stable, or marginal: the inertial top reflects the string's highest harmonics without loss) must leave a lower
// median severity. The envelopes and the delay study are checked against what `drillwave stability` says of each
// law's case.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace {

namespace fs = std::filesystem;

using drillwave::test_support::Outcome;
using drillwave::test_support::RunTool;

// The rows of a CSV file (controllers.csv, ...) as column name -> text.
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

std::string ReadText(const fs::path& file) {
  std::ifstream in(file);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Each law's case as the comparison ran it: case.json with the top controllers.md lists for the law
// ("- <law>: `<top>`").
nlohmann::json LawCase(const fs::path& out, const std::string& law) {
  const std::string md = ReadText(out / "controllers.md"), mark = "- " + law + ": `";
  const std::size_t at = md.find(mark);
  if (at == std::string::npos) return nullptr;
  const std::size_t begin = at + mark.size();
  nlohmann::json doc = nlohmann::json::parse(ReadText(out / "case.json"));
  doc["model"]["top"] = nlohmann::json::parse(md.substr(begin, md.find('`', begin) - begin));
  return doc;
}

fs::path WriteJson(const nlohmann::json& doc, const fs::path& file) {
  std::ofstream(file) << doc.dump(2);
  return file;
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
  ASSERT_EQ(rows.size(), 6u);
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
  EXPECT_NE(text.find("| wave cancellation |"), std::string::npos) << text;
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
  EXPECT_EQ(ReadRows(out / "controllers.csv").size(), 6u);
}

// The stiff PI's stick-slip at 4 rad/s handed over at 20 s; every law mapped on 3 x 3 points of the set-point and the
// weight on bit, across the stiff PI's boundary (unstable at 3 rad/s, marginal above).
constexpr const char* kSpeedAxis = "/model/top/speed_rad_s/knots/1/1=3:9:3";
constexpr const char* kWeightAxis = "/model/bit/friction/W_N=80000:120000:3";
constexpr const char* kLaws[] = {
    "stiff PI", "SoftSpeed", "Z-Torque", "wave cancellation", "filtered wave cancellation", "sliding mode"};
constexpr std::size_t kNumLaws = std::size(kLaws);

// Each law's envelope holds the linear verdicts and rightmost roots `drillwave stability --map` gives for the law's
// own case, and the fractions and boundary counts of controllers.md are those of envelopes.csv's rows.
TEST_F(CompareControllers, EnvelopesAreTheStabilityMapsOfTheLawsCasesAndTheirCountsAddUp) {
  const fs::path out = dir_ / "out";
  const Outcome o = RunTool("compare-controllers " + Case("saldivar-z-torque") +
                            " --set /model/top/speed_rad_s/knots/1/1=4 --handover 20 --after 20 --envelope " +
                            kSpeedAxis + " " + kWeightAxis + " -j 1 -o " + out.string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_TRUE(fs::exists(out / "envelopes.svg"));
  const auto rows = ReadRows(out / "envelopes.csv");
  ASSERT_EQ(rows.size(), 9 * kNumLaws);
  const std::string md = ReadText(out / "controllers.md");
  for (std::size_t law = 0; law < kNumLaws; ++law) {
    const std::vector<std::map<std::string, std::string>> envelope(rows.begin() + 9 * law, rows.begin() + 9 * law + 9);
    ASSERT_EQ(envelope.front().at("law"), kLaws[law]);
    const nlohmann::json law_case = LawCase(out, kLaws[law]);
    ASSERT_FALSE(law_case.is_null()) << kLaws[law] << "'s top is not listed in controllers.md";
    const fs::path map = dir_ / ("map" + std::to_string(law));
    const Outcome m = RunTool("stability " + WriteJson(law_case, dir_ / "law.json").string() + " --map " +
                              kSpeedAxis + " " + kWeightAxis + " -j 1 -o " + map.string());
    ASSERT_EQ(m.exit_code, 0) << m.output;
    const auto reference = ReadRows(map / "stability_map.csv");
    ASSERT_EQ(reference.size(), 9u);
    int linear_free = 0, simulated_free = 0, boundary = 0, agreeing = 0, simulated_boundary = 0;
    auto free = [&](std::size_t k) {
      return envelope[k].at("verdict") == "stable" || envelope[k].at("verdict") == "marginal";
    };
    for (std::size_t k = 0; k < 9; ++k) {
      EXPECT_EQ(envelope[k].at("verdict"), reference[k].at("verdict")) << kLaws[law] << " point " << k;
      const double re = std::stod(envelope[k].at("rightmost_re_per_s"));
      EXPECT_NEAR(re, std::stod(reference[k].at("spectral_abscissa_per_s")), 1e-5 * std::abs(re) + 1e-12)
          << kLaws[law] << " point " << k;
      const std::size_t i = k % 3, j = k / 3;
      const bool on_boundary = (i > 0 && free(k - 1) != free(k)) || (i < 2 && free(k + 1) != free(k)) ||
                               (j > 0 && free(k - 3) != free(k)) || (j < 2 && free(k + 3) != free(k));
      EXPECT_EQ(envelope[k].at("boundary"), on_boundary ? "1" : "0") << kLaws[law] << " point " << k;
      const bool smooth = envelope[k].at("regime") == "smooth";
      auto smooth_at = [&](std::size_t m) { return envelope[m].at("regime") == "smooth"; };
      const bool on_runs_boundary = (i > 0 && smooth_at(k - 1) != smooth) || (i < 2 && smooth_at(k + 1) != smooth) ||
                                    (j > 0 && smooth_at(k - 3) != smooth) || (j < 2 && smooth_at(k + 3) != smooth);
      EXPECT_EQ(envelope[k].at("simulated_boundary"), on_runs_boundary ? "1" : "0") << kLaws[law] << " point " << k;
      simulated_boundary += on_runs_boundary;
      linear_free += free(k), simulated_free += smooth, boundary += on_boundary;
      agreeing += on_boundary && free(k) == smooth;
    }
    EXPECT_GE(boundary, 1) << kLaws[law] << ": the grid should cross the law's linear boundary";
    std::ostringstream counts;
    counts << "| " << kLaws[law] << " | " << std::setprecision(3) << linear_free / 9.0 << " | ";
    const std::size_t row = md.find(counts.str());
    ASSERT_NE(row, std::string::npos) << counts.str() << " not in\n" << md;
    std::stringstream cells(md.substr(row, md.find('\n', row) - row));
    std::vector<std::string> cell;
    for (std::string c; std::getline(cells, c, '|');) cell.push_back(c);
    ASSERT_GE(cell.size(), 10u) << md.substr(row, 200);
    EXPECT_DOUBLE_EQ(std::stod(cell[4]), std::round(simulated_free / 9.0 * 1000) / 1000) << kLaws[law];
    EXPECT_EQ(std::stoi(cell[5]), boundary) << kLaws[law];
    EXPECT_EQ(std::stoi(cell[6]), agreeing) << kLaws[law];
    EXPECT_EQ(std::stoi(cell[9]), simulated_boundary) << kLaws[law];
  }
}

// At every delay every law runs; the rows at the case's own delay (0) are the comparison's, and the verdict at a
// delay is the one `drillwave stability` gives for the law's case with that actuator delay: the linearization holds
// the delay (it turns the marginal Z-Torque and the stable wave cancellation unstable; the filtered law less so).
TEST_F(CompareControllers, ActuatorDelaysRerunEveryLawAndTheVerdictsHoldTheDelay) {
  const fs::path out = dir_ / "out";
  const Outcome o = RunTool("compare-controllers " + Case("saldivar-z-torque") +
                            " --set /model/top/speed_rad_s/knots/1/1=4 --handover 20 --after 20 "
                            "--actuator-delays 0,0.1 -o " + out.string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto nominal = ReadRows(out / "controllers.csv"), delays = ReadRows(out / "delays.csv");
  ASSERT_EQ(delays.size(), 2 * kNumLaws);
  for (std::size_t law = 0; law < kNumLaws; ++law) {
    auto at_zero = delays[law];
    EXPECT_EQ(at_zero.at("actuator_delay_s"), "0");
    at_zero.erase("actuator_delay_s");
    EXPECT_EQ(at_zero, nominal[law]) << kLaws[law];
    const auto& delayed = delays[kNumLaws + law];
    ASSERT_EQ(delayed.at("law"), kLaws[law]);
    EXPECT_EQ(delayed.at("actuator_delay_s"), "0.1");
    nlohmann::json law_case = LawCase(out, kLaws[law]);
    law_case["model"]["top"]["actuator_delay_s"] = 0.1;
    const fs::path roots = dir_ / "roots";
    const Outcome s = RunTool("stability " + WriteJson(law_case, dir_ / "law.json").string() + " --no-run -o " +
                              roots.string());
    ASSERT_EQ(s.exit_code, 0) << s.output;
    const double re = std::stod(ReadRows(roots / "roots.csv").front().at("re_per_s"));
    EXPECT_NEAR(std::stod(delayed.at("rightmost_re_per_s")), re, 1e-3 * std::abs(re)) << kLaws[law];
    fs::remove_all(roots);
  }
  EXPECT_EQ(delays[kNumLaws + 2].at("verdict"), "unstable");  // Z-Torque
  EXPECT_EQ(delays[kNumLaws + 3].at("verdict"), "unstable");  // the wave cancellation
  // Read 0.1 s late the exact law sends down up to twice the arriving wave at every frequency (its essential spectrum
  // near ln 2 / 2 tau); the filtered law only below its corner, so its rightmost root lies further left.
  EXPECT_LT(std::stod(delays[kNumLaws + 4].at("rightmost_re_per_s")),
            std::stod(delays[kNumLaws + 3].at("rightmost_re_per_s")));
  EXPECT_NE(ReadText(out / "controllers.md").find("## Actuator delay"), std::string::npos);
}

// Bad --envelope, --actuator-delays and --torque-limit exit 2 naming the option and write nothing; an axis must
// address the laws' cases (a dissipative top's damping is not one of their fields).
TEST_F(CompareControllers, RefusesBadEnvelopeDelayAndTorqueLimitInput) {
  const fs::path out = dir_ / "out";
  const std::string pi = Case("saldivar-stickslip") + " --stiff-pi 500,5000,5000 --handover 20 --after 20 ";
  const std::string w = std::string(" ") + kWeightAxis;
  for (const auto& [args, option] : std::vector<std::pair<std::string, std::string>>{
           {"--envelope " + std::string(kSpeedAxis), "--envelope"},
           {"--envelope /model/top/nope=1:2:2" + w, "--envelope"},
           {"--envelope /model/top/beta_Nms_per_rad=1:2:2" + w, "--envelope"},
           {"--envelope /model/top/speed_rad_s/knots/1/1=1:2:x" + w, "--envelope"},
           {"--envelope speed=1:2:2" + w, "--envelope"},
           {"--actuator-delays 0,-0.1", "--actuator-delays"},
           {"--actuator-delays 0,soon", "--actuator-delays"},
           {"--actuator-delays 11", "--actuator-delays"},
           {"--torque-limit 0", "--torque-limit"}}) {
    const Outcome o = RunTool("compare-controllers " + pi + args + " -o " + out.string());
    EXPECT_EQ(o.exit_code, 2) << args << ": " << o.output;
    EXPECT_NE(o.output.find(option), std::string::npos) << args << ": " << o.output;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
}

}  // namespace
