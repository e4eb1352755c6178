#pragma once
// The one integration loop of drillwave: a Boost.Odeint dense-output Dormand–Prince stepper driven through
// delays, breakpoints and events. Everything model-specific lives in the Process (Drake's Context): it owns the
// committed history and the discrete mode, and its Derivatives() is pure given those.
//
// A Process provides
//   int Dimension() const;
//   void Derivatives(const std::vector<double>& x, std::vector<double>& dxdt, double t) const;
//   double MaxStep() const;            // smallest delay, so that delayed values come from committed history
//   void BeginStep(double t0);         // delayed look-ups at t0 take right limits, later ones left limits
//   double PrepareCommit(const Piece& piece, double abs_tol, double rel_tol);
//                                      // computes what the piece adds to the stored history and returns the scaled
//                                      // interpolation error of those stored signals (> 1: the step is redone)
//   void Commit(const Piece& piece);   // appends the prepared piece; the only place history grows
//   int NumWitnesses() const;
//   double Witness(int i, double t, const std::vector<double>& x) const;  // event when it goes from > 0 to <= 0
//                                      // (or from exactly 0 to < 0)
//   bool OnEvent(int i, double t, std::vector<double>& x);  // apply the event; true if mode or state changed
//   double NextBreakpoint() const;     // +inf if none
//   void OnBreakpoint(double t);       // the loop has stepped exactly onto NextBreakpoint(); or instead
//   void OnBreakpoint(double t, std::vector<double>& x);  // ... and may set the state there (a controller's handover)
// and optionally (detected at compile time; a process without them is integrated exactly as before)
//   bool ReadsAhead() const;           // a look-up since BeginStep/SetTrial asked for a time after the step start
//   void SetTrial(const Piece& trial); // serve such look-ups from this trial of the current step
//   bool CutAt(const Piece& piece);    // true if the process found (and queued) a breakpoint inside the piece: the
//                                      // step is redone up to it
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "drillwave/core/cancellation.hpp"

#include <boost/numeric/odeint.hpp>

#include "drillwave/core/error.hpp"
#include "drillwave/integration/options.hpp"

namespace drillwave::integration {

using PieceObserver = std::function<void(const Piece&)>;

// The history members of a Process without delayed arguments (an ODE with events), for it to inherit: no step limit,
// nothing stored, so nothing to check.
struct WithoutHistory {
  double MaxStep() const { return std::numeric_limits<double>::infinity(); }
  double PrepareCommit(const Piece&, double, double) { return 0; }
  void Commit(const Piece&) {}
};

namespace detail {
template <class P, class = void>
struct ReadsItsOwnStep : std::false_type {};
template <class P>
struct ReadsItsOwnStep<P, std::void_t<decltype(std::declval<const P&>().ReadsAhead()),
                                      decltype(std::declval<P&>().SetTrial(std::declval<const Piece&>()))>>
    : std::true_type {};
template <class P, class = void>
struct SetsStateAtBreakpoints : std::false_type {};
template <class P>
struct SetsStateAtBreakpoints<P, std::void_t<decltype(std::declval<P&>().OnBreakpoint(
                                     0.0, std::declval<std::vector<double>&>()))>> : std::true_type {};
template <class P, class = void>
struct CutsSteps : std::false_type {};
template <class P>
struct CutsSteps<P, std::void_t<decltype(std::declval<P&>().CutAt(std::declval<const Piece&>()))>> : std::true_type {};

// Anderson acceleration (Walker & Ni 2011) of a fixed-point iteration z = G(z): the next trial is the combination
// of the last few images whose residuals G(z) - z cancel best (least squares, in the caller's scaled units). A
// neutral term with coefficient c contracts the plain iteration only by c per trial; on such a nearly linear map
// the mixing converges in a few trials.
class AndersonMixer {
 public:
  void Reset() { size_ = 0; }
  // Records the trial z and its image g (both scaled) and overwrites z with the next trial.
  void Next(std::vector<double>& z, const std::vector<double>& g) {
    const std::size_t n = z.size();
    if (size_ == kMemory + 1) {  // forget the oldest pair
      std::rotate(std::begin(z_), std::begin(z_) + 1, std::end(z_));
      std::rotate(std::begin(g_), std::begin(g_) + 1, std::end(g_));
      --size_;
    }
    z_[size_] = z;
    g_[size_] = g;
    ++size_;
    const int k = static_cast<int>(size_) - 1;  // differences available
    z = g;
    if (k == 0) return;
    // Normal equations of min |r_k - sum_j gamma_j (r_j+1 - r_j)|, r = g - z (k <= 3: tiny and well scaled).
    double a[kMemory][kMemory + 1] = {};
    auto dr = [&](int j, std::size_t i) { return (g_[j + 1][i] - z_[j + 1][i]) - (g_[j][i] - z_[j][i]); };
    for (int p = 0; p < k; ++p) {
      for (int q = 0; q < k; ++q)
        for (std::size_t i = 0; i < n; ++i) a[p][q] += dr(p, i) * dr(q, i);
      for (std::size_t i = 0; i < n; ++i) a[p][k] += dr(p, i) * (g_[k][i] - z_[k][i]);
      a[p][p] *= 1 + 1e-10;  // keeps nearly dependent differences solvable
    }
    double gamma[kMemory];
    for (int p = 0; p < k; ++p) {  // Gaussian elimination with partial pivoting
      int best = p;
      for (int q = p + 1; q < k; ++q)
        if (std::abs(a[q][p]) > std::abs(a[best][p])) best = q;
      std::swap(a[p], a[best]);
      if (a[p][p] == 0) return;  // degenerate: keep the plain step
      for (int q = p + 1; q < k; ++q) {
        const double f = a[q][p] / a[p][p];
        for (int c = p; c <= k; ++c) a[q][c] -= f * a[p][c];
      }
    }
    for (int p = k - 1; p >= 0; --p) {
      double v = a[p][k];
      for (int c = p + 1; c < k; ++c) v -= a[p][c] * gamma[c];
      gamma[p] = v / a[p][p];
    }
    for (std::size_t i = 0; i < n; ++i)
      for (int j = 0; j < k; ++j) z[i] -= gamma[j] * (g_[j + 1][i] - g_[j][i]);
  }

