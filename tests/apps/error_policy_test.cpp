// The error policy (issues 15, 16 and 41) as a user meets it: exit codes 0 / 1 / 2 / 3 / 4 / 5 / 6, bad input named with
// its path and value before any work starts, non-finite runs as numerical failures, output folders replaced whole and
// only when they hold nothing but drillwave's outputs, write failures after the work named with the file and cause.
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace {

namespace fs = std::filesystem;
using drillwave::test_support::Outcome;
using drillwave::test_support::RunTool;

const std::string kCases = std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/";

std::string Contents(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class ErrorPolicy : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = drillwave::test_support::ScratchFolder("policy");
    std::ifstream in(kCases + "saldivar-stickslip.json");
    base_ = nlohmann::json::parse(in);
    base_["simulation"]["duration_s"] = 10;
    base_["statistics"]["window_s"] = {5, 10};
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const nlohmann::json& doc, const std::string& name = "case.json") {
    const std::string file = (dir_ / name).string();
    std::ofstream(file) << doc.dump();
    return file;
  }
  // Expects `args` to exit with `code`, mention `text`, and write no `out` folder.
  void Expect(const std::string& args, int code, const std::string& text) {
    const Outcome o = RunTool(args);
    EXPECT_EQ(o.exit_code, code) << args << "\n" << o.output;
    EXPECT_NE(o.output.find(text), std::string::npos) << "expected '" << text << "' in: " << o.output;
    EXPECT_FALSE(fs::exists(dir_ / "out")) << args;
  }
  std::string Out() const { return " -o " + (dir_ / "out").string(); }

  fs::path dir_;
  nlohmann::json base_;
};

TEST_F(ErrorPolicy, OptionErrorsAreBadInputNotCli11Codes) {
  // CLI11 exits 104-109 by itself; the policy says 2.
  Expect("run " + Write(base_) + " --bogus" + Out(), 2, "--bogus");
  Expect("sweep " + Write(base_) + " -v 1:2:2" + Out(), 2, "--param");
  Expect("sweep " + Write(base_) + " -p /model/bit/inertia_kgm2 -v 80,90 -j many" + Out(), 2, "many");
  EXPECT_EQ(RunTool("--help").exit_code, 0);
}

TEST_F(ErrorPolicy, EmptyPathsAreErrorsNotTheDefaultCase) {
  Expect("run ''" + Out(), 2, "case: empty value");
  Expect("validate ''", 2, "case: empty value");
  Expect("inspect ''" + Out(), 2, "recording: empty value");
  Expect("run " + Write(base_) + " -o ''", 2, "--out: empty value");
  Expect("diagnose " + kCases + "baseline-60rpm.json " + Write(base_, "x.csv") + " --sidecar ''" + Out(), 2,
         "--sidecar: empty value");
}

TEST_F(ErrorPolicy, ExpectBlocksAreValidated) {
  auto doc = base_;
  doc["expect"] = {{"stick_slip_period_s", {{"min", "3.2"}}}};  // was an uncaught type_error.302, exit 1
  Expect("run " + Write(doc) + Out(), 2, "/expect/stick_slip_period_s/min: expected a finite number, got a string");
  doc["expect"] = {{"stick_fraction", {{"min", 0.5}, {"max", 0.4}}}};
  Expect("validate " + Write(doc), 2, "/expect/stick_fraction: the range [min, max] = [0.5, 0.4] is reversed");
  doc["expect"] = {{"stick_fraction", {{"rel_tol", 0.1}}}};
  Expect("validate " + Write(doc), 2, "/expect/stick_fraction/rel_tol: a tolerance needs a \"value\"");
  doc["expect"] = {{"stick_fraction", {{"value", 0.4}, {"rel_tol", -1}}}};
  Expect("validate " + Write(doc), 2, "/expect/stick_fraction/rel_tol: expected a number >= 0, got -1");
  doc["expect"] = {{"stick_fraction", {{"maximum", 0.4}}}};
  Expect("validate " + Write(doc), 2, "/expect/stick_fraction/maximum: unknown field");
}

