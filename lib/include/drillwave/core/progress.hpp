#pragma once
// Progress of long computations (issue 41: `stability` on a 100-section string said nothing for 571 s of CPU,
// `inspect` on a 391 MB recording nothing for 569 s). Long tasks say what they are doing through Progress; nothing
// is shown unless a program installs a sink (the command-line tool prints to stderr), so library calls and the
// Python module stay silent. With a sink, a thread of its own shows every task that has run longer than the
// interval, once per interval: its current step and, where known, how far it is — also while one step (a large
// eigenvalue problem) takes long.
//
//   Progress progress("inspect " + file);
//   for (std::size_t j = 0; j < n; ++j) {
//     progress.Count("masking artefacts", j, n, "channels");
//     ...
//   }
#include <chrono>
#include <functional>
#include <string>

namespace drillwave {

// Installs `sink` (nullptr: none) for the tasks created from now on and starts the thread that calls it every
// `interval_s` seconds with one line per task running longer than that.
void SetProgressSink(std::function<void(const std::string&)> sink, double interval_s = 5);

class Progress {
 public:
  explicit Progress(std::string task);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // What the task does now ("computing the eigenvalues of 12000 unknowns").
  void Step(std::string step);
  // What it does now and how far it is in it: "<step>: <done> of <total> <unit> (<percent> %)".
  void Count(const std::string& step, double done, double total, const std::string& unit);

  // The line shown for this task after `elapsed_s`: "<task>: <step>[: done of total unit (x %)], <elapsed> s".
  std::string Line(double elapsed_s) const;

 private:
  friend void TickProgress();
  std::string task_, step_, unit_;
  double done_ = 0, total_ = 0;
  std::chrono::steady_clock::time_point start_;
  bool active_;
};

// Calls the sink once for every task running longer than the interval (what the sink's thread does each interval;
// for tests).
void TickProgress();

}  // namespace drillwave
