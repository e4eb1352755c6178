#pragma once
// Wall-clock seconds since a start, for the work a report accounts for (a run's, sweep's or map's wall_time_s,
// diagnosis.json's wall_seconds).
#include <chrono>

namespace drillwave {

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double Seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace drillwave
