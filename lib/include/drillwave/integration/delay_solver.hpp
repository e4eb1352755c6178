#pragma once
// Generic solver for delay differential equations, retarded and neutral, with constant or state-dependent delays:
//   x'(t) = f(t, x(t), x(t - tau_i(t, x)), x'(t - tau_j(t, x))),   x(t) = phi(t) for t <= t0,
// plus a discrete mode switched by events (for right-hand sides with switches such as [u(t/2) < 0]).
// f reads the past through a PastView. A look-up inside the step being taken (a delay shorter than the step, or
// vanishing) is served from that step's own previous trial, and the step is redone until its trials agree.
#include <functional>
#include <limits>
#include <vector>

#include "drillwave/integration/hermite_history.hpp"
#include "drillwave/integration/options.hpp"

namespace drillwave::integration {

class StepTrial;    // the current step's latest trial solution (delay_solver.cpp)
struct LookupLog;   // how far look-ups reached (delay_solver.cpp)

// Read access to the solution before the current time, with the side rule of a step: a look-up at the start of
// the step takes right limits, any later one left limits, so breakpoints on the step boundary are seen correctly.
class PastView {
 public:
  PastView(const HermiteHistory& history, double step_start, const StepTrial* trial = nullptr,
           LookupLog* log = nullptr)
      : history_(history), step_start_(step_start), trial_(trial), log_(log) {}
  double Value(double s, int i, double t) const;
  double Derivative(double s, int i, double t) const;

 private:
  Side SideAt(double t) const { return t <= step_start_ ? Side::kRight : Side::kLeft; }
  bool InStep(double s, double t) const;  // records the look-up; true if s is after the step start
  const HermiteHistory& history_;
  double step_start_;
  const StepTrial* trial_;
  LookupLog* log_;
};

// A time before t0 where the history phi or its derivative of the given order jumps (0: phi itself).
struct HistoryBreakpoint {
  double time;
  int order;
};

struct DelayProblem {
  using State = std::vector<double>;
  using Mode = std::vector<int>;

  int dimension = 1;
  double t0 = 0;
  // phi and phi' for t <= t0 (phi' is read only by neutral terms).
  std::function<void(double t, double* value, double* derivative)> history;
  std::vector<HistoryBreakpoint> history_breakpoints;
  std::function<void(double t, const State& x, const PastView& past, const Mode& mode, State& dxdt)> rhs;
  // Constant delays: breakpoints propagate from t0, from the history's breakpoints and from every event by these.
  // By default the step is capped at the smallest.
  std::vector<double> constant_delays;
  // State-dependent delays, optional: the deviating arguments alpha_k(t, x) = t - tau_k(t, x) that rhs looks up.
  // With them the solver locates where an argument crosses a past breakpoint (the solution is not smooth there)
  // and steps onto it; without them the step-size control has to resolve those kinks.
  int num_deviating_arguments = 0;
  std::function<void(double t, const State& x, double* arguments)> deviating_arguments;
  // Neutral terms carry a jump in a derivative on at the same order instead of smoothing it one order per delay;
  // the solver then measures each jump where it arrives and drops it once it is below the tolerance.
  bool neutral = false;
  Mode initial_mode;
  // Events: witness k fires when it goes from > 0 to <= 0; on_event then updates mode and, if needed, the state.
  std::vector<std::function<double(double t, const State& x, const PastView& past, const Mode& mode)>> witnesses;
  std::function<void(int witness, double t, State& x, Mode& mode)> on_event;
};

struct DelaySolution {
  HermiteHistory trajectory;  // the whole solution, prehistory included, as a dense quartic interpolant
  std::vector<double> event_times;
  std::vector<double> breakpoints;  // where the solver stepped onto a propagated or located breakpoint
  IntegrationStats stats;
  double Value(double t, int i) const { return trajectory.Value(t, i); }
};

// Throws std::invalid_argument for an ill-posed problem or options (tolerances must be positive), NumericalError if
// the integration fails, saying why: blow-up, a NaN from rhs, a delayed argument that runs past the present (the
// solution ceases to exist there), a step whose own delayed values do not settle, or an exhausted budget.
DelaySolution SolveDelayProblem(const DelayProblem& problem, double t_end, const IntegratorOptions& options);

}  // namespace drillwave::integration
