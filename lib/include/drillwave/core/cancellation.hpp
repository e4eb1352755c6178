#pragma once
// Cooperative cancellation of long work: a caller that can be interrupted (the Python module on Ctrl-C) raises the
// process-wide flag, and the work stops at its next check — every integration step and every item of a ParallelMap —
// by throwing Cancelled, which no run, sweep, map or fit catches as one of its own failures. The command-line tool
// never raises it (a signal ends its process, see io/output_dir.hpp).
//
//   RequestCancellation();   // from the thread that saw the interrupt
//   ...                      // the work throws Cancelled from its threads; the caller joins it
//   ClearCancellation();     // before the next call
#include <atomic>
#include <stdexcept>

namespace drillwave {

class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

namespace detail {
inline std::atomic<bool> cancellation_requested{false};
}  // namespace detail

inline void RequestCancellation() { detail::cancellation_requested.store(true, std::memory_order_relaxed); }
inline void ClearCancellation() { detail::cancellation_requested.store(false, std::memory_order_relaxed); }
inline bool CancellationRequested() { return detail::cancellation_requested.load(std::memory_order_relaxed); }
inline void ThrowIfCancelled() {
  if (CancellationRequested()) throw Cancelled();
}

}  // namespace drillwave
