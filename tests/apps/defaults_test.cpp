// What the tool says and chooses by itself: its version, and the default thread count under a CPU affinity mask.
#include <sched.h>

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

TEST(Version, PrintsTheProjectVersionOfCMakeLists) {
  const Outcome o = RunTool("--version");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(o.output, std::string("drillwave ") + DRILLWAVE_VERSION + "\n");
}

// Restricts the test process (and so the tool it starts, which inherits the mask) to its first allowed CPU, and
// restores the mask afterwards.
class OneCpu : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(sched_getaffinity(0, sizeof original_, &original_), 0);
    if (CPU_COUNT(&original_) < 2) GTEST_SKIP() << "only one CPU allowed already: a wider default cannot show";
    cpu_set_t one;
    CPU_ZERO(&one);
    for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
      if (CPU_ISSET(cpu, &original_)) {
        CPU_SET(cpu, &one);
        break;
      }
    ASSERT_EQ(sched_setaffinity(0, sizeof one, &one), 0);
    restricted_ = true;
    dir_ = drillwave::test_support::ScratchFolder("defaults");
  }
  void TearDown() override {
    if (restricted_) sched_setaffinity(0, sizeof original_, &original_);
    if (!dir_.empty()) fs::remove_all(dir_);
  }

  cpu_set_t original_;
  bool restricted_ = false;
  fs::path dir_;
};

// `taskset -c 0 drillwave sweep ...` on a machine with more CPUs: one thread, not one per CPU of the machine.
TEST_F(OneCpu, SweepRunsOnOneThreadByDefault) {
  std::ifstream in(std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/saldivar-stickslip.json");
  nlohmann::json doc = nlohmann::json::parse(in);
  doc["simulation"]["duration_s"] = 4;
  doc["statistics"]["window_s"] = {2, 4};
  const std::string file = (dir_ / "case.json").string();
  std::ofstream(file) << doc.dump();
  const Outcome o = RunTool("sweep " + file + " -p /model/bit/inertia_kgm2 -v 80,90 -o " + (dir_ / "out").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("over 2 values on 1 thread(s)"), std::string::npos) << o.output;
}

}  // namespace
