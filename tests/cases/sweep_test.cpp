// Parameter sweeps: value lists, independence of the runs (threads change nothing), bad input before any run,
// numerical failures recorded per point, and the files written.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/sweep.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/csv.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

namespace fs = std::filesystem;

nlohmann::json ShortTwoDisc() {
  nlohmann::json doc = testing::LoadCase("two-disc-setup");
  doc["simulation"]["duration_s"] = 60;
  doc["statistics"]["window_s"] = {30, 60};
  return doc;
}

constexpr const char* kVoltage = "/model/upper_disc/input_voltage_V";

TEST(SweepValues, RangesAndLists) {
  EXPECT_EQ(ParseSweepValues("0:1:5", "values"), (std::vector<double>{0, 0.25, 0.5, 0.75, 1}));
  EXPECT_EQ(ParseSweepValues("2:9:1", "values"), (std::vector<double>{2}));
  EXPECT_EQ(ParseSweepValues("0.5,2,-1e-3", "values"), (std::vector<double>{0.5, 2, -1e-3}));
  for (const char* bad : {"", "1:2", "1:2:0", "1:2:2.5", "a,b", "1,,2", "1,", "1:2:3:4", "nan", "1:inf:3"}) {
    try {
      ParseSweepValues(bad, "values");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.json_path(), "values") << bad;
    }
  }
}

TEST(Sweep, AHugeSweepIsRefusedFromItsWorkEstimateBeforeAnythingElseIsParsed) {
  // Issue 41: 1e6 values held 3.8 GB of parsed cases before the first run (exit 4 on the command line; the Python
  // interpreter died). 60 s every 0.01 s is 6000 samples a run, counted as 1e4; the limit is 100 x --max-samples.
  struct RestoreLimit {
    double previous = MaxSamples();
    ~RestoreLimit() { SetMaxSamples(previous); }
  } restore;
  SetMaxSamples(1e5);  // a sweep's limit of 1e7: 1000 runs
  EXPECT_THROW(RunSweep(ShortTwoDisc(), {kVoltage, std::vector<double>(1001, 1.0), 1}, nullptr), InputError);
  SetMaxSamples(1e7);
  const std::vector<double> values = ParseSweepValues("0.1:6:1000000", "values");
  try {
    RunSweep(ShortTwoDisc(), {kVoltage, values, 2}, nullptr);
    ADD_FAILURE() << "a sweep of 1e6 runs was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "values");
    EXPECT_NE(std::string(e.what()).find("values: 1000000 runs of about 6000 output samples or steps each (each run "
                                         "counted as at least 10000: 1e+10 in all) are above a sweep's limit of "
                                         "1000000000 (100 x max_samples)"),
              std::string::npos)
        << e.what();
  }
}

TEST(Sweep, EachPointEqualsASingleRunWhateverTheNumberOfThreads) {
  const nlohmann::json doc = ShortTwoDisc();
  const std::vector<double> values{0.3, 0.6, 2.0, 8.0};
  int calls = 0;
  const SweepResult serial = RunSweep(doc, {kVoltage, values, 1}, [&](const SweepPoint&, int done, int total) {
    EXPECT_EQ(done, ++calls);
    EXPECT_EQ(total, 4);
  });
  const SweepResult parallel = RunSweep(doc, {kVoltage, values, 3}, nullptr);
  ASSERT_EQ(serial.points.size(), values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    nlohmann::json single = doc;
    single["model"]["upper_disc"]["input_voltage_V"] = values[i];
    const nlohmann::json alone = RunCase(ParseCase(single)).summary;
    for (const SweepResult* r : {&serial, &parallel}) {
      const SweepPoint& p = r->points[i];
      ASSERT_TRUE(p.ok) << p.error;
      EXPECT_EQ(p.value, values[i]);
      for (const char* key : {"stick_onsets", "stick_fraction", "bit_speed_min_rad_s", "bit_speed_max_rad_s",
                              "steps", "events"})
        EXPECT_EQ(p.summary.at(key), alone.at(key)) << key << " at " << values[i];
    }
  }
  // The sweep sees the regimes of the set-up: steady rotation, oscillation without sticking, stick-slip.
  EXPECT_EQ(serial.points[0].summary.at("stick_onsets").get<int>(), 0);
  EXPECT_GT(serial.points[1].summary.at("bit_speed_range_rad_s").get<double>(), 0.5);
  EXPECT_GT(serial.points[2].summary.at("stick_onsets").get<int>(), 3);
}

