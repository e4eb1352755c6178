// core/progress: long tasks say what they do and how far they are, only through a sink a program installs.
#include "drillwave/core/progress.hpp"

#include <algorithm>
#include <mutex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace drillwave {
namespace {

TEST(Progress, ShowsEachRunningTasksStepAndCountOnlyWithASink) {
  {
    Progress silent("a task before any sink");
    silent.Count("step", 1, 2, "items");
    TickProgress();  // no sink: nothing to call, nothing registered
  }
  std::mutex mutex;
  std::vector<std::string> lines;
  SetProgressSink(
      [&](const std::string& line) {
        std::lock_guard<std::mutex> lock(mutex);
        lines.push_back(line);
      },
      0);  // every task is due at once
  {
    Progress task("inspect rec.csv");
    task.Count("artefacts of each channel", 3, 12, "channels");
    TickProgress();
    task.Step("which channels move together");
    TickProgress();
  }
  TickProgress();  // the task is over: nothing more about it
  SetProgressSink(nullptr);
  std::lock_guard<std::mutex> lock(mutex);
  // (the sink's own thread may have shown the same lines as well)
  auto shown = [&](const std::string& line) { return std::find(lines.begin(), lines.end(), line) != lines.end(); };
  EXPECT_TRUE(shown("inspect rec.csv: artefacts of each channel: 3 of 12 channels (25 %), 0 s"));
  EXPECT_TRUE(shown("inspect rec.csv: which channels move together, 0 s"));
  for (const std::string& line : lines) EXPECT_EQ(line.find("before any sink"), std::string::npos) << line;
}

}  // namespace
}  // namespace drillwave
