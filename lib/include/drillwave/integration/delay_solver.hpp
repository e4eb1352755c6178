#pragma once
// Generic solver for delay differential equations, retarded and neutral, with constant or state-dependent delays:
//   x'(t) = f(t, x(t), x(t - tau_i(t, x)), x'(t - tau_j(t, x))),   x(t) = phi(t) for t <= t0,
// plus a discrete mode switched by events (for right-hand sides with switches such as [u(t/2) < 0]).
// f reads the past through a PastView; delayed times past the committed history (vanishing delays) are served by
// extrapolating the last step, which the step-size control keeps accurate.
#include <functional>
#include <limits>
#include <vector>

#include "drillwave/integration/hermite_history.hpp"
#include "drillwave/integration/simulator.hpp"

namespace drillwave::integration {

// Read access to the solution before the current time, with the side rule of a step: a look-up at the start of
// the step takes right limits, any later one left limits, so breakpoints on the step boundary are seen correctly.
class PastView {
 public:
  PastView(const HermiteHistory& history, double step_start) : history_(history), step_start_(step_start) {}
  double Value(double s, int i, double t) const { return history_.Value(s, i, SideAt(t)); }
  double Derivative(double s, int i, double t) const { return history_.Derivative(s, i, SideAt(t)); }

 private:
  Side SideAt(double t) const { return t <= step_start_ ? Side::kRight : Side::kLeft; }
  const HermiteHistory& history_;
  double step_start_;
};

struct DelayProblem {
  using State = std::vector<double>;
  using Mode = std::vector<int>;

  int dimension = 1;
  double t0 = 0;
  // phi and phi' for t <= t0 (phi' is read only by neutral terms).
  std::function<void(double t, double* value, double* derivative)> history;
  std::function<void(double t, const State& x, const PastView& past, const Mode& mode, State& dxdt)> rhs;
  // Constant delays: breakpoints propagate from t0 and from every event by these (state-dependent ones are not
  // tracked; the step-size control resolves their kinks). By default the step is capped at the smallest.
  std::vector<double> constant_delays;
  bool neutral = false;   // neutral terms carry jumps forever instead of smoothing them one order per delay
  Mode initial_mode;
  // Events: witness k fires when it goes from > 0 to <= 0; on_event then updates mode and, if needed, the state.
  std::vector<std::function<double(double t, const State& x, const PastView& past, const Mode& mode)>> witnesses;
  std::function<void(int witness, double t, State& x, Mode& mode)> on_event;
};

struct DelaySolution {
  HermiteHistory trajectory;  // the whole solution, prehistory included, as a dense cubic Hermite interpolant
  std::vector<double> event_times;
  IntegrationStats stats;
  double Value(double t, int i) const { return trajectory.Value(t, i); }
};

DelaySolution SolveDelayProblem(const DelayProblem& problem, double t_end, const IntegratorOptions& options);

}  // namespace drillwave::integration
