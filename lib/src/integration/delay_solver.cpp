#include "drillwave/integration/delay_solver.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "drillwave/core/validity.hpp"
#include "drillwave/integration/breakpoints.hpp"
#include "drillwave/integration/simulator.hpp"

namespace drillwave::integration {
namespace {

// Times computed as (t + tau) - tau miss a stored boundary by a few ulps; closer than this they are on it.
double Snap(double t) { return 1e-12 * std::max(1.0, std::abs(t)); }

// A jump in derivative k changes a fifth-order step's local error (the h^6 term) only up to k = 6; beyond, a
// retarded echo is smooth enough for the step-size control alone.
constexpr int kHighestRetardedOrder = 6;
// Neutral echoes keep their order, so they are measured instead: the jump in derivative k, as the quartic pieces on
// both sides give it. Up to the third derivative that measurement is well above the pieces' own error.
constexpr int kHighestMeasuredOrder = 3;

}  // namespace

// How far the look-ups of the current step attempt reached.
struct LookupLog {
  bool ahead = false;  // some look-up was after the step start
  // Largest s - t (a look-up after its own time) in the latest call of rhs or a witness. Stages of trial steps
  // wander; the latest call before a commit is at the accepted end state, where only an argument that really
  // runs past the present shows more than tolerance-sized advances.
  double advance = -std::numeric_limits<double>::infinity();
};

// The quartic of one piece (a trial of the current step, or the last committed piece) in powers of s = (t - t0)/h.
class StepTrial {
 public:
  void Set(const Piece& p) {
    t0_ = p.t0;
    h_ = p.t1 - p.t0;
    const std::size_t n = p.x0.size();
    c_.resize(5 * n);
    for (std::size_t i = 0; i < n; ++i) {
      const double x0 = p.x0[i], x1 = p.x1[i], d0 = h_ * p.f0[i], d1 = h_ * p.f1[i];
      const double b = 16.0 * (p.x_mid[i] - 0.5 * (x0 + x1) - 0.125 * (d0 - d1));  // see HermiteHistory::Append
      double* c = &c_[5 * i];
      c[0] = x0;
      c[1] = d0;
      c[2] = -3 * x0 - 2 * d0 + 3 * x1 - d1 + b;
      c[3] = 2 * x0 + d0 - 2 * x1 + d1 - 2 * b;
      c[4] = b;
    }
  }
  double t0() const { return t0_; }
  double t1() const { return t0_ + h_; }
  double h() const { return h_; }
  // Derivative of order k (0: the value) of component i at time t; beyond the piece it extrapolates.
  double At(double t, int i, int k = 0) const {
    const double s = (t - t0_) / h_;
    const double* c = &c_[5 * static_cast<std::size_t>(i)];
    static constexpr double kFalling[5][5] = {
        {1, 1, 1, 1, 1}, {0, 1, 2, 3, 4}, {0, 0, 2, 6, 12}, {0, 0, 0, 6, 24}, {0, 0, 0, 0, 24}};
    double v = 0;
    for (int j = 4; j >= k; --j) v = v * s + kFalling[k][j] * c[j];
    return v / std::pow(h_, k);
  }

 private:
  double t0_ = 0, h_ = 1;
  std::vector<double> c_;
};

bool PastView::InStep(double s, double t) const {
  if (!log_) return false;
  log_->advance = std::max(log_->advance, s - t);
  if (!(s > step_start_ + Snap(step_start_))) return false;
  log_->ahead = true;
  return trial_ != nullptr;
}

// Before the first trial of a step, a look-up inside it gets a predictor: the last piece extrapolated, or in the
// first step (nothing stored yet) phi(t0), not phi past the end of its domain.
double PastView::Value(double s, int i, double t) const {
  if (InStep(s, t)) return trial_->At(s, i);
  return history_.Value(history_.empty() ? std::min(s, step_start_) : s, i, SideAt(t));
}

double PastView::Derivative(double s, int i, double t) const {
  if (InStep(s, t)) return trial_->At(s, i, 1);
  return history_.Derivative(history_.empty() ? std::min(s, step_start_) : s, i, SideAt(t));
}

namespace {

class DelayProcess {
 public:
  using State = std::vector<double>;

