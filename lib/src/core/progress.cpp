#include "drillwave/core/progress.hpp"

#include <condition_variable>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>
#include <utility>

namespace drillwave {
namespace {

// Guards the sink, the interval and every registered task's step and counts.
std::mutex progress_mutex;
std::function<void(const std::string&)>& Sink() {
  static std::function<void(const std::string&)> sink;
  return sink;
}
std::set<Progress*>& Tasks() {
  static std::set<Progress*> tasks;
  return tasks;
}
double interval_s = 5;
bool ticker_started = false;

}  // namespace

void SetProgressSink(std::function<void(const std::string&)> sink, double interval) {
  std::lock_guard<std::mutex> lock(progress_mutex);
  Sink() = std::move(sink);
  interval_s = interval;
  if (!Sink() || ticker_started) return;
  ticker_started = true;
  std::thread([] {
    for (;;) {
      double wait;
      {
        std::lock_guard<std::mutex> lock(progress_mutex);
        wait = interval_s;
      }
      std::this_thread::sleep_for(std::chrono::duration<double>(wait > 0.01 ? wait : 0.01));
      TickProgress();
    }
  }).detach();
}

void TickProgress() {
  std::lock_guard<std::mutex> lock(progress_mutex);
  if (!Sink()) return;
  const auto now = std::chrono::steady_clock::now();
  for (const Progress* task : Tasks()) {
    const double elapsed = std::chrono::duration<double>(now - task->start_).count();
    if (elapsed >= interval_s) Sink()(task->Line(elapsed));
  }
}

Progress::Progress(std::string task) : task_(std::move(task)), start_(std::chrono::steady_clock::now()) {
  std::lock_guard<std::mutex> lock(progress_mutex);
  active_ = static_cast<bool>(Sink());
  if (active_) Tasks().insert(this);
}

Progress::~Progress() {
  if (!active_) return;
  std::lock_guard<std::mutex> lock(progress_mutex);
  Tasks().erase(this);
}

void Progress::Step(std::string step) {
  if (!active_) return;
  std::lock_guard<std::mutex> lock(progress_mutex);
  step_ = std::move(step);
  unit_.clear();
  done_ = total_ = 0;
}

void Progress::Count(const std::string& step, double done, double total, const std::string& unit) {
  if (!active_) return;
  std::lock_guard<std::mutex> lock(progress_mutex);
  if (step_ != step) step_ = step;
  if (unit_ != unit) unit_ = unit;
  done_ = done;
  total_ = total;
}

std::string Progress::Line(double elapsed_s) const {
  std::ostringstream line;
  line.precision(3);
  line << task_;
  if (!step_.empty()) line << ": " << step_;
  if (total_ > 0) {
    line.precision(12);
    line << ": " << done_ << " of " << total_ << (unit_.empty() ? "" : " ") << unit_;
    line.precision(3);
    line << " (" << 100 * done_ / total_ << " %)";
  }
  line << ", " << static_cast<long long>(elapsed_s) << " s";
  return line.str();
}

}  // namespace drillwave
