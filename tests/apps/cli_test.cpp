// The command-line tool as a user meets it: exit codes, messages that name the JSON path, nothing written on failure.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace {

namespace fs = std::filesystem;

using drillwave::test_support::Outcome;
using drillwave::test_support::RunTool;

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = drillwave::test_support::ScratchFolder("cli");
    std::ifstream in(std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/saldivar-stickslip.json");
    base_ = nlohmann::json::parse(in);
    base_["simulation"]["duration_s"] = 10;
    base_["statistics"]["window_s"] = {5, 10};
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& text) {
    const std::string file = (dir_ / "case.json").string();
    std::ofstream(file) << text;
    return file;
  }
  // Runs a case that must be rejected, and checks the exit code, the message and that nothing was written.
  void ExpectRejected(const std::string& text, int code, const std::string& must_mention) {
    const std::string out = (dir_ / "out").string();
    const Outcome o = RunTool("run " + Write(text) + " --out " + out);
    EXPECT_EQ(o.exit_code, code) << o.output;
    EXPECT_NE(o.output.find(must_mention), std::string::npos) << "message should mention '" << must_mention
                                                                << "': " << o.output;
    EXPECT_FALSE(fs::exists(out)) << "nothing may be written on failure";
    for (const auto& entry : fs::directory_iterator(dir_))
      EXPECT_EQ(entry.path().filename().string().find("staging"), std::string::npos) << "staging left behind";
  }

  fs::path dir_;
  nlohmann::json base_;
};

TEST_F(Cli, RunsACaseAndWritesEveryOutput) {
  const std::string out = (dir_ / "out").string();
  const Outcome o = RunTool("run " + Write(base_.dump()) + " --out " + out);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  for (const char* f : {"trajectory.csv", "summary.json", "plot.svg", "report.md", "case.json"})
    EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
  std::ifstream csv(fs::path(out) / "trajectory.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("time_s,top_rpm,bit_rpm,top_torque_Nm,bit_torque_Nm", 0), 0u) << header;
  std::ifstream summary_file(fs::path(out) / "summary.json");
  const auto summary = nlohmann::json::parse(summary_file);
  for (const char* key : {"stick_slip_period_s", "stick_fraction", "bit_speed_max_rad_s", "bit_speed_mean_rad_s",
                          "steps", "events", "wall_time_s"})
    EXPECT_TRUE(summary.contains(key)) << key;
}

// The saldivar string at 10 rad/s: steady sliding is linearly stable, yet the run from rest sticks and slips. `run`
// says so (two attractors); at 20 rad/s it drills smoothly and there is nothing to say.
TEST_F(Cli, RunSaysWhenAStableSteadyStateCoexistsWithTheStickSlipItFound) {
  const std::string out = (dir_ / "out").string();
  const Outcome o = RunTool("run " + Write(base_.dump()) + " --out " + out);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  std::ifstream summary_file(fs::path(out) / "summary.json");
  const auto summary = nlohmann::json::parse(summary_file);
  ASSERT_TRUE(summary.contains("linear_verdict")) << summary.dump();
  EXPECT_NE(summary["linear_verdict"].get<std::string>().find("6.2052 rad/s"), std::string::npos);
  EXPECT_NE(o.output.find("coexists with the stick-slip"), std::string::npos) << o.output;
  base_["model"]["top"]["speed_rad_s"]["knots"][1][1] = 20.0;
  const std::string smooth = (dir_ / "smooth").string();
  ASSERT_EQ(RunTool("run " + Write(base_.dump()) + " --out " + smooth).exit_code, 0);
  std::ifstream smooth_file(fs::path(smooth) / "summary.json");
  EXPECT_FALSE(nlohmann::json::parse(smooth_file).contains("linear_verdict"));
}

// `stability` says the same: it runs the case from its start beside the linearization (unless --no-run), and at 20
// rad/s, where the run drills smoothly, it has nothing to add.
TEST_F(Cli, StabilitySaysWhenAStableSteadyStateCoexistsWithStickSlipFromTheStart) {
  const std::string out = (dir_ / "stab").string();
  const Outcome o = RunTool("stability " + Write(base_.dump()) + " --out " + out);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("coexists with the stick-slip"), std::string::npos) << o.output;
  std::ifstream file(fs::path(out) / "stability.json");
  const auto stability = nlohmann::json::parse(file);
  ASSERT_TRUE(stability.contains("run_from_start")) << stability.dump();
  EXPECT_TRUE(stability["run_from_start"]["sticks"].get<bool>());
  EXPECT_NE(stability["run_from_start"]["note"].get<std::string>().find("6.2052 rad/s"), std::string::npos);
  EXPECT_EQ(stability["operating_points"][0]["verdict"], "stable");

  const std::string skipped = (dir_ / "skipped").string();
  const Outcome no_run = RunTool("stability " + Write(base_.dump()) + " --no-run --out " + skipped);
  ASSERT_EQ(no_run.exit_code, 0) << no_run.output;
  std::ifstream skipped_file(fs::path(skipped) / "stability.json");
  EXPECT_FALSE(nlohmann::json::parse(skipped_file).contains("run_from_start"));

  base_["model"]["top"]["speed_rad_s"]["knots"][1][1] = 20.0;
  const std::string smooth = (dir_ / "smooth").string();
  ASSERT_EQ(RunTool("stability " + Write(base_.dump()) + " --out " + smooth).exit_code, 0);
  std::ifstream smooth_file(fs::path(smooth) / "stability.json");
  const auto smooth_stability = nlohmann::json::parse(smooth_file);
  EXPECT_FALSE(smooth_stability["run_from_start"]["sticks"].get<bool>());
  EXPECT_EQ(smooth_stability["run_from_start"]["note"], "");
}

