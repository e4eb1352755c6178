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
//   void OnBreakpoint(double t);       // the loop has stepped exactly onto NextBreakpoint()
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include "drillwave/core/error.hpp"

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
  // The most steps a run may need at the longest step the process allows (its shortest delay): refused before the
  // first step, with InputError("/model", ...), rather than integrated for hours (a string of G = 1e300 Pa). A run
  // that makes more than 2 x max_steps derivative evaluations anyway (stiffness) stops with a NumericalError.
  double max_steps = std::numeric_limits<double>::infinity();
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
  const double h = p.t1 - p.t0, s = (t - p.t0) / h, s2 = s * s, s3 = s2 * s, r = 1 - s;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double cubic_mid = 0.5 * (p.x0[i] + p.x1[i]) + 0.125 * h * (p.f0[i] - p.f1[i]);
    x[i] = (2 * s3 - 3 * s2 + 1) * p.x0[i] + (s3 - 2 * s2 + s) * h * p.f0[i] + (-2 * s3 + 3 * s2) * p.x1[i] +
           (s3 - s2) * h * p.f1[i] + 16.0 * (p.x_mid[i] - cubic_mid) * s2 * r * r;
  }
}

struct IntegrationStats {
  long steps = 0;                // accepted pieces
  long derivative_evaluations = 0;
  long events = 0;               // mode changes applied
  long breakpoints = 0;          // breakpoints stepped onto
  long history_rejections = 0;   // steps redone because their interpolant was not accurate enough
  double wall_time_s = 0;
};

using PieceObserver = std::function<void(const Piece&)>;

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
  if ((t_end - t0) / max_step > options_.max_steps)
    throw InputError("/model", "its shortest delay limits steps to " + ReadableNumber(max_step) + " s, so " +
                                   ReadableNumber(t_end - t0) + " s need at least " +
                                   ReadableNumber((t_end - t0) / max_step) + " steps, above the limit of " +
                                   ReadableNumber(options_.max_steps) +
                                   " (--max-samples); check the model's lengths, moduli and densities");
  auto dense = odeint::make_dense_output(options_.abs_tol, options_.rel_tol,
                                         std::isfinite(max_step) ? max_step : 0.0, Stepper());

  // The right-hand side as odeint sees it. It keeps the first derivative after a restart (the right limit at the
  // restart point) and the last one (after do_step: the first-same-as-last stage f(t1, x1), a left limit), so the
  // history gets exact end derivatives without extra evaluations.
  bool capture_first = false;
  double last_t = std::numeric_limits<double>::quiet_NaN();
  State f0(n), f1(n);
  auto system = [&](const State& xs, State& dxdt, double t) {
    process_.Derivatives(xs, dxdt, t);
    ++stats_.derivative_evaluations;
    last_t = t;
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
  State x_event(n), x_try(n), f_event(n), x_mid(n), x_mid_event(n);
  bool history_limited = false;  // the last piece asked for a shorter step than the stepper's suggestion
  int events_here = 0;
  double events_here_time = t0;
  // Applies event i at t; many at one instant mean the modes chatter (no consistent regime exists there).
  auto apply_event = [&](int i, double te, State& xe) {
    if (te == events_here_time) {
      if (++events_here > options_.max_events_at_one_instant)
        throw NumericalError("too many events at one instant (chattering between modes)", te, xe);
    } else {
      events_here_time = te;
      events_here = 0;
    }
    if (process_.OnEvent(i, te, xe)) ++stats_.events;
  };

  while (t < t_end) {
    const double t_stop = std::min(process_.NextBreakpoint(), t_end);
    if (t_stop <= t + 1e-13 * std::max(1.0, std::abs(t))) {  // standing on a breakpoint
      if (t_stop >= t_end) break;
      process_.OnBreakpoint(t_stop);
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
    if (static_cast<double>(stats_.derivative_evaluations) > 2 * options_.max_steps)  // a budget, not a guess
      throw NumericalError("more than " + ReadableNumber(2 * options_.max_steps) + " derivative evaluations (a step "
                           "size collapsed by stiffness; the limit is 2 x --max-samples)", t, x);
    try {
      dense.do_step(system);
    } catch (const odeint::step_adjustment_error&) {
      throw NumericalError("step size underflow (the error tolerance cannot be met)", t, x);
    }
    const double t1 = dense.current_time();
    const State& x1 = dense.current_state();
    if (!(t1 - t > 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t))))
      throw NumericalError("step size underflow (a discontinuity the integrator cannot step over?)", t, x);
    if (!std::all_of(x1.begin(), x1.end(), [](double v) { return std::isfinite(v); }))
      throw NumericalError("non-finite state in the step after this point (diverged, or a model function gave NaN)",
                           t, x);
    if (last_t != t1) throw NumericalError("internal: the last stage is not at the step end", t1, x1);
    dense.calc_state(0.5 * (t + t1), x_mid);
    double dt_history = std::numeric_limits<double>::infinity();
    if (options_.control_history_error) {
      const double h = t1 - t;
      double worst = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const double cubic_mid = 0.5 * (x[i] + x1[i]) + 0.125 * h * (f0[i] - f1[i]);
        const double scale = options_.abs_tol + options_.rel_tol * std::max(std::abs(x[i]), std::abs(x1[i]));
        worst = std::max(worst, std::abs(x_mid[i] - cubic_mid) / scale);
      }
      if (worst <= 1.0)  // the stored signals need checking only if the state passed
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
    std::swap(f0, f1);  // the last stage is the next step's first (first same as last)
    g0.swap(g1);
    if (on_stop && t < t_end) {
      process_.OnBreakpoint(t_stop);
      ++stats_.breakpoints;
      restart = true;
    }
  }
  stats_.wall_time_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return x;
}

}  // namespace drillwave::integration
