// The one thread pool: results in index order whatever the number of threads, and a worker's exception reaches the
// caller with its type and message (the lowest failing index's, as a serial loop would throw) instead of aborting.
#include <sched.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/core/parallel.hpp"

namespace drillwave {
namespace {

struct ItemFailure : std::runtime_error {
  explicit ItemFailure(std::size_t i) : std::runtime_error("item " + std::to_string(i) + " failed"), index(i) {}
  std::size_t index;
};

TEST(ParallelMap, ResultsComeInIndexOrder) {
  for (int threads : {1, 2, 3, 8}) {
    const auto squares = ParallelMap(50, threads, [](std::size_t i) { return std::to_string(i * i); });
    ASSERT_EQ(squares.size(), 50u);
    for (std::size_t i = 0; i < squares.size(); ++i) EXPECT_EQ(squares[i], std::to_string(i * i)) << threads;
  }
  EXPECT_TRUE(ParallelMap(0, 2, [](std::size_t i) { return i; }).empty());
  EXPECT_THROW(ParallelMap(3, 0, [](std::size_t i) { return i; }), std::invalid_argument);
}

TEST(ParallelMap, ProgressIsCalledOnceForEveryItemOneAtATime) {
  int calls = 0;  // not atomic: progress runs from one thread at a time
  std::size_t last_done = 0;
  ParallelMap(
      40, 2, [](std::size_t i) { return 2 * i; },
      [&](std::size_t result, std::size_t done, std::size_t total) {
        ++calls;
        EXPECT_EQ(result % 2, 0u);
        EXPECT_EQ(done, last_done + 1);
        EXPECT_EQ(total, 40u);
        last_done = done;
      });
  EXPECT_EQ(calls, 40);
}

TEST(ParallelMap, AWorkersExceptionReachesTheCallerAndStopsTheWork) {
  const std::size_t n = 1000, k = 5;
  for (int threads : {1, 2}) {
    std::atomic<std::size_t> started{0};
    try {
      ParallelMap(n, threads, [&](std::size_t i) {
        ++started;
        if (i == k) throw ItemFailure(i);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        return i;
      });
      FAIL() << "the failure of item " << k << " was lost (" << threads << " threads)";
    } catch (const ItemFailure& e) {
      EXPECT_EQ(e.index, k);
      EXPECT_STREQ(e.what(), "item 5 failed");
    }
    // No item is handed out once the failure is known; the serial map stops right at it.
    if (threads == 1) {
      EXPECT_EQ(started.load(), k + 1);
    }
    EXPECT_LT(started.load(), 100u) << threads << " threads";
  }
}

TEST(ParallelMap, TheLowestFailingIndexWinsWhateverFailsFirst) {
  // With 2 threads item 7 fails first in time while item 3 is still running; the caller sees item 3's failure, as
  // with one thread.
  for (int threads : {1, 2}) {
    try {
      ParallelMap(20, threads, [](std::size_t i) {
        if (i == 3) {
          std::this_thread::sleep_for(std::chrono::milliseconds(50));
          throw ItemFailure(i);
        }
        if (i == 7) throw std::logic_error("item 7");
        return i;
      });
      FAIL() << "nothing thrown";
    } catch (const ItemFailure& e) {
      EXPECT_EQ(e.index, 3u) << threads << " threads";
    }
  }
}

TEST(ParallelMap, AProgressCallbacksExceptionStopsTheMapToo) {
  EXPECT_THROW(ParallelMap(
                   10, 2, [](std::size_t i) { return i; },
                   [](std::size_t, std::size_t done, std::size_t) {
                     if (done == 4) throw std::runtime_error("cancelled");
                   }),
               std::runtime_error);
}

// Under `taskset -c 0` (or a container's cpuset) the default is the one CPU the process may use, not every CPU of
// the machine; with the mask restored, every CPU it allows.
TEST(DefaultThreadCount, IsTheNumberOfCpusTheAffinityMaskAllows) {
  cpu_set_t original;
  ASSERT_EQ(sched_getaffinity(0, sizeof original, &original), 0);
  if (CPU_COUNT(&original) < 2) GTEST_SKIP() << "only one CPU allowed already: a wider default cannot show";
  cpu_set_t one;
  CPU_ZERO(&one);
  for (int cpu = 0; cpu < CPU_SETSIZE && CPU_COUNT(&one) == 0; ++cpu)
    if (CPU_ISSET(cpu, &original)) CPU_SET(cpu, &one);
  ASSERT_EQ(sched_setaffinity(0, sizeof one, &one), 0);
  const int restricted = DefaultThreadCount();
  ASSERT_EQ(sched_setaffinity(0, sizeof original, &original), 0);
  EXPECT_EQ(restricted, 1);
  EXPECT_EQ(DefaultThreadCount(), CPU_COUNT(&original));
}

}  // namespace
}  // namespace drillwave