TEST_F(Cli, NoArgumentsRunsTheEmbeddedDefaultCase) {
  const Outcome o = RunTool("run --out " + (dir_ / "default").string());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("saldivar-stickslip"), std::string::npos);
  EXPECT_NE(o.output.find("trajectory.csv"), std::string::npos);
}

TEST_F(Cli, MalformedJsonIsRejectedWithLineAndColumn) { ExpectRejected("{\"name\": \"x\",\n  oops}", 2, "line 2"); }

TEST_F(Cli, UnknownKeyIsRejected) {
  auto doc = base_;
  doc["model"]["bit"]["inertai_kgm2"] = 89;
  ExpectRejected(doc.dump(), 2, "/model/bit/inertai_kgm2");
}

TEST_F(Cli, MissingFieldIsRejected) {
  auto doc = base_;
  doc["model"]["string"]["sections"][0].erase("length_m");
  ExpectRejected(doc.dump(), 2, "/model/string/sections/0/length_m");
}

TEST_F(Cli, WrongTypeIsRejected) {
  auto doc = base_;
  doc["model"]["bit"]["inertia_kgm2"] = "heavy";
  ExpectRejected(doc.dump(), 2, "/model/bit/inertia_kgm2");
}

TEST_F(Cli, NegativeLengthIsRejected) {
  auto doc = base_;
  doc["model"]["string"]["sections"][0]["length_m"] = -3;
  ExpectRejected(doc.dump(), 2, "expected a number > 0, got -3");
}

TEST_F(Cli, ZeroInertiaWithSetValuedFrictionIsRejected) {
  auto doc = base_;
  doc["model"]["bit"]["inertia_kgm2"] = 0;
  ExpectRejected(doc.dump(), 2, "/model/bit/inertia_kgm2");
}

TEST_F(Cli, InfinityIsRejected) {
  std::string text = base_.dump();
  const std::string key = "\"beta_Nms_per_rad\":2000";
  text.replace(text.find(key), key.size(), "\"beta_Nms_per_rad\":1e999");
  ExpectRejected(text, 2, "1e999");
}