  DelayProcess(const DelayProblem& problem, double t_end, const IntegratorOptions& options)
      : problem_(problem),
        t_end_(t_end),
        options_(options),
        history_(problem.dimension, problem.history),
        mode_(problem.initial_mode),
        arguments_(2 * static_cast<std::size_t>(problem.num_deviating_arguments)),
        last_crossed_(static_cast<std::size_t>(problem.num_deviating_arguments),
                      std::numeric_limits<double>::quiet_NaN()) {
    for (const HistoryBreakpoint& b : problem.history_breakpoints) {
      past_.push_back({b.time, b.order});
      AddEchoes(b.time, b.order);
    }
    std::sort(past_.begin(), past_.end(), [](const Past& a, const Past& b) { return a.time < b.time; });
    past_.push_back({problem.t0, 1});  // phi'(t0-) generally differs from x'(t0+)
    AddEchoes(problem.t0, 1);
  }

  int Dimension() const { return problem_.dimension; }
  double MaxStep() const {
    double smallest = std::numeric_limits<double>::infinity();
    for (double tau : problem_.constant_delays) smallest = std::min(smallest, tau);
    return smallest;
  }
  void BeginStep(double t0) {
    step_start_ = t0;
    has_trial_ = false;
    log_ = LookupLog{};
  }
  void Derivatives(const State& x, State& dxdt, double t) const {
    log_.advance = -std::numeric_limits<double>::infinity();
    problem_.rhs(t, x, View(), mode_, dxdt);
  }
  bool ReadsAhead() const { return log_.ahead; }
  void SetTrial(const Piece& trial) {
    trial_.Set(trial);
    has_trial_ = true;
    log_ = LookupLog{};
  }
  bool CutAt(const Piece& p);
  double PrepareCommit(const Piece&, double, double) { return 0; }  // the state is the history: checked already
  void Commit(const Piece& p);
  int NumWitnesses() const { return static_cast<int>(problem_.witnesses.size()); }
  double Witness(int i, double t, const State& x) const {
    log_.advance = -std::numeric_limits<double>::infinity();
    return problem_.witnesses[i](t, x, View(), mode_);
  }
  bool OnEvent(int i, double t, State& x) {
    if (!problem_.on_event) return false;
    problem_.on_event(i, t, x, mode_);
    event_times_.push_back(t);
    Arrive(t, 1);  // the mode changes x'
    return true;
  }
  double NextBreakpoint() const { return queue_.NextTime(); }
  // Everything due now is merged into one breakpoint at the lowest order that arrived: coincident echoes (sums of
  // several delays) are passed on once.
  void OnBreakpoint(double t) {
    const std::vector<Breakpoint> due = queue_.PopAt(t, Snap(t));
    if (due.empty()) return;
    int order = due.front().order;
    for (const Breakpoint& b : due) order = std::min(order, b.order);
    stepped_onto_.push_back(t);
    Arrive(t, order);
  }

  HermiteHistory TakeHistory() { return std::move(history_); }
  std::vector<double> TakeEventTimes() { return std::move(event_times_); }
  std::vector<double> TakeBreakpoints() { return std::move(stepped_onto_); }

 private:
  struct Past {
    double time;
    int order;  // the derivative that jumps there
  };

  PastView View() const { return PastView(history_, step_start_, has_trial_ ? &trial_ : nullptr, &log_); }