TEST_F(ErrorPolicy, WorkIsEstimatedAndRefusedAboveTheLimit) {
  auto doc = base_;
  doc["simulation"]["output_interval_s"] = 1e-7;  // 1e8 samples
  Expect("run " + Write(doc) + Out(), 2, "/simulation/output_interval_s: 10 s simulated every 1e-07 s: the number "
                                          "of output samples is 100000000, above the limit of 10000000");
  Expect("validate " + Write(doc), 2, "or raise --max-samples");
  EXPECT_EQ(RunTool("validate " + Write(doc) + " --max-samples 2e8").exit_code, 0);
  doc["simulation"]["output_interval_s"] = 0.01;
  doc["simulation"]["max_step_s"] = 1e-7;
  Expect("validate " + Write(doc), 2, "/simulation/max_step_s: 10 s simulated in steps of at most 1e-07 s");
  Expect("validate " + Write(base_) + " --max-samples 0", 2, "--max-samples: expected a finite number >= 1");
}

TEST_F(ErrorPolicy, AHugeSweepIsRefusedBeforeAnyRun) {
  // Issue 41: a sweep of 1e6 values allocated 3.8 GB before its first run and ended as an internal error (exit 4).
  const Outcome o = drillwave::test_support::RunCommand(
      "timeout 60 " + std::string(DRILLWAVE_BINARY) + " sweep " + Write(base_) +
      " -p /model/bit/inertia_kgm2 -v 50:150:1000000" + Out());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("--values: 1000000 runs of about"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("or raise --max-samples"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

// Issue 38: compare-controllers ran every law again at each actuator delay with no estimate (2 000 delays: 35 min,
// a million: days); its delays are counted as a run of each law (five) before any run.
TEST_F(ErrorPolicy, AMillionActuatorDelaysAreRefusedBeforeAnyRun) {
  const Outcome o = drillwave::test_support::RunCommand(
      "timeout 60 " + std::string(DRILLWAVE_BINARY) + " compare-controllers " + kCases +
      "saldivar-soft-torque.json --actuator-delays 0:1:1000000" + Out());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("--actuator-delays: 5000000 points of about"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("top-drive laws on"), std::string::npos) << "refused only after starting: " << o.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

// AddressSanitizer as gcc (__SANITIZE_ADDRESS__) and clang (__has_feature) say it.
#if defined(__SANITIZE_ADDRESS__)
#define DRILLWAVE_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DRILLWAVE_UNDER_ASAN 1
#endif
#endif
#ifndef DRILLWAVE_UNDER_ASAN
#define DRILLWAVE_UNDER_ASAN 0
#endif

// Issue 41: a run whose trajectory the memory cannot hold (8e6 samples of about 20 channels, some 450 MB, under an
// address-space limit of 400 MB) ended as an internal error (exit 4, std::bad_alloc) after part of the work; now it is
// refused before the run with exit 6, naming both sizes and what to ask for instead.
TEST_F(ErrorPolicy, ARunLargerThanTheMemoryIsRefusedBeforeTheRun) {
#if DRILLWAVE_UNDER_ASAN
  GTEST_SKIP() << "AddressSanitizer maps terabytes of shadow memory: no run starts under an address-space limit";
#endif
  auto doc = base_;
  doc["simulation"]["duration_s"] = 80;
  doc["statistics"]["window_s"] = {40, 80};
  doc["simulation"]["output_interval_s"] = 1e-5;
  const Outcome o = drillwave::test_support::RunCommand("bash -c 'ulimit -v 400000; exec timeout 60 " +
                                                        std::string(DRILLWAVE_BINARY) + " run " + Write(doc) + Out() +
                                                        "'");
  EXPECT_EQ(o.exit_code, 6) << o.output;
  EXPECT_NE(o.output.find("not enough memory: about "), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("of memory for the run's trajectory, but only "), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("/simulation/output_interval_s"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("running case"), std::string::npos) << "refused only after starting: " << o.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(ErrorPolicy, NonFiniteOutputsAreANumericalFailureNeverExitZero) {
  // Issue 16: beta = 1e308 wrote 15 852 NaN rows and a summary "stuck 100 % of the time", exit 0.
  auto doc = base_;
  doc["model"]["top"]["beta_Nms_per_rad"] = 1e308;
  const Outcome o = RunTool("run " + Write(doc) + Out());
  EXPECT_EQ(o.exit_code, 3) << o.output;
  EXPECT_NE(o.output.find("is not finite"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find(" at t = "), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("state = ["), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(ErrorPolicy, ARunawayBitIsANumericalFailureNotAResult) {
  // Issue 39: the exact wave cancellation behind 100 ms ran the coupled baseline's bit to 3.7e8 rad/s by 60 s and
  // wrote it out, exit 0.
  std::ifstream in(kCases + "baseline-60rpm.json");
  auto doc = nlohmann::json::parse(in);
  doc.erase("expect");
  doc["model"]["top"] = {{"type", "wave_cancellation"},    {"inertia_kgm2", 2500},    {"kp_Nms_per_rad", 5000},
                         {"speed_loop_corner_rad_s", 0.2}, {"actuator_delay_s", 0.1}, {"speed_rad_s", 6.283185307}};
  const Outcome o = RunTool("run " + Write(doc) + Out());
  EXPECT_EQ(o.exit_code, 3) << o.output;
  EXPECT_NE(o.output.find("runaway: the bit turns at"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("state = ["), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(ErrorPolicy, EveryChannelsFirstSampleIsDefined) {
  // Every Jeffcott trajectory started with rotor_speed_norm = nan.
  std::ifstream in(kCases + "jeffcott-unbalance.json");
  auto doc = nlohmann::json::parse(in);
  doc["simulation"]["duration_s"] = 0.5;
  doc["statistics"]["window_s"] = {0, 0.5};
  doc.erase("expect");
  const Outcome o = RunTool("run " + Write(doc) + Out());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  std::ifstream csv(dir_ / "out" / "trajectory.csv");
  std::string header, first;
  std::getline(csv, header);
  std::getline(csv, first);
  EXPECT_NE(header.find("rotor_speed_norm"), std::string::npos);
  EXPECT_EQ(first.find("nan"), std::string::npos) << header << "\n" << first;
  EXPECT_EQ(Contents(dir_ / "out" / "summary.json").find("1e+300"), std::string::npos);
}

TEST_F(ErrorPolicy, AFailedWriteNeverLeavesAMixedFolder) {
  // Issue 16's reproduction: an old trajectory and report (plain files with drillwave's names) are replaced whole.
  const fs::path out = dir_ / "o";
  fs::create_directories(out);
  std::ofstream(out / "trajectory.csv") << "OLD\n";
  std::ofstream(out / "report.md") << "OLD\n";
  const Outcome o = RunTool("run " + Write(base_) + " -o " + out.string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_TRUE(fs::is_regular_file(out / "summary.json"));
  EXPECT_EQ(Contents(out / "trajectory.csv").rfind("time_s,", 0), 0u);
  EXPECT_NE(Contents(out / "report.md"), "OLD\n");
  // A folder holding something drillwave did not write is refused before the run, and left as it was.
  std::ofstream(out / "notes.txt") << "mine";
  const std::string before = Contents(out / "trajectory.csv");
  const Outcome refused = RunTool("run " + Write(base_) + " -o " + out.string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("notes.txt"), std::string::npos) << refused.output;
  EXPECT_EQ(refused.output.find("running case"), std::string::npos) << "checked before the run";
  EXPECT_EQ(Contents(out / "trajectory.csv"), before);
  EXPECT_EQ(Contents(out / "notes.txt"), "mine");
}

TEST_F(ErrorPolicy, ASubFolderNamedLikeAnOutputIsRefusedBeforeTheRun) {
  // Issue 41: summary.json/ holding the user's files was replaced with the rest (exit 0, the files gone). Issue 16's
  // own reproduction had an empty summary.json/ replaced; a sub-folder is refused now, empty or not.
  const fs::path out = dir_ / "o";
  fs::create_directories(out / "summary.json");
  fs::create_directories(out / "report.md");
  std::ofstream(out / "summary.json" / "mine.txt") << "mine";
  std::ofstream(out / "trajectory.csv") << "OLD\n";
  const Outcome o = RunTool("run " + Write(base_) + " -o " + out.string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("holds the sub-folder \"report.md/\""), std::string::npos)
      << "the first foreign entry in name order: " << o.output;
  EXPECT_EQ(o.output.find("running case"), std::string::npos) << "checked before the run";
  EXPECT_EQ(Contents(out / "summary.json" / "mine.txt"), "mine");
  EXPECT_EQ(Contents(out / "trajectory.csv"), "OLD\n");
}

TEST_F(ErrorPolicy, ASymbolicLinkAsTheOutputFolderIsRefusedBeforeTheRun) {
  // Documented in README (Exit codes): -o naming a link is refused, so neither the link nor the folder behind it
  // is touched; give the folder itself.
  const fs::path target = dir_ / "target", link = dir_ / "link";
  ASSERT_EQ(RunTool("run " + Write(base_) + " -o " + target.string()).exit_code, 0);
  const std::string before = Contents(target / "trajectory.csv");
  fs::create_directory_symlink(target, link);
  const Outcome o = RunTool("run " + Write(base_) + " -o " + link.string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find(link.string() + " is a symbolic link (to " + target.string() + ")"), std::string::npos)
      << o.output;
  EXPECT_EQ(o.output.find("running case"), std::string::npos) << "checked before the run";
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(Contents(target / "trajectory.csv"), before);
  EXPECT_EQ(RunTool("run " + Write(base_) + " -o " + target.string()).exit_code, 0) << "the folder itself is fine";
}

// A folder this process may read but not write in (mode 555). Root may write anywhere, so for root the tool is run
// as nobody (setpriv), for whom the folder is read-only too.
class ReadOnlyFolder : public ErrorPolicy {
 protected:
  void Lock(const fs::path& folder) {
    fs::permissions(folder, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
  }
  // Why a read-only folder cannot be had here (the test is then skipped); empty if it can.
  std::string WhyNoReadOnlyFolder(const std::string& case_file) {
    if (::geteuid() != 0) return "";
    if (drillwave::test_support::RunCommand("setpriv --version").exit_code != 0)
      return "running as root without setpriv: cannot make a folder read-only";
    as_user_ = "setpriv --reuid=65534 --regid=65534 --clear-groups ";
    if (drillwave::test_support::RunCommand(as_user_ + "test -r " + case_file).exit_code != 0)
      return "nobody cannot read " + case_file + " (a private temporary folder?)";
    return "";
  }
  // Expects `run case_file -o out` to exit 2 with `message`, before the run.
  void ExpectRefusedBeforeTheRun(const std::string& case_file, const fs::path& out, const std::string& message) {
    const Outcome o =
        drillwave::test_support::RunCommand(as_user_ + DRILLWAVE_BINARY + " run " + case_file + " -o " + out.string());
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_NE(o.output.find(message), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("running case"), std::string::npos) << "checked before the run";
  }

  std::string as_user_;
};

TEST_F(ReadOnlyFolder, AnOutputFolderThatCannotBeCreatedIsFoundBeforeTheRun) {
  // Issue 41: a read-only parent was found after the whole simulation, as an internal error (exit 4).
  const fs::path locked = dir_ / "locked";
  fs::create_directories(locked);
  Lock(locked);
  const std::string file = Write(base_), why = WhyNoReadOnlyFolder(file);
  if (!why.empty()) GTEST_SKIP() << why;
  for (const fs::path& out : {locked / "out", locked / "new" / "out"})
    ExpectRefusedBeforeTheRun(file, out, "--out: cannot create " + out.string() + ": the folder " + locked.string() +
                                             " is not writable (Permission denied)");
  fs::permissions(locked, fs::perms::owner_all);
  EXPECT_TRUE(fs::is_empty(locked));
}

TEST_F(ReadOnlyFolder, AnOutputFolderThatCannotBeReplacedIsFoundBeforeTheRun) {
  // An earlier run's folder, writable itself, in a parent made read-only since: the new folder is swapped in by a
  // rename in the parent, which would fail after the whole run. Checked before it (exit 2, naming the parent).
  const fs::path locked = dir_ / "locked", out = locked / "out";
  const std::string file = Write(base_);
  ASSERT_EQ(RunTool("run " + file + " -o " + out.string()).exit_code, 0);
  fs::permissions(out, fs::perms::all);  // so that only the parent stands in the way, for nobody too
  const std::string before = Contents(out / "trajectory.csv");
  Lock(locked);
  const std::string why = WhyNoReadOnlyFolder(file);
  if (!why.empty()) GTEST_SKIP() << why;
  ExpectRefusedBeforeTheRun(file, out, "--out: cannot replace " + out.string() + ": its parent folder " +
                                           locked.string() + " is not writable (Permission denied)");
  fs::permissions(locked, fs::perms::owner_all);
  EXPECT_EQ(Contents(out / "trajectory.csv"), before);
}

TEST_F(ErrorPolicy, AWriteFailureAfterTheRunNamesTheFileAndItsCause) {
  // Issue 41: a full disk was an internal error (exit 4) naming .drillwave-output. A file-size limit (ulimit -f, in
  // blocks of 512 bytes) fails the writes the same way, with "File too large" for "No space left on device".
  const fs::path out = dir_ / "out";
  const std::string file = Write(base_);
  ASSERT_EQ(RunTool("run " + file + " -o " + out.string()).exit_code, 0);
  const std::string before = Contents(out / "trajectory.csv");
  const Outcome o = drillwave::test_support::RunCommand("trap '' XFSZ; ulimit -f 16; exec " +
                                                        std::string(DRILLWAVE_BINARY) + " run " + file + " -o " +
                                                        out.string());
  EXPECT_EQ(o.exit_code, 5) << o.output;
  EXPECT_NE(o.output.find("drillwave: cannot write the outputs: cannot write " + (out / "trajectory.csv").string() +
                          ": File too large"),
            std::string::npos)
      << o.output;
  EXPECT_EQ(o.output.find("internal error"), std::string::npos) << o.output;
  EXPECT_EQ(Contents(out / "trajectory.csv"), before) << "the old folder is kept whole";
  std::vector<std::string> entries;
  for (const auto& e : fs::directory_iterator(dir_)) entries.push_back(e.path().filename().string());
  std::sort(entries.begin(), entries.end());
  EXPECT_EQ(entries, (std::vector<std::string>{"case.json", "out"})) << "no staging folder left";
}

TEST_F(ErrorPolicy, RecordingsAreValidatedByFileLineAndColumn) {
  auto recording = [&](const std::string& name, const std::string& header, const std::string& bad_row) {
    std::ofstream out(dir_ / name);
    out << header << "\n";
    for (int i = 0; i < 50; ++i) out << 0.01 * i << ",60," << 50 + i % 7 << "\n";
    if (!bad_row.empty()) out << bad_row << "\n";
    return (dir_ / name).string();
  };
  const std::string header = "time_s,top_rpm,bit_rpm";
  std::string file = recording("blank.csv", header, "0.5,60,");
  Expect("inspect " + file + Out(), 2, file + ":52: column bit_rpm (3): blank cell");
  file = recording("inf.csv", header, "0.5,inf,60");
  Expect("inspect " + file + Out(), 2, file + ":52: column top_rpm (2): \"inf\" is not a finite number");
  file = recording("time.csv", header, "1e999,60,60");
  Expect("inspect " + file + Out(), 2, file + ":52: column time_s (1): \"1e999\" is not a finite number");
  file = recording("dup.csv", "time_s,bit_rpm,bit_rpm", "");
  Expect("inspect " + file + Out(), 2, "columns 2 and 3 are both named \"bit_rpm\"");
  file = recording("latin1.csv", "time_s,top_rpm,bit_rpm,caf\xE9", "");
  Expect("inspect " + file + Out(), 2, "column 4 of the header (\"caf\\xE9\") has a byte that is not UTF-8");
  file = recording("back.csv", header, "0.2,60,60");
  Expect("inspect " + file + Out(), 2, file + ": column time_s: time does not increase at data row 51 (0.2 s after 0.49 s)");
  Expect("inspect " + (dir_ / "none.csv").string() + Out(), 2, "cannot open CSV file " + (dir_ / "none.csv").string());
}

TEST_F(ErrorPolicy, WindowsFeaturesAndBoundsAreCheckedBeforeAnyRun) {
  auto doc = base_;
  const std::string file = Write(doc);
  const std::string truth = (dir_ / "truth").string();
  ASSERT_EQ(RunTool("run " + file + " -o " + truth).exit_code, 0);
  const std::string csv = truth + "/trajectory.csv";
  Expect("compare " + file + " " + csv + " --window 8,3" + Out(), 2, "--window: '8,3' is reversed");
  Expect("compare " + file + " " + csv + " --window 50,60" + Out(), 2, "--window: fewer than 10 recorded samples");
  Expect("compare " + file + " " + csv + " --map bit_rpm=nothing" + Out(), 2, "the model has no channel nothing");
  Expect("compare " + file + " " + csv + " --map nothing=bit_rpm" + Out(), 2, "has no channel nothing");
  Expect("fit " + file + " " + csv + " -p /model/bit/friction/mu_s:0.6:0.9 --feature no_such" + Out(), 2,
         "--feature: no feature named 'no_such'");
  Expect("fit " + file + " " + csv + " -p /model/bit/friction/mu_s:0.9:0.6" + Out(), 2, "the bounds are reversed");
  Expect("fit " + file + " " + csv + " -p /model/bit/inertia_kgm2:-5:90" + Out(), 2, "the bound -5 is not valid");
  Expect("fit " + file + " " + csv + " -p /model/bit/friction/mu_s:0.6:0.9 --window 9,2" + Out(), 2, "reversed");
}

TEST_F(ErrorPolicy, InspectGrowsLinearlyWithTheNumberOfChannels) {
  // 2 000 channels made 276 MB of outputs from an 8 MB CSV (every pair of channels correlated and listed).
  auto write = [&](int channels) {
    const fs::path file = dir_ / ("wide-" + std::to_string(channels) + ".csv");
    std::ofstream out(file);
    out << "time_s,top_rpm,bit_rpm";
    for (int j = 0; j < channels; ++j) out << ",c" << j;
    out << "\n";
    for (int i = 0; i < 200; ++i) {
      out << 0.01 * i << ",60," << (i % 40 < 20 ? 0 : 90);
      for (int j = 0; j < channels; ++j) out << "," << (i * (j + 3)) % 17;
      out << "\n";
    }
    return file.string();
  };
  auto output_bytes = [&](int channels) {
    const fs::path out = dir_ / ("insp-" + std::to_string(channels));
    const Outcome o = RunTool("inspect " + write(channels) + " -o " + out.string());
    EXPECT_EQ(o.exit_code, 0) << o.output;
    std::uintmax_t bytes = 0;
    for (const auto& e : fs::directory_iterator(out)) bytes += fs::file_size(e.path());
    return static_cast<double>(bytes);
  };
  const double small = output_bytes(100), large = output_bytes(800);
  std::cout << "[ measured ] inspect outputs: " << small << " bytes for 100 channels, " << large << " for 800 (ratio "
            << large / small << "; quadratic growth would give ~64)\n";
  EXPECT_LT(large / small, 12);
}

}  // namespace
