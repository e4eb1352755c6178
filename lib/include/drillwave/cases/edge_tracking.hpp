#pragma once
// Edge tracking: the boundary between two attractors of a case (a stable steady state and a stick-slip cycle) by
// bisection on one parameter of a perturbation, and the saddle cycle on that boundary. A run started just on the
// decaying side of the boundary shadows the saddle cycle that separates the basins before it leaves it, so the
// stretch where its oscillation neither grows nor decays gives that cycle's period and amplitude. This is the honest
// tool for models whose full shooting is heavy (the wave network is a neutral delay system).
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/cases/model_kind.hpp"

namespace drillwave::cases {

struct EdgeSpec {
  std::string pointer;  // the perturbation's parameter (JSON pointer), e.g. a knot of the top-speed schedule
  double decays = 0;    // a value whose run does not stick in the statistics window
  double sticks = 1;    // a value whose run sticks there
  double tolerance = 1e-12;  // bisection stops when |sticks - decays| <= tolerance * max(1, |decays|)
};

struct EdgeResult {
  double decays = 0, sticks = 0;  // the final bracket
  RunResult edge;                 // the run at `decays`: it shadows the saddle cycle
  int runs = 0;
};

// Throws InputError if the two ends do not straddle the boundary (naming the pointer and both values). progress, if
// given, hears the bracket after every run.
EdgeResult TrackEdge(const nlohmann::json& document, const EdgeSpec& spec,
                     const std::function<void(int runs, double decays, double sticks)>& progress = {});

struct ShadowedCycle {
  bool found = false;
  double period_s = 0;          // between the two maxima of the most nearly steady cycle
  double amplitude = 0;         // peak-to-peak of the signal over that cycle
  double time_s = 0;            // where that cycle starts
  double relative_change = 0;   // |A_{k+1} - A_{k-1}| / (2 A_k) there: how nearly steady
};

// The cycle of y(t) (after t_from, between consecutive maxima) whose peak-to-peak amplitude changes least between
// its neighbours, among cycles of at least 1 % of the largest amplitude.
ShadowedCycle FindShadowedCycle(const std::vector<double>& time_s, const std::vector<double>& y, double t_from);

// `drillwave orbits --edge POINTER=decays:sticks`: "POINTER=a:b" with a the value whose run decays to the steady
// state and b one whose run sticks; InputError naming --edge otherwise (and naming the pointer if the case has no
// number there).
EdgeSpec ParseEdgeOption(const std::string& text, const nlohmann::json& document);

// edge.json (bracket, runs, the shadowed cycle of `channel` after `after_s`), edge_run.csv (time and every channel
// of the run at the edge), edge.svg (the channel with the cycle marked), report.md, case.json; all or nothing.
void WriteEdgeOutputs(const nlohmann::json& document, const EdgeSpec& spec, const EdgeResult& edge,
                      const std::string& channel, double after_s, const ShadowedCycle& cycle,
                      const std::string& out_dir);

}  // namespace drillwave::cases