TEST_F(Cli, UnknownModelKindIsRejected) {
  auto doc = base_;
  doc["model"]["kind"] = "quantum_string";
  ExpectRejected(doc.dump(), 2, "/model/kind");
}

// A bit law with strongly negative damping makes the solution overflow: reported with the time and the state.
TEST_F(Cli, DivergenceIsANumericalFailure) {
  // Every law and range is physical, so overflow is forced: 1e300 N·m on 1e-300 kg·m² gives an infinite
  // acceleration at the first evaluation; the run must stop with the time and state, and write nothing.
  auto doc = base_;
  doc["model"]["top"] = {{"type", "torque"}, {"inertia_kgm2", 1e-300}, {"torque_Nm", 1e300}};
  ExpectRejected(doc.dump(), 3, "at t = ");
}

TEST_F(Cli, CheckFlagFailsOnAnUnmetExpectation) {
  auto doc = base_;
  doc["expect"] = {{"stick_fraction", {{"min", 0.99}}}};
  const Outcome o = RunTool("run " + Write(doc.dump()) + " --check --out " + (dir_ / "out").string());
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("FAIL"), std::string::npos);
}

TEST_F(Cli, SweepWritesEveryPointOrNothing) {
  auto doc = base_;
  const std::string file = Write(doc.dump());
  const std::string out = (dir_ / "sweep").string();
  Outcome o = RunTool("sweep " + file + " -p /model/bit/inertia_kgm2 -v 80,-1 -o " + out);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("/model/bit/inertia_kgm2"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(out));
  o = RunTool("sweep " + file + " -p /model/no/such -v 1:2:2 -o " + out);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_FALSE(fs::exists(out));
  o = RunTool("sweep " + file + " -p /model/bit/inertia_kgm2 -v 60:120:3 -j 2 -o " + out);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("[3/3]"), std::string::npos) << o.output;
  for (const char* f : {"sweep.csv", "bifurcation.svg", "report.md", "case.json"})
    EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
}