  // A breakpoint of the given order at t (now). Retarded echoes are one order smoother and known at once; a
  // neutral one is measured when the step after it is committed (pending_).
  void Arrive(double t, int order) {
    if (problem_.neutral) {
      if (has_pending_ && pending_.time == t) order = std::min(order, pending_.order);
      pending_ = {t, order};
      has_pending_ = true;
      return;
    }
    Keep(t, order);
    AddEchoes(t, order + 1);
  }
  void Keep(double t, int order) {
    if (past_.empty() || t > past_.back().time) past_.push_back({t, order});
    else past_.back().order = std::min(past_.back().order, order);
  }
  void AddEchoes(double t, int order) {
    if (order > (problem_.neutral ? kHighestMeasuredOrder : kHighestRetardedOrder)) return;
    for (double tau : problem_.constant_delays)
      if (t + tau < t_end_ && t + tau > problem_.t0) queue_.Push({t + tau, 0, 1.0, order});
  }
  // The lowest order k whose jump at the left piece's end matters to a step across it (|jump| h^k / k! above the
  // tolerance, h the longer of the two pieces); 0 if none up to kHighestMeasuredOrder does.
  int MeasuredOrder(const StepTrial& left, const StepTrial& right) const {
    const double t = right.t0(), h = std::max(left.h(), right.h());
    double factorial = 1, hk = 1;
    for (int k = 1; k <= kHighestMeasuredOrder; ++k) {
      factorial *= k;
      hk *= h;
      for (int i = 0; i < problem_.dimension; ++i) {
        const double scale = options_.abs_tol + options_.rel_tol * std::abs(right.At(t, i));
        if (std::abs(left.At(t, i, k) - right.At(t, i, k)) * hk / factorial > scale) return k;
      }
    }
    return 0;
  }
  // A look-up after its own time that tolerance-sized errors in a state-dependent argument cannot explain.
  void CheckAdvance(const Piece& p) {
    if (!(log_.advance > Snap(p.t1))) {
      advance_since_ = std::numeric_limits<double>::quiet_NaN();
      return;
    }
    if (std::isnan(advance_since_)) advance_since_ = p.t0;
    const double limit = 100 * std::max(options_.abs_tol, options_.rel_tol) * std::max(1.0, std::abs(p.t1));
    if (log_.advance > limit)
      throw NumericalError("the solution ceases to exist near t = " + std::to_string(advance_since_) +
                               ": a delayed argument runs past the present (by " + std::to_string(log_.advance) +
                               " at t = " + std::to_string(p.t1) + "), so the equation would need the future",
                           advance_since_, p.x0);
  }

