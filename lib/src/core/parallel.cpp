#include "drillwave/core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>

#if defined(__linux__)
#include <sched.h>
#endif

#include "drillwave/core/cancellation.hpp"

namespace drillwave {

int DefaultThreadCount() {
#if defined(__linux__)
  cpu_set_t allowed;
  // Fails (EINVAL) only on machines with more CPUs than a cpu_set_t holds (1024); the count of all CPUs then.
  if (sched_getaffinity(0, sizeof allowed, &allowed) == 0 && CPU_COUNT(&allowed) > 0) return CPU_COUNT(&allowed);
#endif
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

void ParallelFor(std::size_t n, int threads, const std::function<void(std::size_t)>& body) {
  if (threads < 1) throw std::invalid_argument("ParallelFor: threads must be >= 1, got " + std::to_string(threads));
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex error_mutex;
  std::exception_ptr error;
  std::size_t error_index = n;
  // Every index below a failing one was handed out before it and runs to its end, so the lowest failing index is
  // always among those caught.
  auto worker = [&]() noexcept {
    while (!stop.load()) {
      const std::size_t i = next++;
      if (i >= n) return;
      try {
        ThrowIfCancelled();  // an interrupted caller hands out no further item
        body(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (i < error_index) error = std::current_exception(), error_index = i;
        stop = true;
      }
    }
  };
  const std::size_t count = std::min<std::size_t>(static_cast<std::size_t>(threads), n);
  std::vector<std::thread> pool;
  pool.reserve(count > 0 ? count - 1 : 0);
  try {
    for (std::size_t t = 1; t < count; ++t) pool.emplace_back(worker);
  } catch (const std::system_error&) {
    // No more threads to be had: those started and the caller's do the work.
  }
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace drillwave