TEST_F(Cli, StabilityReportsTheSteadyStateOrSaysWhyNot) {
  const std::string out = (dir_ / "stab").string();
  Outcome o = RunTool("stability " + std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/saldivar-stickslip.json -o " + out);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("stable: rightmost root -0.2094"), std::string::npos) << o.output;
  EXPECT_TRUE(fs::exists(fs::path(out) / "stability.json"));
  // An induction motor top (its fluxes linearized) is analysed, no longer refused.
  o = RunTool("stability " + std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/induction-motor-stickslip.json -o " +
              (dir_ / "stab_induction").string());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  const std::string out2 = (dir_ / "stab2").string();
  o = RunTool("stability " + std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/jeffcott-unbalance.json -o " + out2);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("/model/kind"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(out2));
  o = RunTool("stability " + std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/saldivar-stickslip.json -p /model/bit/inertia_kgm2 -o " + out2);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_FALSE(fs::exists(out2));
}

TEST_F(Cli, StabilityMapWhoseAnalysisFailsInAWorkerExitsTwo) {
  // The first value passes the check before the threads start; strings of 1e20 m fail inside the workers (more roots
  // on the neutral chain than the analysis takes).
  const std::string file = Write(base_.dump());
  for (const char* jobs : {"1", "2"}) {
    const std::string out = (dir_ / (std::string("map") + jobs)).string();
    const Outcome o = RunTool("stability " + file + " -p /model/string/sections/0/length_m -v 1172,1e20,1e21 -j " +
                              jobs + " -o " + out);
    EXPECT_EQ(o.exit_code, 2) << jobs << " jobs: " << o.output;
    EXPECT_NE(o.output.find("out of range"), std::string::npos) << o.output;
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST_F(Cli, TwoParameterStabilityMap) {
  const std::string file = Write(base_.dump());
  const std::string out = (dir_ / "map2").string();
  Outcome o = RunTool("stability " + file + " --map /model/top/speed_rad_s/knots/1/1=7:10:4 /model/bit/inertia_kgm2=80:100:3 "
                      "--simulate --set /simulation/duration_s=20 --set /statistics/window_s=[10,20] -j 2 -o " + out);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  for (const char* f : {"stability_map.csv", "stability_map.svg", "report.md", "case.json"})
    EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
  // Bad input exits 2 naming the option and the text, before any output.
  const std::string bad = (dir_ / "map-bad").string();
  for (const std::string args : {"--map /model/no_such/field=1:2:3 /model/bit/inertia_kgm2=80:100:3",
                                 "--map /model/bit/inertia_kgm2=1:2 /model/bit/inertia_kgm2=80:100:3",
                                 "--map model/bit/inertia_kgm2=1:2:3 /model/bit/inertia_kgm2=80:100:3",
                                 "--map /model/bit/inertia_kgm2=-5:2:3 /model/top/beta_Nms_per_rad=1:2:2",
                                 "--simulate"}) {
    o = RunTool("stability " + file + " " + args + " -o " + bad);
    EXPECT_EQ(o.exit_code, 2) << args << ": " << o.output;
    EXPECT_TRUE(o.output.find("--map") != std::string::npos || o.output.find("--simulate") != std::string::npos ||
                o.output.find("inertia_kgm2 = -5") != std::string::npos) << args << ": " << o.output;
    EXPECT_FALSE(fs::exists(bad)) << args;
  }
}

TEST_F(Cli, OrbitsContinuesTheBranchFromTheHopfPointAndRefusesBadInput) {
  const std::string file = std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/two-disc-setup.json";
  const std::string out = (dir_ / "orbits").string();
  Outcome o = RunTool("orbits " + file + " --continue /model/upper_disc/input_voltage_V=4:5.2:25 -o " + out);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("1 Hopf point(s): 4.322"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("fold at 4.93"), std::string::npos) << o.output;
  for (const char* f : {"orbits.csv", "orbits.svg", "report.md", "case.json"})
    EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
  const std::string bad = (dir_ / "orbits-bad").string();
  for (const std::string& args : {file + " --continue /model/upper_disc/no_such=1:2",
                                 file + " --continue /model/upper_disc/input_voltage_V=2:1",
                                 file + " --continue model/upper_disc/input_voltage_V=1:2",
                                 file + " --continue /model/string/stiffness_Nm_per_rad=-1:2",
                                 std::string(DRILLWAVE_TEST_SOURCE_DIR) +
                                     "/json-cases/saldivar-stickslip.json --continue /model/bit/inertia_kgm2=80:90",
                                 file}) {
    o = RunTool("orbits " + args + " -o " + bad);
    EXPECT_EQ(o.exit_code, 2) << args << ": " << o.output;
    EXPECT_NE(o.output.find("--continue"), std::string::npos) << args << ": " << o.output;
    EXPECT_FALSE(fs::exists(bad)) << args;
  }
}

// The saddle cycle between the Saldivar string's two attractors at 10 rad/s, from the command line: edge tracking on
// the depth of a top-speed dip finds the boundary near a dip to 7.1249 rad/s and the cycle the run there shadows
// (period 2.585 s; it tends to the Hopf pair's 2.541 s as the top speed comes down, tests/cases/edge_tracking_test.cpp).
TEST_F(Cli, OrbitsEdgeFindsTheSaddleCycleBetweenTheAttractorsAndRefusesBadInput) {
  const std::string file = std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/saldivar-saddle-cycle.json";
  const std::string out = (dir_ / "edge").string();
  Outcome o = RunTool("orbits " + file + " --edge /model/top/speed_rad_s/knots/4/1=9:4 --after 101 -o " + out);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  for (const char* f : {"edge.json", "edge_run.csv", "edge.svg", "report.md", "case.json"})
    EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
  std::ifstream file_json(fs::path(out) / "edge.json");
  const auto edge = nlohmann::json::parse(file_json);
  EXPECT_NEAR(edge["decays"].get<double>(), 7.1249, 1e-3);
  ASSERT_TRUE(edge["cycle_found"].get<bool>()) << edge.dump();
  EXPECT_NEAR(edge["saddle_cycle"]["period_s"].get<double>(), 2.585, 0.01) << edge.dump();
  EXPECT_LT(edge["saddle_cycle"]["relative_change_per_cycle"].get<double>(), 0.01);
  const std::string bad = (dir_ / "edge-bad").string();
  for (const auto& [args, named] :
       {std::pair<std::string, std::string>{"--edge 9:4", "--edge"},
        {"--edge /model/top/speed_rad_s/knots/4/1=9:x", "--edge"},
        {"--edge /model/top/speed_rad_s/knots/4/1=5:4", "do not straddle"},
        {"--edge /model/top/speed_rad_s/knots/4/1=9:4 --channel no_such", "--channel"},
        {"--edge /model/top/speed_rad_s/knots/4/1=9:4 --continue /model/bit/inertia_kgm2=1:2", "excludes"}}) {
    o = RunTool("orbits " + file + " " + args + " -o " + bad);
    EXPECT_NE(o.exit_code, 0) << args << ": " << o.output;
    EXPECT_NE(o.output.find(named), std::string::npos) << args << ": " << o.output;
    EXPECT_FALSE(fs::exists(bad)) << args;
  }
}

TEST_F(Cli, InspectNamesAMissingChannel) {
  const std::string csv = (dir_ / "rec.csv").string();
  {
    std::ofstream out(csv);
    out << "time_s,top_rpm,speed\n";
    for (int i = 0; i < 100; ++i) out << 0.01 * i << ",60," << 50 + i % 7 << "\n";
  }
  const std::string out = (dir_ / "insp").string();
  Outcome o = RunTool("inspect " + csv + " -o " + out);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("bit_rpm"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(out));
  o = RunTool("inspect " + csv + " --bit speed -o " + out);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_TRUE(fs::exists(fs::path(out) / "findings.json"));
}

TEST_F(Cli, CompareChecksItsChannelMapsBeforeWriting) {
  auto doc = base_;
  const std::string file = Write(doc.dump());
  const std::string csv = (dir_ / "rec.csv").string();
  {
    std::ofstream out(csv);
    out << "time_s,top_rpm,bit_rpm,tob_Nm\n";
    for (int i = 0; i < 1000; ++i) out << 0.01 * i << ",95," << 50 + 40 * (i % 300 < 150) << ",7000\n";
  }
  const std::string out = (dir_ / "cmp").string();
  Outcome o = RunTool("compare " + file + " " + csv + " --map tob_Nm=no_such_channel -o " + out);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("no_such_channel"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(out));
  o = RunTool("compare " + file + " " + csv + " --map tob_Nm=bit_torque_Nm -o " + out);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  for (const char* f : {"comparison.json", "report.md", "plot.svg"}) EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
}

TEST_F(Cli, FitWritesTheFittedCaseOrNothing) {
  auto doc = base_;
  const std::string file = Write(doc.dump());
  const std::string truth = (dir_ / "truth").string();
  ASSERT_EQ(RunTool("run " + file + " -o " + truth).exit_code, 0);
  const std::string out = (dir_ / "fit").string();
  Outcome o = RunTool("fit " + file + " " + truth + "/trajectory.csv -p /model/bit/friction/mu_s:0.9:0.5 -o " + out);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("lower < upper"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(out));
  o = RunTool("fit " + file + " " + truth + "/trajectory.csv -p /model/bit/friction/mu_s:0.6:0.9 --set "
              "/model/bit/friction/mu_s=0.75 --max-evaluations 6 -o " + out);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  for (const char* f : {"fitted-case.json", "fit.json", "report.md", "plot.svg"})
    EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
}

TEST_F(Cli, DiagnoseRejectsABadSidecarAndWritesNothing) {
  const std::string sidecar = (dir_ / "side.json").string();
  std::ofstream(sidecar) << R"({"recording": "x", "duration_s": 10})";
  const std::string csv = (dir_ / "rec.csv").string();
  {
    std::ofstream out(csv);
    out << "time_s,top_rpm,bit_rpm\n";
    for (int i = 0; i < 100; ++i) out << 0.1 * i << ",60,60\n";
  }
  const std::string out = (dir_ / "dg").string();
  const Outcome o = RunTool("diagnose " + std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/baseline-60rpm.json " +
                            csv + " --sidecar " + sidecar + " -o " + out);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  // The sidecar's own file and the entry in it, not the case generated from it.
  EXPECT_NE(o.output.find(sidecar + ": /well/measured_depth_m: missing"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(out));
}

// calibrate end to end on a short noisy twin of the two-mass case: the posterior's files, a chain of the asked
// size, and the P(stick-slip) map over its samples; bad options exit 2 naming the option, writing nothing.
TEST_F(Cli, CalibrateWritesThePosteriorAndStabilityMapsOverItsSamples) {
  const std::string cases = std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/";
  const std::string twin = (dir_ / "twin").string();
  ASSERT_EQ(RunTool("run " + cases + "two-mass-stickslip.json --set /simulation/duration_s=60 --set /statistics/window_s=[30,60] -o " + twin).exit_code, 0);
  const std::string csv = twin + "/trajectory.csv";
  const std::string post = (dir_ / "post").string();
  const std::string common = "calibrate " + cases + "two-mass-stickslip.json " + csv +
                             " --map top_rpm=top_rpm bit_rpm=bit_rpm --fit-window 30,45 --held-out 45,59 "
                             "--params /model/bit/friction/mu_s:0.55:1.2 ";
  const Outcome o = RunTool(common + "--walkers 4 --steps 4 --burn-in 2 --predictive-draws 3 -o " + post);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  for (const char* f : {"posterior_samples.csv", "posterior.json", "predictive.csv", "posterior.svg", "map-case.json",
                        "report.md"})
    EXPECT_TRUE(fs::exists(fs::path(post) / f)) << f;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(fs::path(post) / "posterior.json"));
  EXPECT_EQ(j["walkers"], 4);
  EXPECT_EQ(j["steps"], 4);
  EXPECT_EQ(j["predictive_runs"], 3);
  const std::string map = (dir_ / "pmap").string();
  const Outcome m = RunTool("stability " + cases + "two-mass-stickslip.json --map "
                            "/model/top/speed_rad_s/knots/1/1=0.5:5:3 /model/bit/friction/W_N=50000:150000:2 --draws " +
                            post + "/posterior_samples.csv -o " + map);
  ASSERT_EQ(m.exit_code, 0) << m.output;
  EXPECT_TRUE(fs::exists(fs::path(map) / "p_stick_slip.svg"));
  std::ifstream table(fs::path(map) / "stability_map.csv");
  std::string header;
  std::getline(table, header);
  EXPECT_NE(header.find(",p_linearly_unstable,p_stick_slip"), std::string::npos) << header;
  // Bad input: the option named, exit 2, nothing written.
  const std::string bad = (dir_ / "bad").string();
  Outcome b = RunTool(common + "--walkers 3 -o " + bad);
  EXPECT_EQ(b.exit_code, 2) << b.output;
  EXPECT_NE(b.output.find("--walkers"), std::string::npos) << b.output;
  b = RunTool("stability " + cases + "two-mass-stickslip.json --draws " + post + "/posterior_samples.csv -o " + bad);
  EXPECT_EQ(b.exit_code, 2) << b.output;
  EXPECT_NE(b.output.find("--draws"), std::string::npos) << b.output;
  EXPECT_FALSE(fs::exists(bad));
}

TEST_F(Cli, CompareWithASidecarRunsTheWarmUpAndComparesInRecordingTime) {
  const fs::path synthetic = fs::path(DRILLWAVE_SHARED_DIR) / "recordings" / "synthetic";
  if (!fs::exists(synthetic / "rec07.csv")) GTEST_SKIP() << "the synthetic recordings are not at " << synthetic;
  const std::string out = (dir_ / "cmp").string();
  const Outcome o = RunTool("compare " + std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/baseline-60rpm.json " +
                            (synthetic / "rec07.csv").string() + " --sidecar " + (synthetic / "rec07.json").string() +
                            " -o " + out);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const nlohmann::json c = nlohmann::json::parse(std::ifstream(fs::path(out) / "comparison.json"));
  // Recording time, the first 5 s left to settle, to the recording's end (100 s): not the model's own time.
  EXPECT_DOUBLE_EQ(c["window_s"][0].get<double>(), 5.0);
  EXPECT_NEAR(c["window_s"][1].get<double>(), 100.0, 0.02);
}

TEST_F(Cli, KindsListsFieldsWithUnits) {
  const Outcome o = RunTool("kinds");
  EXPECT_EQ(o.exit_code, 0);
  EXPECT_NE(o.output.find("torsional_wave"), std::string::npos);
  EXPECT_NE(o.output.find("length_m"), std::string::npos);
  for (const char* kind : {"two_mass", "two_disc", "jeffcott", "axial_torsional"})
    EXPECT_NE(o.output.find(kind), std::string::npos) << kind;
}

// Issue 41: `stability` on a many-section string and `inspect` on a huge recording said nothing until the end.
// Long work now says on stderr every 5 s what it does and how far it is; DRILLWAVE_PROGRESS_S shortens the interval
// here so that short work shows it too (and without it, short work stays quiet).
TEST_F(Cli, LongWorkSaysWhatItDoesAndHowFarItIs) {
  nlohmann::json doc = nlohmann::json::parse(
      std::ifstream(std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/saldivar-collars.json"));
  doc.erase("expect");
  nlohmann::json sections = nlohmann::json::array();
  for (int k = 0; k < 8; ++k)
    sections.push_back({{"name", "s" + std::to_string(k)}, {"length_m", 150 + 7 * k}, {"shear_modulus_Pa", 79.3e9},
                        {"density_kg_m3", 8000}, {"polar_moment_m4", 1.19e-5 * (1 + 0.3 * (k % 3))}});
  doc["model"]["string"]["sections"] = sections;
  const std::string file = Write(doc.dump());
  const std::string stability = "stability " + file + " --no-run -o " + (dir_ / "stab").string();
  Outcome o = drillwave::test_support::RunCommand("DRILLWAVE_PROGRESS_S=0.01 " + std::string(DRILLWAVE_BINARY) + " " +
                                                  stability);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("drillwave: characteristic roots of a linear system of 17 states: "), std::string::npos)
      << o.output;
  o = RunTool(stability);
  EXPECT_EQ(o.output.find("characteristic roots of"), std::string::npos) << "quiet under 5 s: " << o.output;

  const fs::path csv = dir_ / "wide.csv";
  {
    std::ofstream out(csv);
    out << "time_s,top_rpm,bit_rpm";
    for (int j = 0; j < 800; ++j) out << ",c" << j;
    out << "\n";
    // 3.2 million cells: reading and inspecting them lasts well over the 10-ms interval on any machine (400 rows
    // were done before the progress thread's first look on an idle one).
    for (int i = 0; i < 4000; ++i) {
      out << 0.01 * i << ",60," << (i % 40 < 20 ? 0 : 90);
      for (int j = 0; j < 800; ++j) out << "," << (i * (j + 3)) % 17;
      out << "\n";
    }
  }
  o = drillwave::test_support::RunCommand("DRILLWAVE_PROGRESS_S=0.01 " + std::string(DRILLWAVE_BINARY) +
                                          " inspect " + csv.string() + " -o " + (dir_ / "insp").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const bool reading = o.output.find("drillwave: reading " + csv.string() + ": ") != std::string::npos;
  const bool inspecting = o.output.find("drillwave: inspect " + csv.string() + ": ") != std::string::npos;
  EXPECT_TRUE(reading || inspecting) << o.output.substr(0, 2000);
}

}  // namespace
