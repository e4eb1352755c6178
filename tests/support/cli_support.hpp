#pragma once
// Running the command-line tool from tests: exit code and combined output.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace drillwave::test_support {

struct Outcome {
  int exit_code;  // -1 if the tool did not exit normally (a crash)
  std::string output;
};

// A fresh, empty folder for the running test: TEMP/drillwave-PREFIX-PID-TESTNAME (the caller removes it).
inline std::filesystem::path ScratchFolder(const std::string& prefix) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("drillwave-" + prefix + "-" + std::to_string(::getpid()) + "-" +
       ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Runs a shell command line, stderr merged into the output.
inline Outcome RunCommand(const std::string& command_line) {
  const std::string command = command_line + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

// Runs `drillwave ARGS` (arguments are shell words).
inline Outcome RunTool(const std::string& args) { return RunCommand(std::string(DRILLWAVE_BINARY) + " " + args); }

}  // namespace drillwave::test_support
