#pragma once
// Future times where the solution or one of its low derivatives is not smooth (jumps and kinks of inputs,
// events, and their echoes after each travel time). The integrator steps exactly onto each of them.
#include <limits>
#include <queue>
#include <vector>

namespace drillwave::integration {

struct Breakpoint {
  double time;
  int site;       // where the breakpoint acts: a node of a wave network, a delay of a DDE, ...
  double weight;  // size of the discontinuity relative to its origin; echoes below a threshold are dropped
  int order;      // which derivative jumps (0: the value itself)
  int via = -1;   // where it came from (a section of a wave network), -1 for a source
  int generation = 0;  // how many times it has been passed on
};

class BreakpointQueue {
 public:
  void Push(const Breakpoint& b) { heap_.push(b); }
  bool empty() const { return heap_.empty(); }
  double NextTime() const { return heap_.empty() ? std::numeric_limits<double>::infinity() : heap_.top().time; }
  // Removes and returns every breakpoint at time t (within tol): several echoes can arrive at the same instant.
  std::vector<Breakpoint> PopAt(double t, double tol) {
    std::vector<Breakpoint> due;
    while (!heap_.empty() && heap_.top().time <= t + tol) {
      due.push_back(heap_.top());
      heap_.pop();
    }
    return due;
  }
  std::size_t size() const { return heap_.size(); }

 private:
  struct Later {
    bool operator()(const Breakpoint& a, const Breakpoint& b) const { return a.time > b.time; }
  };
  std::priority_queue<Breakpoint, std::vector<Breakpoint>, Later> heap_;
};

}  // namespace drillwave::integration