TEST(Sweep, BadInputStopsBeforeAnyRunAndNamesTheValue) {
  const nlohmann::json doc = ShortTwoDisc();
  int runs = 0;
  auto count = [&](const SweepPoint&, int, int) { ++runs; };
  try {
    RunSweep(doc, {"/model/lower_disc/inertia_kgm2", {0.03, -1.0}, 1}, count);
    ADD_FAILURE() << "a negative inertia was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/model/lower_disc/inertia_kgm2");
    EXPECT_NE(std::string(e.what()).find("= -1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(RunSweep(doc, {"/model/no_such_field", {1.0}, 1}, count), InputError);
  EXPECT_THROW(RunSweep(doc, {kVoltage, {}, 1}, count), InputError);
  EXPECT_THROW(RunSweep(doc, {kVoltage, {1.0}, 0}, count), InputError);
  EXPECT_EQ(runs, 0);
}

TEST(Sweep, NumericalFailureIsRecordedAndTheSweepGoesOn) {
  // A top of 1e-300 kg·m² driven by 1e4 N·m cannot be integrated (infinite acceleration, or steps too short to
  // represent); the ordinary inertias run fine.
  nlohmann::json doc = testing::LoadCase("saldivar-stickslip");
  doc["simulation"]["duration_s"] = 5;
  doc["statistics"]["window_s"] = {0, 5};
  doc["model"]["top"] = {{"type", "torque"}, {"inertia_kgm2", 1000.0}, {"torque_Nm", 1e4}};
  const SweepResult r = RunSweep(doc, {"/model/top/inertia_kgm2", {1000.0, 1e-300, 2000.0}, 2}, nullptr);
  ASSERT_EQ(r.points.size(), 3u);
  EXPECT_TRUE(r.points[0].ok);
  EXPECT_FALSE(r.points[1].ok);
  EXPECT_NE(r.points[1].error.find("at t = "), std::string::npos) << r.points[1].error;
  EXPECT_TRUE(r.points[2].ok);
}

TEST(Sweep, WritesTheTableTheFigureAndTheReport) {
  const nlohmann::json doc = ShortTwoDisc();
  const SweepSpec spec{kVoltage, {0.3, 2.0}, 2};
  const SweepResult r = RunSweep(doc, spec, nullptr);
  const fs::path dir = fs::temp_directory_path() / ("drillwave-sweep-test-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  WriteSweepOutputs(doc, spec, r, dir.string());
  const io::CsvTable table = io::ReadCsv((dir / "sweep.csv").string());
  EXPECT_EQ(table.Column(kVoltage), (std::vector<double>{0.3, 2.0}));
  EXPECT_EQ(table.Column("ok"), (std::vector<double>{1, 1}));
  EXPECT_EQ(table.Column("stick_onsets")[1], r.points[1].summary.at("stick_onsets").get<double>());
  for (const char* f : {"bifurcation.svg", "report.md", "case.json"}) EXPECT_TRUE(fs::exists(dir / f)) << f;
  fs::remove_all(dir);
}

// A value refused by the case says its path once, then which sweep value it was.
TEST(Sweep, ARefusedValueSaysItsPathOnce) {
  const nlohmann::json doc = testing::LoadCase("two-disc-setup");
  try {
    RunSweep(doc, SweepSpec{"/model/lower_disc/inertia_kgm2", {-1.0}, 1}, nullptr);
    FAIL() << "a negative inertia was not refused";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.json_path(), "/model/lower_disc/inertia_kgm2");
    EXPECT_EQ(what.find("/model/lower_disc/inertia_kgm2: "), 0u) << what;
    EXPECT_EQ(what.find("/model/lower_disc/inertia_kgm2: ", 1), std::string::npos) << what;
    EXPECT_NE(what.find("(sweep value /model/lower_disc/inertia_kgm2 = -1)"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace drillwave::cases
