#pragma once
// What the two drilling kinds (axial_torsional on wave strings, lumped_axial_torsional on a spring) sample along a
// run and how they summarize it: one place for the channels and statistics they share.
#include <vector>

#include "drillwave/cases/model_kind.hpp"
#include "drillwave/cases/statistics.hpp"
#include "drillwave/integration/options.hpp"

namespace drillwave::cases {

struct DrillingSamples {
  std::vector<double> time, top, bit, top_torque, bit_torque, wob, depth, vbit, tn, stuck, off, angle;
};

// The steady drilling a run started from: depth of cut per blade [m], rate of penetration [m/s], torque on bit [N m].
struct SteadyDrillingValues {
  double depth, rop, tob;
};

// result.summary: the stick-slip statistics over the settings' window, the window means of WOB, torque on bit, rate
// of penetration and off-bottom share, the steady values and the integrator's counts. result.channels and
// plot_panels: the shared channels, moved out of samples, with `hookload` after wob_N when it is not empty.
void SummarizeDrillingRun(DrillingSamples& samples, std::vector<double> hookload,
                          const std::vector<StuckInterval>& stuck, const RunSettings& settings,
                          const SteadyDrillingValues& steady, const integration::IntegrationStats& stats,
                          RunResult& result);

}  // namespace drillwave::cases
