#include "drillwave/integration/delay_solver.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "drillwave/integration/breakpoints.hpp"

namespace drillwave::integration {
namespace {

// Derivative jumps of order above this are below what a fifth-order method notices.
constexpr int kHighestTrackedOrder = 6;

class DelayProcess {
 public:
  using State = std::vector<double>;

  DelayProcess(const DelayProblem& problem, double t_end)
      : problem_(problem),
        t_end_(t_end),
        history_(problem.dimension, problem.history),
        mode_(problem.initial_mode) {
    AddEchoes(problem.t0, 1);  // phi'(t0-) generally differs from x'(t0+)
  }

  int Dimension() const { return problem_.dimension; }
  double MaxStep() const {
    double smallest = std::numeric_limits<double>::infinity();
    for (double tau : problem_.constant_delays) smallest = std::min(smallest, tau);
    return smallest;
  }
  void BeginStep(double t0) { step_start_ = t0; }
  void Derivatives(const State& x, State& dxdt, double t) const {
    problem_.rhs(t, x, PastView(history_, step_start_), mode_, dxdt);
  }
  double PrepareCommit(const Piece&, double, double) { return 0; }  // the state is the history: checked already
  void Commit(const Piece& p) {
    history_.Append(p.t0, p.x0.data(), p.f0.data(), p.t1, p.x1.data(), p.f1.data(), p.x_mid.data());
  }
  int NumWitnesses() const { return static_cast<int>(problem_.witnesses.size()); }
  double Witness(int i, double t, const State& x) const {
    return problem_.witnesses[i](t, x, PastView(history_, step_start_), mode_);
  }
  bool OnEvent(int i, double t, State& x) {
    if (!problem_.on_event) return false;
    problem_.on_event(i, t, x, mode_);
    event_times_.push_back(t);
    AddEchoes(t, 1);
    return true;
  }
  double NextBreakpoint() const { return breakpoints_.NextTime(); }
  // Echo each instant once, at the lowest order popped there: coincident breakpoints (sums of several delays)
  // would otherwise multiply without bound in neutral problems, whose orders never rise.
  void OnBreakpoint(double t) {
    const std::vector<Breakpoint> due = breakpoints_.PopAt(t, 1e-12 * std::max(1.0, std::abs(t)));
    if (due.empty()) return;
    int order = due.front().order;
    for (const Breakpoint& b : due) order = std::min(order, b.order);
    AddEchoes(t, problem_.neutral ? order : order + 1);
  }

  // Seeds the first step's look-ups past t0 with x0 + (t - t0) x'(t0+), x'(t0+) from the right-hand side.
  void SetStart(double t0, const State& x0, State& f0) {
    step_start_ = t0;
    Derivatives(x0, f0, t0);
    history_.SetStart(t0, x0.data(), f0.data());
  }

  HermiteHistory TakeHistory() { return std::move(history_); }
  std::vector<double> TakeEventTimes() { return std::move(event_times_); }

 private:
  void AddEchoes(double t, int order) {
    if (order > kHighestTrackedOrder) return;
    for (double tau : problem_.constant_delays) {
      if (t + tau < t_end_) breakpoints_.Push({t + tau, 0, 1.0, order});
    }
  }

  const DelayProblem& problem_;
  double t_end_;
  HermiteHistory history_;
  DelayProblem::Mode mode_;
  double step_start_ = 0;
  BreakpointQueue breakpoints_;
  std::vector<double> event_times_;
};

}  // namespace

DelaySolution SolveDelayProblem(const DelayProblem& problem, double t_end, const IntegratorOptions& options) {
  if (problem.dimension <= 0) throw std::invalid_argument("DelayProblem: dimension must be positive");
  if (!problem.history || !problem.rhs) throw std::invalid_argument("DelayProblem: history and rhs are required");
  if (problem.witnesses.size() && !problem.on_event)
    throw std::invalid_argument("DelayProblem: witnesses need an on_event handler");
  for (double tau : problem.constant_delays)
    if (!(tau > 0)) throw std::invalid_argument("DelayProblem: constant delays must be positive");

  DelayProcess process(problem, t_end);
  std::vector<double> x0(problem.dimension), d0(problem.dimension), f0(problem.dimension);
  problem.history(problem.t0, x0.data(), d0.data());
  process.SetStart(problem.t0, x0, f0);
  Simulator<DelayProcess> simulator(process, options);
  simulator.Integrate(problem.t0, x0, t_end);
  return DelaySolution{process.TakeHistory(), process.TakeEventTimes(), simulator.stats()};
}

}  // namespace drillwave::integration
