#pragma once
// What the integration loop (simulator.hpp) takes and gives, without Boost.Odeint: its options, the accepted pieces
// it hands to processes and observers, and its work counters. Headers that only pass these around include this one.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "drillwave/integration/quartic.hpp"

namespace drillwave::integration {

struct IntegratorOptions {
  double abs_tol = 1e-8;
  double rel_tol = 1e-8;
  double initial_step = 1e-4;
  double max_step = std::numeric_limits<double>::infinity();  // further capped by Process::MaxStep()
  double event_time_tol = 1e-12;                              // width of the bracket that locates an event
  int max_events_at_one_instant = 16;                         // guards against chattering mode changes
  // Delayed values come from the stored interpolant, whose error the stepper's own control never sees (it is
  // exact for the stages, not between steps). When on, a step is redone shorter if its cubic Hermite interpolant
  // misses the continuous extension's midpoint by more than the tolerance.
  bool control_history_error = true;
  // A piece whose history error stays above tolerance is accepted once its step is below this floor (and always
  // below 1e-9 t): a jump or kink nobody announced as a breakpoint cannot be resolved by shrinking the step, and a
  // model whose waves carry many unannounced kinks can trade that error for speed here.
  double history_step_floor = 0;
  // Work budgets, 0 for none: a run that needs more accepted steps or right-hand-side evaluations stops with a
  // NumericalError that says which budget ran out, instead of creeping on.
  long max_steps = 0;
  long max_evaluations = 0;
  // The most steps a run may need at the longest step the process allows (its shortest delay): refused before the
  // first step, with InputError("/model", ...), rather than integrated for hours (a string of G = 1e300 Pa).
  double max_planned_steps = std::numeric_limits<double>::infinity();

  // Tolerances, initial_step and event_time_tol finite and > 0; max_step and max_planned_steps > 0 (infinite: no
  // limit); max_events_at_one_instant >= 1; history_step_floor finite and >= 0; the budgets >= 0 (core/validity.hpp).
  bool IsValid(std::string* error) const;
};

// One accepted piece of the solution: values and derivatives at both ends (one-sided limits) and the value at the
// midpoint from the stepper's continuous extension, which together fix a quartic interpolant.
struct Piece {
  double t0, t1;
  const std::vector<double>& x0;
  const std::vector<double>& f0;
  const std::vector<double>& x1;
  const std::vector<double>& f1;
  const std::vector<double>& x_mid;
};

// The piece's quartic at time t in [t0, t1]: the interpolant the history stores, for sampling outputs.
inline void InterpolatePiece(const Piece& p, double t, std::vector<double>& x) {
  const double h = p.t1 - p.t0, s = (t - p.t0) / h;
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = QuarticValue(s, h, p.x0[i], p.x1[i], p.f0[i], p.f1[i],
                        BubbleWeight(h, p.x0[i], p.x1[i], p.f0[i], p.f1[i], p.x_mid[i]));
}

struct IntegrationStats {
  long steps = 0;                // accepted pieces
  long derivative_evaluations = 0;
  long events = 0;               // mode changes applied
  long breakpoints = 0;          // breakpoints stepped onto
  long history_rejections = 0;   // steps redone because their interpolant was not accurate enough
  long trial_redos = 0;          // steps redone reading their own previous trial (delays inside the step)
  double wall_time_s = 0;
};

}  // namespace drillwave::integration
