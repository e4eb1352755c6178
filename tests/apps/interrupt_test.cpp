// A run killed while it writes its outputs (issue 16): the target folder keeps its old contents, whole, and no
// staging folder outlives the run (SIGTERM: removed by the dying run; SIGKILL: removed by the next run).
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using drillwave::test_support::RunTool;

std::map<std::string, std::string> Snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    std::ifstream in(e.path(), std::ios::binary);
    files[e.path().filename().string()] = {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  return files;
}

std::vector<std::string> StagingFolders(const fs::path& parent) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(parent))
    if (e.path().filename().string().find(".staging-") != std::string::npos) names.push_back(e.path().filename());
  return names;
}

class Interrupt : public ::testing::TestWithParam<int> {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("drillwave-interrupt-" + std::to_string(::getpid()) + "-" +
                                        std::to_string(GetParam()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A case whose trajectory.csv is tens of megabytes, so that writing it takes a while.
  std::string BigCase(double duration_s) {
    std::ifstream in(std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/saldivar-stickslip.json");
    auto doc = nlohmann::json::parse(in);
    doc["simulation"]["duration_s"] = duration_s;
    doc["simulation"]["output_interval_s"] = 0.002;
    doc["statistics"]["window_s"] = {0, duration_s};
    doc.erase("expect");
    const std::string file = (dir_ / "big.json").string();
    std::ofstream(file) << doc.dump();
    return file;
  }

  // Starts `drillwave run CASE -o OUT`, waits until its staging folder holds more than a megabyte of
  // trajectory.csv, sends `signal` and returns the exit status; -1 if the run finished before it could be caught.
  int KillWhileWriting(const std::string& case_file, const fs::path& out, int signal) {
    const std::string binary = DRILLWAVE_BINARY, output = out.string();
    std::vector<char*> argv = {const_cast<char*>(binary.c_str()), const_cast<char*>("run"),
                               const_cast<char*>(case_file.c_str()), const_cast<char*>("-o"),
                               const_cast<char*>(output.c_str()), nullptr};
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) return -2;
    const fs::path staging = dir_ / (".out.staging-" + std::to_string(pid) + "-0") / "trajectory.csv";
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    int status = 0;
    while (std::chrono::steady_clock::now() < deadline) {
      std::error_code ignored;
      if (fs::file_size(staging, ignored) > (1u << 20) && !ignored) {
        ::kill(pid, signal);
        ::waitpid(pid, &status, 0);
        return status;
      }
      if (::waitpid(pid, &status, WNOHANG) == pid) return -1;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    return -1;
  }

  fs::path dir_;
};

TEST_P(Interrupt, KilledMidWriteLeavesTheOldFolderWholeAndNoLeftovers) {
  const int signal = GetParam();
  const fs::path out = dir_ / "out";
  // The old folder: a finished short run.
  std::ifstream in(std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/saldivar-stickslip.json");
  auto small = nlohmann::json::parse(in);
  small["simulation"]["duration_s"] = 5;
  small["statistics"]["window_s"] = {0, 5};
  small.erase("expect");
  std::ofstream(dir_ / "small.json") << small.dump();
  ASSERT_EQ(RunTool("run " + (dir_ / "small.json").string() + " -o " + out.string()).exit_code, 0);
  auto before = Snapshot(out);

  int status = -1;
  for (double duration = 1000; status == -1 && duration <= 8000; duration *= 2) {
    status = KillWhileWriting(BigCase(duration), out, signal);
    if (status == -1) before = Snapshot(out);  // that run finished and replaced the folder: the new old one
  }
  ASSERT_NE(status, -1) << "every run finished before it could be interrupted";
  if (signal == SIGKILL) {
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    EXPECT_EQ(StagingFolders(dir_).size(), 1u) << "SIGKILL leaves the partial staging folder behind...";
  } else {
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 128 + signal);
    EXPECT_TRUE(StagingFolders(dir_).empty()) << "a terminated run removes its own staging folder";
  }
  EXPECT_EQ(Snapshot(out), before) << "the target folder is the old one, whole";

  // ...which the next run into the same parent folder removes, its process being gone.
  ASSERT_EQ(RunTool("run " + (dir_ / "small.json").string() + " -o " + (dir_ / "other").string()).exit_code, 0);
  EXPECT_TRUE(StagingFolders(dir_).empty());
  EXPECT_EQ(Snapshot(out), before);
}

INSTANTIATE_TEST_SUITE_P(Signals, Interrupt, ::testing::Values(SIGKILL, SIGTERM, SIGINT));

}  // namespace
