// Stability maps over parameter draws (stability_map.hpp: ReadParameterDraws, StabilityMapOverDraws): the
// probability of stick-slip per point is the share of the draws' own maps that call it so, the case's map stands
// beside it, and the draws file is read by its JSON-pointer columns, spread evenly, bad files refused by --draws.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "drillwave/cases/stability_map.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

namespace fs = std::filesystem;

nlohmann::json TwoMass() {
  return testing::LoadCase("two-mass-stickslip");
}

std::string WriteFile(const std::string& name, const std::string& text) {
  const fs::path path = fs::temp_directory_path() / ("drillwave-draws-" + std::to_string(::getpid()) + "-" + name);
  std::ofstream(path) << text;
  return path.string();
}

StabilityMapSpec Spec(const nlohmann::json& doc) {
  return {ParseMapAxis("/model/top/speed_rad_s/knots/1/1=0.5:5:4", doc),
          ParseMapAxis("/model/bit/friction/W_N=50000:150000:3", doc), 1, false};
}

// mu_s = mu_c: no weakening, every point stable; 1.5: strong weakening, unstable up to higher speeds than the case's.
TEST(StabilityMapOverDraws, EachPointsProbabilityIsTheShareOfTheDrawsMapsThatAreUnstableThere) {
  const nlohmann::json doc = TwoMass();
  const StabilityMapSpec spec = Spec(doc);
  const std::string file = WriteFile("two.csv", "step,walker,/model/bit/friction/mu_s\n1,0,0.5\n1,1,1.5\n");
  const ParameterDraws draws = ReadParameterDraws(file, doc, 0);
  ASSERT_EQ(draws.rows.size(), 2u);
  const StabilityMapResult over = StabilityMapOverDraws(doc, spec, draws);
  const StabilityMapResult own = StabilityMap2D(doc, spec);
  nlohmann::json weak = doc, strong = doc;
  weak["model"]["bit"]["friction"]["mu_s"] = 0.5;
  strong["model"]["bit"]["friction"]["mu_s"] = 1.5;
  const StabilityMapResult a = StabilityMap2D(weak, spec), b = StabilityMap2D(strong, spec);
  ASSERT_EQ(over.p_linearly_unstable.size(), own.cells.size());
  int between = 0;
  for (std::size_t k = 0; k < own.cells.size(); ++k) {
    EXPECT_EQ(over.cells[k].verdict, own.cells[k].verdict) << k;  // the case's own map beside the probabilities
    EXPECT_TRUE(LinearlySteady(a.cells[k])) << k;                  // no weakening: stable everywhere
    const double expected = 0.5 * (!LinearlySteady(a.cells[k]) + !LinearlySteady(b.cells[k]));
    EXPECT_DOUBLE_EQ(over.p_linearly_unstable[k], expected) << k;
    EXPECT_TRUE(std::isnan(over.p_stick_slip[k]));  // not simulated
    between += expected == 0.5;
  }
  EXPECT_GT(between, 6);  // the strong weakening's unstable points
  EXPECT_EQ(over.draws, 2);
  fs::remove(file);
}

TEST(StabilityMapOverDraws, DrawsAreSpreadEvenlyOverTheFileAndBadFilesAreRefused) {
  const nlohmann::json doc = TwoMass();
  std::string rows = "step,/model/bit/friction/mu_s,log_likelihood\n";
  for (int i = 0; i < 10; ++i) rows += std::to_string(i) + "," + std::to_string(0.6 + 0.01 * i) + ",-3\n";
  const std::string file = WriteFile("ten.csv", rows);
  const ParameterDraws five = ReadParameterDraws(file, doc, 5);
  ASSERT_EQ(five.rows.size(), 5u);
  ASSERT_EQ(five.pointers, std::vector<std::string>{"/model/bit/friction/mu_s"});
  for (int d = 0; d < 5; ++d) EXPECT_DOUBLE_EQ(five.rows[d][0], 0.6 + 0.01 * (2 * d));
  EXPECT_EQ(ReadParameterDraws(file, doc, 50).rows.size(), 10u);
  auto refused = [&](const std::string& text, int count = 0) {
    try {
      ReadParameterDraws(WriteFile("bad.csv", text), doc, count);
    } catch (const InputError& e) {
      return e.json_path();
    }
    return std::string();
  };
  EXPECT_EQ(refused("step,log_likelihood\n1,2\n"), "draws");                 // no pointer column
  EXPECT_EQ(refused("/model/bit/friction/law\n1\n"), "draws");               // not a number in the case
  EXPECT_EQ(refused("/model/bit/friction/mu_s\n"), "draws");                 // no rows
  EXPECT_EQ(refused("/model/bit/friction/mu_s\nnan\n"), "draws");            // not finite
  EXPECT_EQ(refused("/model/bit/friction/mu_s\n1\n", -1), "draw_count");
  fs::remove(file);
}

// A value the case refuses is reported with the axis and the field's own message, its path said once.
TEST(StabilityMapOverDraws, AnAxisValueTheCaseRefusesNamesItsFieldOnce) {
  const nlohmann::json doc = testing::LoadCase("baseline-60rpm");
  try {
    ParseMapAxis("/model/hoist/weight_on_bit_N=1000:2000:3", doc);
    FAIL() << "not refused";
  } catch (const InputError& e) {
    const std::string what = e.what(), path = "/model/hoist/weight_on_bit_N";
    EXPECT_EQ(e.json_path(), "map");
    const std::size_t first = what.find(path + ":");
    ASSERT_NE(first, std::string::npos) << what;
    EXPECT_EQ(what.find(path + ":", first + 1), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace drillwave::cases
