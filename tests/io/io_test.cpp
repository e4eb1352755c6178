// io: JSON reader errors, CSV round trip, SVG plot, all-or-nothing output folders.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "drillwave/core/error.hpp"
#include "drillwave/io/csv.hpp"
#include "drillwave/io/json_reader.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/io/svg_plot.hpp"

namespace drillwave::io {
namespace {

namespace fs = std::filesystem;

TEST(JsonReader, ReadsDefaultsAndRejectsUnknownKeys) {
  const nlohmann::json j = {{"a", 2.0}, {"n", 3}, {"s", "x"}, {"typo", 1}};
  const JsonReader r(j, "/model");
  EXPECT_EQ(r.Number("a", Range::Positive()), 2.0);
  EXPECT_EQ(r.Number("b", Range::Positive(), 7.0), 7.0);
  EXPECT_EQ(r.Integer("n", 0, 10), 3);
  EXPECT_EQ(r.String("s", {"x", "y"}), "x");
  try {
    r.Finish();
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/model/typo");
  }
}

TEST(JsonReader, ErrorsNameThePathValueAndRange) {
  const nlohmann::json j = {{"a", -3}, {"b", "abc"}, {"c", 5}};
  const JsonReader r(j, "/m");
  try {
    r.Number("a", Range::Positive());
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "/m/a: expected a number > 0, got -3");
  }
  EXPECT_THROW(r.Number("b", Range::Any()), InputError);
  EXPECT_THROW(r.Number("missing", Range::Any()), InputError);
  EXPECT_THROW(r.Integer("c", 0, 4), InputError);
  EXPECT_THROW(r.String("c", {}), InputError);
}

TEST(Csv, RoundTripWithNaN) {
  const fs::path file = fs::temp_directory_path() / "drillwave-csv-test.csv";
  {
    std::ofstream out(file);
    WriteCsv(out, {"time_s", "v"}, {{0.0, 0.5, 1.0}, {1.25, std::nan(""), -3e-7}});
  }
  const CsvTable t = ReadCsv(file.string());
  ASSERT_EQ(t.header.size(), 2u);
  EXPECT_EQ(t.Column("v")[0], 1.25);
  EXPECT_TRUE(std::isnan(t.Column("v")[1]));
  EXPECT_EQ(t.Column("v")[2], -3e-7);
  fs::remove(file);
}

TEST(SvgPlot, KeepsSpikesThroughDecimation) {
  Series s{"spiky", {}, {}};
  for (int i = 0; i < 1000000; ++i) {
    s.x.push_back(i * 1e-3);
    s.y.push_back(i == 500003 ? 100.0 : (i == 700001 ? -50.0 : std::sin(i * 1e-3)));
  }
  Figure f{"a <title> & more", "time [s]", {Panel{"v", {s}}}};
  std::ostringstream out;
  WriteSvg(f, out);
  const std::string svg = out.str();
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("a &lt;title&gt; &amp; more"), std::string::npos);
  EXPECT_LT(svg.size(), 400000u) << "decimated";
  // The y axis spans the spikes: tick labels near both extremes exist.
  EXPECT_NE(svg.find(">100<"), std::string::npos);
  EXPECT_NE(svg.find(">-50<"), std::string::npos);
}

TEST(OutputDirectory, AllOrNothing) {
  const fs::path dir = fs::temp_directory_path() / "drillwave-out-test";
  fs::remove_all(dir);
  {
    OutputDirectory out(dir.string());
    out.Open("a.txt") << "partial";
  }  // no Commit: as if an exception had been thrown
  EXPECT_FALSE(fs::exists(dir));
  for (const auto& e : fs::directory_iterator(dir.parent_path()))
    EXPECT_EQ(e.path().filename().string().find(".drillwave-out-test.staging"), std::string::npos);
  {
    OutputDirectory out(dir.string());
    out.Open("a.txt") << "done";
    out.Open("b.txt") << "done";
    out.Commit();
  }
  EXPECT_TRUE(fs::exists(dir / "a.txt"));
  EXPECT_TRUE(fs::exists(dir / "b.txt"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace drillwave::io
