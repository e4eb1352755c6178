#pragma once
// Delay equations with closed-form solutions, shared by tests/integration/delay_solver_test.cpp and the bench
// (which sets them against RADAR5's published figures on the same problems).
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "drillwave/integration/delay_solver.hpp"

namespace drillwave::delay_problems {

using integration::DelayProblem;
using integration::PastView;
using State = DelayProblem::State;
using Mode = DelayProblem::Mode;

inline const double kPi = std::acos(-1.0);

// The history is given for t <= t0 only: evaluating it at min(t, t0) keeps a test from handing the solver the exact
// solution beyond t0 for free.
inline double Clamp(double t, double t0) { return std::min(t, t0); }

// Maximum error of the solver's dense output against the exact solution over 4001 equally spaced points of [a, b].
inline double MaxDenseError(const integration::DelaySolution& sol, const std::function<double(double)>& exact,
                            double a, double b) {
  constexpr int kIntervals = 4000;
  double worst = 0;
  for (int i = 0; i <= kIntervals; ++i) {
    const double t = a + (b - a) * i / kIntervals;
    worst = std::max(worst, std::abs(sol.Value(t, 0) - exact(t)));
  }
  return worst;
}

// ddex4 (MATLAB's neutral example), with a vanishing delay: y'(t) = 1 + y(t) - 2 y(t/2)^2 - y'(t - pi),
// y = cos t for t <= 0. Exact y = cos t on [0, pi] (1 + cos t - 2 cos^2(t/2) = 0, -y'(t - pi) = -sin t).
inline DelayProblem NeutralCosineProblem() {
  DelayProblem p;
  p.history = [](double t, double* x, double* d) {
    const double s = Clamp(t, 0.0);
    x[0] = std::cos(s);
    d[0] = -std::sin(s);
  };
  p.rhs = [](double t, const State& x, const PastView& past, const Mode&, State& dxdt) {
    const double half = past.Value(t / 2, 0, t);  // inside the current step early on
    dxdt[0] = 1 + x[0] - 2 * half * half - past.Derivative(t - kPi, 0, t);
  };
  p.constant_delays = {kPi};
  p.neutral = true;
  return p;
}

// Hayashi's state-dependent neutral problem with parameter a:
//   u'(t) = cos t (1 + u(t u^2)) + a u u'(t u^2) + (1 - a) sin t cos(t sin^2 t) - sin(t + t sin^2 t),
// u = sin t for t <= 0; exact u = sin t on [0, pi]. The delay t (1 - u^2) vanishes at t = 0 and t = pi/2, where the
// neutral coefficient a u reaches a.
inline DelayProblem HayashiProblem(double a) {
  DelayProblem p;
  p.history = [](double t, double* x, double* d) {
    const double s = Clamp(t, 0.0);
    x[0] = std::sin(s);
    d[0] = std::cos(s);
  };
  p.rhs = [a](double t, const State& x, const PastView& past, const Mode&, State& dxdt) {
    const double u = x[0], delayed = t * u * u, st = std::sin(t);
    dxdt[0] = std::cos(t) * (1 + past.Value(delayed, 0, t)) + a * u * past.Derivative(delayed, 0, t) +
              (1 - a) * st * std::cos(t * st * st) - std::sin(t + t * st * st);
  };
  p.neutral = true;
  return p;
}

// Paul's y'(t) = y(y(t)) for t >= 1, y = 1/2 for t <= 1: the delay t - y(t) depends on the state.
// Exact: y = t/2 on [1, 2] (y(t) <= 1 reads the history); y = e^((t-2)/2) on [2, 2 + 2 ln 2] (y(y) = y/2);
// y = 2 - 2 ln((4 + 2 ln 2 - t)/2) on [2 + 2 ln 2, 3 + 2 ln 2] (y(y) = e^((y-2)/2)). Its breakpoints are where y(t)
// crosses an earlier one: 2 (y = 1, y'' jumps), 2 + 2 ln 2 (y = 2, y''' jumps), 3 + 2 ln 2 (the end).
inline const double kPaulStart = 1.0;
inline const double kPaulEnd = 3 + 2 * std::log(2.0);
inline const double kPaulKink1 = 2.0;
inline const double kPaulKink2 = 2 + 2 * std::log(2.0);

inline double PaulExact(double t) {
  if (t <= kPaulKink1) return t / 2;
  if (t <= kPaulKink2) return std::exp((t - 2) / 2);
  return 2 - 2 * std::log((4 + 2 * std::log(2.0) - t) / 2);
}

inline DelayProblem PaulProblem(bool declare_argument) {
  DelayProblem p;
  p.t0 = kPaulStart;
  p.history = [](double, double* x, double* d) {
    x[0] = 0.5;
    d[0] = 0;
  };
  p.rhs = [](double t, const State& x, const PastView& past, const Mode&, State& dxdt) {
    dxdt[0] = past.Value(x[0], 0, t);
  };
  if (declare_argument) {
    p.num_deviating_arguments = 1;
    p.deviating_arguments = [](double, const State& x, double* alpha) { alpha[0] = x[0]; };
  }
  return p;
}

// y'(t) = -(1/n) sum_k y(t - tau_k), y = 1 for t <= 0: the cost probe (one delay, or three incommensurate
// ones). With flag_neutral the solver is told the equation is neutral (it is not: its jumps smooth out), which made
// it echo every breakpoint by every delay at the same order.
inline DelayProblem AveragedDelaysProblem(const std::vector<double>& delays, bool flag_neutral) {
  DelayProblem p;
  p.history = [](double, double* x, double* d) {
    x[0] = 1;
    d[0] = 0;
  };
  p.rhs = [delays](double t, const State&, const PastView& past, const Mode&, State& dxdt) {
    double sum = 0;
    for (double tau : delays) sum += past.Value(t - tau, 0, t);
    dxdt[0] = -sum / static_cast<double>(delays.size());
  };
  p.constant_delays = delays;
  p.neutral = flag_neutral;
  return p;
}

// A solution that ceases to exist: y'(t) = 1 + y'(y(t)) / 2, y = t - 1 for t <= 0. While y(t) reads the history
// y' = 3/2; after that y' = s_k on [T_k, T_k+1] with s_k = 1 + s_(k-1) / 2 -> 2 and T_k+1 the time y reaches T_k.
// The argument y(t) catches up with t at T* = sum of the (geometrically shrinking) intervals, where y' -> 2 > 1:
// beyond T* the equation would read y' at times after t.
inline double CeasesToExistTime() {
  double length = 1, slope = 1, end = 0;  // T_0 - y(0) = 1, phi' = 1
  for (int k = 0; k < 200; ++k) {
    slope = 1 + slope / 2;
    length /= slope;
    end += length;
  }
  return end;
}

inline DelayProblem CeasesToExistProblem() {
  DelayProblem p;
  p.history = [](double t, double* x, double* d) {
    x[0] = Clamp(t, 0.0) - 1;
    d[0] = 1;
  };
  p.rhs = [](double t, const State& x, const PastView& past, const Mode&, State& dxdt) {
    dxdt[0] = 1 + 0.5 * past.Derivative(x[0], 0, t);
  };
  p.neutral = true;
  return p;
}

}  // namespace drillwave::delay_problems
