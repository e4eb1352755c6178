#pragma once
// Future times where the solution or one of its low derivatives is not smooth (jumps and kinks of inputs,
// events, and their echoes after each travel time). The integrator steps exactly onto each of them.
#include <algorithm>
#include <limits>
#include <map>
#include <vector>

namespace drillwave::integration {

struct Breakpoint {
  double time;
  int site;       // where the breakpoint acts: a node of a wave network, a delay of a DDE, ...
  double weight;  // signed size of the discontinuity relative to its origin; echoes below a threshold are dropped
  int order;      // which derivative jumps (0: the value itself)
  int via = -1;   // where it came from (a section of a wave network), -1 for a source
  int generation = 0;  // how many times it has been passed on
};

// Pending breakpoints in time order. Echoes that reach the same site by the same way at the same time (within a
// merge window) are one discontinuity: their signed weights add. Without merging, every junction doubles the
// echoes of each pass and their number grows exponentially; merged, it grows only with the number of distinct
// arrival times, and cancelling paths (the reflections of an energy-conserving junction) drop out.
class BreakpointQueue {
 public:
  // Adds b, or adds its weight to a pending breakpoint of the same site, way and order within merge_window of its
  // time. Returns false if it was merged.
  bool Push(const Breakpoint& b, double merge_window = 0) {
    if (merge_window > 0 && Merge(b, merge_window)) return false;
    pending_.emplace(b.time, b);
    return true;
  }
  // Adds b's weight to a pending breakpoint of the same site, way and order within merge_window; false if none.
  bool Merge(const Breakpoint& b, double merge_window) {
    for (auto it = pending_.lower_bound(b.time - merge_window); it != pending_.end() && it->first <= b.time + merge_window;
         ++it) {
      Breakpoint& p = it->second;
      if (p.site == b.site && p.via == b.via && p.order == b.order) {
        p.weight += b.weight;
        p.generation = std::min(p.generation, b.generation);
        return true;
      }
    }
    return false;
  }
  bool empty() const { return pending_.empty(); }
  double NextTime() const { return pending_.empty() ? std::numeric_limits<double>::infinity() : pending_.begin()->first; }
  // Removes and returns every breakpoint at time t (within tol): several echoes can arrive at the same instant.
  std::vector<Breakpoint> PopAt(double t, double tol) {
    std::vector<Breakpoint> due;
    auto end = pending_.upper_bound(t + tol);
    for (auto it = pending_.begin(); it != end; ++it) due.push_back(it->second);
    pending_.erase(pending_.begin(), end);
    return due;
  }
  std::size_t size() const { return pending_.size(); }

 private:
  std::multimap<double, Breakpoint> pending_;
};

}  // namespace drillwave::integration
