// Every case in json-cases/ runs and meets its own expect block (each case carries its expectations).
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

std::vector<std::string> CaseFiles() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(DRILLWAVE_SOURCE_DIR) + "/json-cases"))
    if (entry.path().extension() == ".json") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

class JsonCase : public ::testing::TestWithParam<std::string> {};

TEST_P(JsonCase, MeetsItsExpectations) {
  const Case c = ParseCase(io::LoadJsonFile(GetParam()));
  ASSERT_FALSE(c.expect.empty()) << GetParam() << " has no expect block";
  const CaseRun run = RunCase(c);
  for (const ExpectationCheck& check : CheckExpectations(c.expect, run.summary)) {
    std::cout << "[ expect ] " << c.name << ": " << check.detail << "\n";
    EXPECT_TRUE(check.passed) << c.name << ": " << check.detail;
  }
}

INSTANTIATE_TEST_SUITE_P(AllCases, JsonCase, ::testing::ValuesIn(CaseFiles()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = std::filesystem::path(info.param).stem().string();
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

TEST(DefaultCase, IsTheSaldivarStickSlipCase) {
  const auto embedded = nlohmann::json::parse(DefaultCaseText());
  const auto file = testing::LoadCase("saldivar-stickslip");
  EXPECT_EQ(embedded, file);
}

TEST(ParameterPaths, EveryParameterIsAddressableByItsJsonPointer) {
  auto doc = testing::LoadCase("saldivar-stickslip");
  io::SetByPointer(doc, "/model/top/speed_rad_s", 20.0);
  io::SetByPointer(doc, "/simulation/duration_s", 30.0);
  io::SetByPointer(doc, "/statistics/window_s", nlohmann::json::array({20.0, 30.0}));
  const CaseRun run = RunCase(ParseCase(doc));
  EXPECT_EQ(run.summary.at("stick_onsets").get<int>(), 0);  // 20 rad/s: smooth drilling
  io::SetByPointer(doc, "/model/bit/no_such_field", 1.0);  // added, then refused by the kind's reader
  EXPECT_THROW(ParseCase(doc), InputError);
}

}  // namespace
}  // namespace drillwave::cases

namespace drillwave::cases {
namespace {

// --set reaches every documented optional field, also one the case leaves out; a misspelt one is refused by the
// kind's reader with its path.
TEST(SetOptionalFields, AMissingOptionalFieldCanBeSetAndAMisspeltOneIsRefused) {
  nlohmann::json doc = testing::LoadCase("saldivar-stickslip");
  io::SetByPointer(doc, "/model/initial/bit_speed_rad_s", 6.0);
  EXPECT_NO_THROW(ParseCase(doc));
  io::SetByPointer(doc, "/model/bit/inertia_kgm3", 1.0);
  try {
    ParseCase(doc);
    FAIL() << "a misspelt field was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("inertia_kgm3"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace drillwave::cases
