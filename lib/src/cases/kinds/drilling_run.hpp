#pragma once
// What the two drilling kinds (axial_torsional on wave strings, lumped_axial_torsional on a spring) sample along a
// run and how they summarize it: one place for the channels and statistics they share.
#include <vector>

#include "drillwave/cases/model_kind.hpp"
#include "drillwave/cases/statistics.hpp"
#include "drillwave/integration/options.hpp"
#include "drillwave/model/schedule.hpp"

namespace drillwave::cases {

struct DrillingSamples {
  std::vector<double> time, top, bit, top_torque, bit_torque, wob, depth, vbit, tn, stuck, off, angle;
};

// The steady drilling a run started from: depth of cut per blade [m], rate of penetration [m/s], torque on bit [N m].
struct SteadyDrillingValues {
  double depth, rop, tob;
};

// A bit turning this many times faster than the fastest speed the top is commanded (at least 1 rad/s) is a run that
// has left physics: stick-slip swings the bit to 2-3 times the set-point and a bouncing bit a few times more, while a
// law or gain that makes the model unstable grows without bound (the exact wave cancellation behind a delay reached
// 3.7e8 rad/s, far below the integrator's own blow-up test, which must allow angles that grow for days).
inline constexpr double kRunawaySpeedFactor = 100;

// The speed beyond which ThrowIfRunaway stops a run: kRunawaySpeedFactor times the schedule's largest |value| or 1.
double RunawaySpeed(const model::Schedule& top_speed);

// Throws NumericalError at t with the state where |bit_speed| exceeds `runaway` (or is not a number): the sampled
// run is stopped there with a message that says what grew, instead of integrating an unbounded solution to the end.
void ThrowIfRunaway(double t, double bit_speed, double runaway, const std::vector<double>& state);

// result.summary: the stick-slip statistics over the settings' window, the window means of WOB, torque on bit, rate
// of penetration and off-bottom share, the steady values and the integrator's counts. result.channels and
// plot_panels: the shared channels, moved out of samples, with `hookload` after wob_N when it is not empty.
void SummarizeDrillingRun(DrillingSamples& samples, std::vector<double> hookload,
                          const std::vector<StuckInterval>& stuck, const RunSettings& settings,
                          const SteadyDrillingValues& steady, const integration::IntegrationStats& stats,
                          RunResult& result);

}  // namespace drillwave::cases