  const DelayProblem& problem_;
  double t_end_;
  IntegratorOptions options_;
  HermiteHistory history_;
  DelayProblem::Mode mode_;
  double step_start_ = 0;
  StepTrial trial_;
  bool has_trial_ = false;
  mutable LookupLog log_;
  StepTrial last_;  // the last committed piece
  bool has_last_ = false;
  BreakpointQueue queue_;
  std::vector<Past> past_;  // by time: the history's breakpoints, t0 and every one arrived at since
  Past pending_{0, 0};
  bool has_pending_ = false;
  std::vector<double> arguments_;  // deviating arguments at a piece's start, then at its end
  // The past breakpoint each argument crossed last. The step redone up to a located crossing can end a hair
  // before it (its solution differs from the trial's within the tolerance); the same crossing is not located again.
  std::vector<double> last_crossed_;
  double advance_since_ = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> event_times_, stepped_onto_;
};

void DelayProcess::Commit(const Piece& p) {
  CheckAdvance(p);
  history_.Append(p.t0, p.x0.data(), p.f0.data(), p.t1, p.x1.data(), p.f1.data(), p.x_mid.data());
  StepTrial piece;
  piece.Set(p);
  if (has_pending_ && std::abs(p.t0 - pending_.time) <= Snap(p.t0)) {
    has_pending_ = false;
    const int order = has_last_ ? MeasuredOrder(last_, piece) : pending_.order;
    if (order > 0) {
      Keep(pending_.time, order);
      AddEchoes(pending_.time, order);
    }
  }
  last_ = std::move(piece);
  has_last_ = true;
  has_trial_ = false;
}

// Where a deviating argument alpha(t, x(t)) crosses a past breakpoint b, the solution has a breakpoint one order
// smoother (retarded) or of the same order (neutral). Finds the earliest such crossing inside the piece.
bool DelayProcess::CutAt(const Piece& p) {
  const int m = problem_.num_deviating_arguments;
  if (m == 0 || past_.empty()) return false;
  double* a0 = arguments_.data();
  double* a1 = a0 + m;
  problem_.deviating_arguments(p.t0, p.x0, a0);
  problem_.deviating_arguments(p.t1, p.x1, a1);
  StepTrial piece;
  bool have_piece = false;
  State x(problem_.dimension), a(m);
  double first = std::numeric_limits<double>::infinity(), first_crossed = 0;
  int first_order = 0, first_argument = 0;
  for (int k = 0; k < m; ++k) {
    // The past breakpoint nearest to alpha(t0) in the direction alpha moves, if alpha passes it within the piece.
    const bool rising = a1[k] > a0[k];
    const auto by_time = [](const Past& q, double v) { return q.time < v; };
    const Past* b = nullptr;
    if (rising) {
      auto it = std::lower_bound(past_.begin(), past_.end(), a0[k] + Snap(a0[k]), by_time);
      if (it != past_.end() && it->time < a1[k]) b = &*it;
    } else {
      auto it = std::lower_bound(past_.begin(), past_.end(), a0[k] - Snap(a0[k]), by_time);
      if (it != past_.begin() && (it - 1)->time > a1[k]) b = &*(it - 1);
    }
    if (!b || b->time == last_crossed_[k]) continue;
    if (!have_piece) {
      piece.Set(p);
      have_piece = true;
    }
    // Illinois (regula falsi) on g(t) = alpha_k(t, x(t)) - b with x from the piece's quartic.
    auto g = [&](double t) {
      for (int i = 0; i < problem_.dimension; ++i) x[i] = piece.At(t, i);
      problem_.deviating_arguments(t, x, a.data());
      return a[k] - b->time;
    };
    double lo = p.t0, hi = p.t1, g_lo = a0[k] - b->time, g_hi = a1[k] - b->time;
    int side = 0;
    for (int iter = 0; iter < 100 && hi - lo > Snap(hi) * 1e-2; ++iter) {
      const double tm = std::clamp((lo * g_hi - hi * g_lo) / (g_hi - g_lo), lo, hi);
      const double gm = g(tm);
      if ((gm > 0) == (g_hi > 0)) {
        hi = tm;
        g_hi = gm;
        if (side == -1) g_lo *= 0.5;
        side = -1;
      } else {
        lo = tm;
        g_lo = gm;
        if (side == 1) g_hi *= 0.5;
        side = 1;
      }
      if (gm == 0) break;
    }
    const int order = problem_.neutral ? b->order : b->order + 1;
    if (hi < first && order <= kHighestRetardedOrder) {
      first = hi;  // the argument has passed b there
      first_order = order;
      first_argument = k;
      first_crossed = b->time;
    }
  }
  if (!std::isfinite(first) || first - p.t0 <= Snap(p.t0)) return false;
  last_crossed_[first_argument] = first_crossed;
  const bool at_end = p.t1 - first <= Snap(p.t1);
  queue_.Push({at_end ? p.t1 : first, 0, 1.0, first_order});
  return !at_end;
}

}  // namespace

DelaySolution SolveDelayProblem(const DelayProblem& problem, double t_end, const IntegratorOptions& options) {
  if (problem.dimension <= 0) throw std::invalid_argument("DelayProblem: dimension must be positive");
  if (!problem.history || !problem.rhs) throw std::invalid_argument("DelayProblem: history and rhs are required");
  if (problem.witnesses.size() && !problem.on_event)
    throw std::invalid_argument("DelayProblem: witnesses need an on_event handler");
  for (double tau : problem.constant_delays)
    if (!(tau > 0)) throw std::invalid_argument("DelayProblem: constant delays must be positive");
  if (problem.num_deviating_arguments < 0 || (problem.num_deviating_arguments > 0) != bool(problem.deviating_arguments))
    throw std::invalid_argument("DelayProblem: num_deviating_arguments > 0 goes with a deviating_arguments function");
  for (const HistoryBreakpoint& b : problem.history_breakpoints)
    if (!(b.time < problem.t0) || b.order < 0)
      throw std::invalid_argument("DelayProblem: history breakpoints lie before t0 and have an order >= 0");
  ThrowIfInvalid(options);
  if (!(t_end > problem.t0)) throw std::invalid_argument("SolveDelayProblem: t_end must be after t0");

  DelayProcess process(problem, t_end, options);
  std::vector<double> x0(problem.dimension), d0(problem.dimension);
  problem.history(problem.t0, x0.data(), d0.data());
  Simulator<DelayProcess> simulator(process, options);
  simulator.Integrate(problem.t0, x0, t_end);
  return DelaySolution{process.TakeHistory(), process.TakeEventTimes(), process.TakeBreakpoints(),
                       simulator.stats()};
}

}  // namespace drillwave::integration