 private:
  static constexpr int kMemory = 3;
  std::vector<double> z_[kMemory + 1], g_[kMemory + 1];
  std::size_t size_ = 0;
};
}  // namespace detail

// An observer that samples the solution at k * interval, k = 1, 2, ... (the caller samples t0 = 0 itself), from each
// accepted piece's quartic; with interval <= 0 it samples every piece's end instead. Sample times are counted, not
// summed, so they do not drift.
inline PieceObserver SampleEvery(double interval, std::function<void(double t, const std::vector<double>& x)> sample) {
  auto taken = std::make_shared<long>(1);
  auto x = std::make_shared<std::vector<double>>();
  return [=](const Piece& p) {
    if (interval <= 0) return sample(p.t1, p.x1);
    x->resize(p.x1.size());
    for (double next = *taken * interval; next <= p.t1 + 1e-12 * std::max(1.0, p.t1); next = ++*taken * interval) {
      InterpolatePiece(p, std::min(next, p.t1), *x);
      sample(next, *x);
    }
  };
}

template <class Process>
class Simulator {
 public:
  using State = std::vector<double>;

  Simulator(Process& process, IntegratorOptions options) : process_(process), options_(options) {}

  // Integrates from (t0, x0) to t_end; returns the final state. Throws NumericalError on failure.
  State Integrate(double t0, State x0, double t_end, const PieceObserver& observer = nullptr);
  const IntegrationStats& stats() const { return stats_; }

 private:
  using Stepper = boost::numeric::odeint::runge_kutta_dopri5<State>;

  // Bisection for the first root of witness i in (ta, tb] on the stepper's dense output; returns a time where the
  // witness is already <= 0 so that the restarted integration does not find the same root again.
  template <class Dense>
  double LocateEvent(const Dense& dense, int i, double ta, double tb, State& x_at) const;

  // Trials of one step reading its own interpolant: at most this many, settled at this change (tolerance units).
  static constexpr int kMaxTrials = 12;
  // A state component this many times the start's largest (at least 1) is a solution escaping to infinity: far
  // beyond any physical growth (a bit angle after a day at 20 rad/s is 2e6 rad).
  static constexpr double kBlowUpGrowth = 1e12;
  static constexpr double kTrialTolerance = 0.05;

