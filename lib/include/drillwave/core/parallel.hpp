#pragma once
// The one thread pool: independent items (sweep runs, stability analyses) mapped in parallel, exception-safe.
//
//   std::vector<double> squares = ParallelMap(values.size(), jobs, [&](std::size_t i) { return Run(values[i]); });
#include <cstddef>
#include <functional>
#include <mutex>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

namespace drillwave {

// The thread count when the user names none: the CPUs this process may run on (on Linux its affinity mask, which
// taskset, cpusets and container runtimes narrow; hardware_concurrency counts every CPU of the machine), at least 1.
int DefaultThreadCount();

// Calls body(i) for every i in [0, n) on min(threads, n) threads, the caller's among them; threads >= 1
// (std::invalid_argument otherwise). Items are handed out in index order. When a body throws, no further item is
// handed out, the items already started finish, every thread is joined, and the exception of the lowest failing
// index is rethrown in the caller (with its own type): the same exception a serial loop would throw.
void ParallelFor(std::size_t n, int threads, const std::function<void(std::size_t)>& body);

// fn(i) for every i in [0, n), in parallel as ParallelFor, returned in index order whatever the number of threads.
// progress(result, done, n), if given, is called after each item, from one thread at a time; an exception it throws
// stops the map like one of fn's.
template <class Fn, class Progress>
auto ParallelMap(std::size_t n, int threads, Fn&& fn, Progress&& progress) {
  using Result = std::decay_t<std::invoke_result_t<Fn&, std::size_t>>;
  std::vector<std::optional<Result>> slots(n);
  std::mutex progress_mutex;
  std::size_t done = 0;
  ParallelFor(n, threads, [&](std::size_t i) {
    slots[i].emplace(fn(i));
    const std::lock_guard<std::mutex> lock(progress_mutex);
    ++done;
    progress(*slots[i], done, n);
  });
  std::vector<Result> results;
  results.reserve(n);
  for (std::optional<Result>& slot : slots) results.push_back(std::move(*slot));
  return results;
}

template <class Fn>
auto ParallelMap(std::size_t n, int threads, Fn&& fn) {
  return ParallelMap(n, threads, std::forward<Fn>(fn), [](const auto&, std::size_t, std::size_t) {});
}

}  // namespace drillwave