  // The process's OnBreakpoint, with the state where it takes one (the loop restarts from x after it either way).
  void PassBreakpoint(double t, State& x) {
    if constexpr (detail::SetsStateAtBreakpoints<Process>::value) process_.OnBreakpoint(t, x);
    else process_.OnBreakpoint(t);
  }

  Process& process_;
  IntegratorOptions options_;
  IntegrationStats stats_;
};

template <class Process>
template <class Dense>
double Simulator<Process>::LocateEvent(const Dense& dense, int i, double ta, double tb, State& x_at) const {
  while (tb - ta > options_.event_time_tol * std::max(1.0, std::abs(tb))) {
    const double tm = 0.5 * (ta + tb);
    dense.calc_state(tm, x_at);
    if (process_.Witness(i, tm, x_at) > 0) ta = tm; else tb = tm;
  }
  dense.calc_state(tb, x_at);
  return tb;
}

template <class Process>
typename Simulator<Process>::State Simulator<Process>::Integrate(double t0, State x, double t_end,
                                                                 const PieceObserver& observer) {
  namespace odeint = boost::numeric::odeint;
  const auto wall_start = std::chrono::steady_clock::now();
  const std::size_t n = x.size();
  const double max_step = std::min(options_.max_step, process_.MaxStep());
  if ((t_end - t0) / max_step > options_.max_planned_steps)
    throw InputError("/model", "its shortest delay limits steps to " + ReadableNumber(max_step) + " s, so " +
                                   ReadableNumber(t_end - t0) + " s need at least " +
                                   ReadableNumber((t_end - t0) / max_step) + " steps, above the limit of " +
                                   ReadableNumber(options_.max_planned_steps) +
                                   " (max_samples); check the model's lengths, moduli and densities", {"max_samples"});
  auto dense = odeint::make_dense_output(options_.abs_tol, options_.rel_tol,
                                         std::isfinite(max_step) ? max_step : 0.0, Stepper());

  // The right-hand side as odeint sees it. It keeps the first derivative after a restart (the right limit at the
  // restart point) and the last one (after do_step: the first-same-as-last stage f(t1, x1), a left limit), so the
  // history gets exact end derivatives without extra evaluations.
  bool capture_first = false;
  bool reuse_f0 = false;  // a redo of the same step: its first stage f(t, x) is f0 already
  double last_t = std::numeric_limits<double>::quiet_NaN();
  State f0(n), f1(n);
  auto system = [&](const State& xs, State& dxdt, double t) {
    last_t = t;
    if (reuse_f0) {
      reuse_f0 = capture_first = false;
      std::copy(f0.begin(), f0.end(), dxdt.begin());
      std::copy(f0.begin(), f0.end(), f1.begin());
      return;
    }
    if (options_.max_evaluations > 0 && stats_.derivative_evaluations >= options_.max_evaluations)
      throw NumericalError("evaluation budget exhausted (max_evaluations = " +
                               std::to_string(options_.max_evaluations) + " right-hand-side evaluations)",
                           t, xs);
    process_.Derivatives(xs, dxdt, t);
    ++stats_.derivative_evaluations;
    // NaN from a finite state is the model's, not the integrator's (an infinite value may still be stepped around).
    if (std::any_of(dxdt.begin(), dxdt.end(), [](double v) { return std::isnan(v); }) &&
        std::all_of(xs.begin(), xs.end(), [](double v) { return std::isfinite(v); }))
      throw NumericalError("the right-hand side returned NaN for a finite state (a model function is undefined here)",
                           t, xs);
    std::copy(dxdt.begin(), dxdt.end(), f1.begin());
    if (capture_first) {
      std::copy(dxdt.begin(), dxdt.end(), f0.begin());
      capture_first = false;
    }
  };

  auto check_finite = [](const State& xs, double t, const char* what) {
    for (double v : xs)
      if (!std::isfinite(v)) throw NumericalError(what, t, xs);
  };
  check_finite(x, t0, "non-finite initial state");

  const int num_witnesses = process_.NumWitnesses();
  std::vector<double> g0(num_witnesses), g1(num_witnesses);
  auto witnesses = [&](double t, const State& xs, std::vector<double>& g) {
    for (int i = 0; i < num_witnesses; ++i) g[i] = process_.Witness(i, t, xs);
  };

  double t = t0;
  double dt = std::min(options_.initial_step, max_step);
  bool restart = true;  // derivative and witnesses at t must be (re)computed: start, breakpoint or event
  State x1(n), x_event(n), x_try(n), f_event(n), x_mid(n), x_mid_event(n);
  State trial_x1(n), trial_f1(n), trial_mid(n), guess(3 * n), image(3 * n), weight(n);
  detail::AndersonMixer mixer;
  bool history_limited = false;  // the last piece asked for a shorter step than the stepper's suggestion
  int events_here = 0;
  double events_here_time = t0;
  // Events each less than a nanosecond (relative to t) after the one before: modes that chatter on a vanishing time
  // scale (each piece a few 1e-11 s long) would otherwise fill the histories without bound.
  constexpr double kBurstGap = 1e-9;
  int events_in_burst = 0;
  double last_event_time = -std::numeric_limits<double>::infinity(), burst_start = last_event_time;
  // Applies event i at t; many at one instant, or in one burst, mean the modes chatter (no consistent regime exists
  // there).
  auto apply_event = [&](int i, double te, State& xe) {
    if (te == events_here_time) {
      if (++events_here > options_.max_events_at_one_instant)
        throw NumericalError("too many events at one instant (chattering between modes)", te, xe);
    } else {
      events_here_time = te;
      events_here = 0;
    }
    if (te - last_event_time <= kBurstGap * std::max(1.0, std::abs(te))) {
      if (++events_in_burst > 4 * options_.max_events_at_one_instant)
        throw NumericalError(std::to_string(events_in_burst) + " events within " +
                                 ReadableNumber(te - burst_start) + " s (chattering between modes)",
                             te, xe);
    } else {
      burst_start = te;
      events_in_burst = 0;
    }
    last_event_time = te;
    if (process_.OnEvent(i, te, xe)) ++stats_.events;
  };

  // The step size underflows either at a discontinuity nobody announced or because the solution escapes to infinity
  // at a finite time (then the state has grown by many orders of magnitude): say which.
  double start_size = 1;
  for (double v : x) start_size = std::max(start_size, std::abs(v));
  auto underflow = [&](const std::string& why) {
    double size = 0;
    for (double v : x) size = std::max(size, std::abs(v));
    if (size > 1e6 * start_size)
      throw NumericalError("blow-up: the solution has grown to |x| = " + std::to_string(size) + " (from " +
                               std::to_string(start_size) + " at the start) and the step size underflows",
                           t, x);
    throw NumericalError(why, t, x);
  };
  // One attempt at the step from (t, x) as initialized: its end, state and midpoint (f0, f1 filled by system).
  auto attempt = [&]() {
    for (;;) {
      try {
        dense.do_step(system);
      } catch (const odeint::step_adjustment_error&) {
        underflow("step size underflow (the error tolerance cannot be met)");
      }
      const double t1 = dense.current_time();
      x1 = dense.current_state();
      if (!(t1 - t > 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t))))
        underflow("step size underflow (a discontinuity the integrator cannot step over?)");
      if (!std::all_of(x1.begin(), x1.end(), [](double v) { return std::isfinite(v); })) {
        // The error estimate of an overflowing step says nothing: retry a quarter as long. Only a solution that
        // escapes to infinity keeps overflowing down to a vanishing step.
        if (t1 - t > 1e-12 * std::max(1.0, std::abs(t))) {
          dense.initialize(x, t, 0.25 * (t1 - t));
          reuse_f0 = true;
          continue;
        }
        throw NumericalError("blow-up: the state becomes infinite within ever shorter steps after this point", t, x);
      }
      if (last_t != t1) throw NumericalError("internal: the last stage is not at the step end", t1, x1);
      dense.calc_state(0.5 * (t + t1), x_mid);
      return t1;
    }
  };
  while (t < t_end) {
    ThrowIfCancelled();
    if (options_.max_steps > 0 && stats_.steps >= options_.max_steps)
      throw NumericalError("step budget exhausted (max_steps = " + std::to_string(options_.max_steps) +
                               " accepted steps) before the end time " + std::to_string(t_end),
                           t, x);
    const double t_stop = std::min(process_.NextBreakpoint(), t_end);
    if (t_stop <= t + 1e-13 * std::max(1.0, std::abs(t))) {  // standing on a breakpoint
      if (t_stop >= t_end) break;
      PassBreakpoint(t_stop, x);
      ++stats_.breakpoints;
      restart = true;
      continue;
    }
    process_.BeginStep(t);
    const bool limited = t + dt >= t_stop;  // this step must land exactly on the breakpoint
    const double dt_natural = dt;
    if (restart || limited || history_limited) {
      dense.initialize(x, t, limited ? t_stop - t : dt);
      capture_first = true;
      if (restart) {
        witnesses(t, x, g0);
        // A regime can be left at the very instant of a restart (a jump arriving at a breakpoint pushes the
        // driving torque past the static limit): a witness already negative fires at once.
        const auto negative = std::find_if(g0.begin(), g0.end(), [](double g) { return g < 0; });
        if (negative != g0.end()) {
          apply_event(static_cast<int>(negative - g0.begin()), t, x);
          continue;
        }
      }
    }
    double t1 = attempt();
    if constexpr (detail::ReadsItsOwnStep<Process>::value) {
      // A look-up reached into the step itself (a delay shorter than the step, or vanishing), so it read an
      // extrapolation. Redo the step reading its previous trial until two trials agree to a small fraction of the
      // tolerance (fixed-point iteration on the step's own interpolant); one that does not settle is halved.
      int redo = 0;
      bool settled = true;
      mixer.Reset();
      while (process_.ReadsAhead()) {
        // The trial just computed, in tolerance units (fixed for the iteration): end value, midpoint, end slope
        // times h.
        const double h = t1 - t;
        for (std::size_t i = 0; i < n; ++i) {
          if (redo == 0)
            weight[i] = options_.abs_tol + options_.rel_tol * std::max(std::abs(x[i]), std::abs(x1[i]));
          image[i] = x1[i] / weight[i];
          image[n + i] = x_mid[i] / weight[i];
          image[2 * n + i] = h * f1[i] / weight[i];
        }
        if (redo > 0) {
          double change = 0;  // between this trial's input and its result
          for (std::size_t i = 0; i < 3 * n; ++i) change = std::max(change, std::abs(image[i] - guess[i]));
          if (change <= kTrialTolerance) break;
          mixer.Next(guess, image);
        } else {
          guess = image;  // the first attempt read a predictor: its result is the first trial
        }
        if (++redo > kMaxTrials) {
          settled = false;
          break;
        }
        const double trial_t1 = t1;
        for (std::size_t i = 0; i < n; ++i) {
          trial_x1[i] = guess[i] * weight[i];
          trial_mid[i] = guess[n + i] * weight[i];
          trial_f1[i] = guess[2 * n + i] * weight[i] / h;
        }
        process_.SetTrial(Piece{t, t1, x, f0, trial_x1, trial_f1, trial_mid});
        dense.initialize(x, t, h);
        reuse_f0 = true;
        t1 = attempt();
        ++stats_.trial_redos;
        if (t1 != trial_t1) {  // the error control shortened the step: start the iteration afresh on it
          redo = 0;
          mixer.Reset();
        }
      }
      if (!settled) {
        if (t1 - t <= 1e-12 * std::max(1.0, std::abs(t)))
          throw NumericalError("no solution beyond this point: the step reads its own future (a delayed argument "
                               "inside it) and its trials do not settle even for a step of " +
                                   std::to_string(t1 - t) + " (a neutral term whose coefficient reaches 1 there?)",
                               t, x);
        dt = 0.5 * (t1 - t);
        dense.initialize(x, t, dt);
        capture_first = true;
        continue;
      }
    }
    double dt_history = std::numeric_limits<double>::infinity();
    if (options_.control_history_error) {
      const double h = t1 - t;
      double worst = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const double scale = options_.abs_tol + options_.rel_tol * std::max(std::abs(x[i]), std::abs(x1[i]));
        worst = std::max(worst, std::abs(CubicMidpointMiss(h, x[i], x1[i], f0[i], f1[i], x_mid[i])) / scale);
      }
      const bool state_passed = worst <= 1.0;
      if (state_passed)  // the stored signals need checking only if the state passed
        worst = std::max(worst, process_.PrepareCommit(Piece{t, t1, x, f0, x1, f1, x_mid}, options_.abs_tol,
                                                       options_.rel_tol));
      // Cubic interpolation error scales as h^4: the step this piece could have had.
      dt_history = h * std::min(5.0, std::max(0.2, 0.9 / std::sqrt(std::sqrt(worst))));
      // Redo the step shorter; but a jump nobody announced as a breakpoint cannot be resolved by shrinking the
      // step, so below a floor the piece is accepted as it is.
      if (worst > 1.0 && h > std::max(options_.history_step_floor, 1e-9 * std::max(1.0, std::abs(t)))) {
        ++stats_.history_rejections;
        dt = dt_history;
        dense.initialize(x, t, dt);
        capture_first = true;
        continue;
      }
      // Accepted below the floor although the state failed: the process still has to prepare this piece's commit.
      if (!state_passed) process_.PrepareCommit(Piece{t, t1, x, f0, x1, f1, x_mid}, options_.abs_tol, options_.rel_tol);
    }
    if constexpr (detail::CutsSteps<Process>::value) {
      if (process_.CutAt(Piece{t, t1, x, f0, x1, f1, x_mid})) {  // the loop's next stop is now inside this step
        dt = t1 - t;
        continue;
      }
    }
    dt = limited ? std::max(dense.current_time_step(), dt_natural) : dense.current_time_step();
    const bool history_limits_step = dt_history < dt;
    dt = std::min(dt, dt_history);
    history_limited = history_limits_step;
    restart = false;

    // Events: the earliest witness that went from > 0 to <= 0 within the step, or from exactly 0 (where a
    // restart left it, e.g. a speed witness right after break-away) to < 0.
    witnesses(t1, x1, g1);
    int first = -1;
    double t_event = t1;
    for (int i = 0; i < num_witnesses; ++i) {
      if ((g0[i] > 0 && g1[i] <= 0) || (g0[i] == 0 && g1[i] < 0)) {
        const double ti = LocateEvent(dense, i, t, t1, x_try);
        if (first < 0 || ti < t_event) {
          first = i;
          t_event = ti;
          x_event = x_try;
        }
      }
    }

    if (first >= 0) {
      // Commit up to the event with the left-limit derivative there, apply it, restart from it.
      process_.Derivatives(x_event, f_event, t_event);
      dense.calc_state(0.5 * (t + t_event), x_mid_event);
      const Piece piece{t, t_event, x, f0, x_event, f_event, x_mid_event};
      if (t_event > t) {
        process_.PrepareCommit(piece, options_.abs_tol, options_.rel_tol);
        process_.Commit(piece);
        if (observer) observer(piece);
        ++stats_.steps;
      }
      ++stats_.derivative_evaluations;  // the left-limit derivative at the event
      apply_event(first, t_event, x_event);
      check_finite(x_event, t_event, "non-finite state after an event");
      t = t_event;
      x = x_event;
      restart = true;
      continue;
    }

    const Piece piece{t, t1, x, f0, x1, f1, x_mid};
    if (!options_.control_history_error) process_.PrepareCommit(piece, options_.abs_tol, options_.rel_tol);
    process_.Commit(piece);
    if (observer) observer(piece);
    ++stats_.steps;
    const bool on_stop = limited && std::abs(t1 - t_stop) <= 1e-12 * std::max(1.0, std::abs(t_stop));
    t = on_stop ? t_stop : t1;
    x = x1;
    // A solution that escapes to infinity without the step size underflowing (a delayed feedback loop without a
    // limit) would otherwise take ever more steps, and store them, until time or memory runs out.
    for (double v : x)
      if (std::abs(v) > kBlowUpGrowth * start_size)
        throw NumericalError("blow-up: the solution has grown to |x| = " + std::to_string(std::abs(v)) + " (from " +
                                 std::to_string(start_size) + " at the start)",
                             t, x);
    std::swap(f0, f1);  // the last stage is the next step's first (first same as last)
    g0.swap(g1);
    if (on_stop && t < t_end) {
      PassBreakpoint(t_stop, x);
      ++stats_.breakpoints;
      restart = true;
    }
  }
  stats_.wall_time_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return x;
}

}  // namespace drillwave::integration
