// SolveDelayProblem against delay equations with closed-form solutions: retarded with a constant delay, neutral
// with a vanishing delay, state-dependent neutral, Hayashi's state-dependent neutral problem, and a switched
// right-hand side driven through modes and events; then Hayashi with a strong neutral term (a = 0.9), a vanishing
// delay in the first step, Paul's y' = y(y(t)) with located state-dependent breakpoints, the cost of echoes with
// three incommensurate delays, and the failures (no solution beyond a point, blow-up, budgets, bad options). Each
// problem has one test checking the solution (and, where it says something, its one-sided derivatives) at a tight
// tolerance and one sweeping the tolerance, which prints its error-vs-work table ("[ table ]" lines) and checks
// that the error follows the tolerance.
#include <algorithm>
#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "delay_problems.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/integration/delay_solver.hpp"
#include "invalid_field.hpp"

namespace drillwave::integration {
namespace {

using namespace delay_problems;

const std::vector<double> kSweepTolerances = {1e-4, 1e-6, 1e-8, 1e-10};
constexpr int kGridIntervals = 4000;  // the error is the maximum over 4001 equally spaced points

IntegratorOptions Tolerance(double tol) {
  IntegratorOptions o;
  o.abs_tol = tol;
  o.rel_tol = tol;
  return o;
}

double MaxError(const DelaySolution& sol, const std::function<double(double)>& exact, double a, double b) {
  return MaxDenseError(sol, exact, a, b);
}

double MaxDerivativeError(const DelaySolution& sol, const std::function<double(double)>& exact_derivative, double a,
                          double b) {
  double worst = 0;
  for (int i = 0; i <= kGridIntervals; ++i) {
    const double t = a + (b - a) * i / kGridIntervals;
    worst = std::max(worst, std::abs(sol.trajectory.Derivative(t, 0) - exact_derivative(t)));
  }
  return worst;
}

struct SweepRow {
  double tol;
  double error;
  long steps;
  long evals;
  double extra;  // problem-specific column (event-time error), NaN if none
};

void PrintTable(const std::string& title, const std::vector<SweepRow>& rows, const char* extra_name = nullptr) {
  std::cout << "[ table ] " << title << "\n[ table ]      tol    max error   steps   evals";
  if (extra_name) std::cout << "  " << extra_name;
  std::cout << "\n";
  for (const SweepRow& r : rows) {
    std::cout << "[ table ] " << std::setw(8) << std::setprecision(0) << std::scientific << r.tol << std::setw(13)
              << std::setprecision(3) << r.error << std::setw(8) << r.steps << std::setw(8) << r.evals;
    if (extra_name) std::cout << std::setw(13) << r.extra;
    std::cout << "\n";
  }
  std::cout << std::defaultfloat << std::setprecision(6);
}

std::vector<SweepRow> Sweep(const DelayProblem& problem, double t_end, const std::function<double(double)>& exact) {
  std::vector<SweepRow> rows;
  for (double tol : kSweepTolerances) {
    const DelaySolution sol = SolveDelayProblem(problem, t_end, Tolerance(tol));
    rows.push_back({tol, MaxError(sol, exact, problem.t0, t_end), sol.stats.steps,
                    sol.stats.derivative_evaluations, std::nan("")});
  }
  return rows;
}

// The error must follow the tolerance: below c * tol (c measured per problem, with margin) at every tolerance,
// falling at every tightening, and by at least 1e3 over the sweep (1e-4 -> 1e-10).
void ExpectConvergence(const std::vector<SweepRow>& rows, double c) {
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_LE(rows[k].error, c * rows[k].tol + 1e-13) << "tol " << rows[k].tol;
    if (k > 0) {
      EXPECT_LT(rows[k].error, rows[k - 1].error) << "tol " << rows[k].tol;
    }
  }
  EXPECT_LE(1e3 * rows.back().error, rows.front().error);
}

// ---------------------------------------------------------------------------------------------------------------
// 1. u'(t) = -u(t - 1), u = 1 for t <= 0. On [k, k+1], with s = t - k, u = p_k(s) where
//    p_k(s) = p_k(0) - int_0^s p_{k-1}, p_{-1} = 1, p_k(0) = p_{k-1}(1): a polynomial of degree k + 1.

class UnitDelayExact {
 public:
  explicit UnitDelayExact(int intervals) {
    std::vector<double> prev{1.0};  // p_{-1}
    double start = 1.0;             // p_0(0) = u(0)
    for (int k = 0; k < intervals; ++k) {
      std::vector<double> p(prev.size() + 1, 0.0);
      p[0] = start;
      for (std::size_t j = 0; j < prev.size(); ++j) p[j + 1] = -prev[j] / static_cast<double>(j + 1);
      start = 0;
      for (double c : p) start += c;  // p_k(1)
      pieces_.push_back(p);
      prev = p;
    }
  }
  double operator()(double t) const {
    const int k = std::clamp(static_cast<int>(std::floor(t)), 0, static_cast<int>(pieces_.size()) - 1);
    const double s = t - k;
    double v = 0;
    for (auto it = pieces_[k].rbegin(); it != pieces_[k].rend(); ++it) v = v * s + *it;  // Horner
    return v;
  }

 private:
  std::vector<std::vector<double>> pieces_;  // pieces_[k][j]: coefficient of s^j in p_k
};

DelayProblem UnitDelayProblem() {
  DelayProblem p;
  p.history = [](double, double* x, double* d) {
    x[0] = 1;
    d[0] = 0;
  };
  p.rhs = [](double t, const State&, const PastView& past, const Mode&, State& dxdt) {
    dxdt[0] = -past.Value(t - 1, 0, t);
  };
  p.constant_delays = {1.0};
  return p;
}

TEST(DelaySolver, UnitDelayMatchesPiecewisePolynomial) {
  const UnitDelayExact exact(10);
  const DelaySolution sol = SolveDelayProblem(UnitDelayProblem(), 10.0, Tolerance(1e-10));
  EXPECT_LE(MaxError(sol, exact, 0, 10), 2e-11);  // measured 5.2e-12
  // u' jumps from 0 (history) to -1 at t = 0; the stored pieces keep both limits.
  EXPECT_EQ(sol.trajectory.Derivative(0, 0, Side::kLeft), 0.0);
  EXPECT_NEAR(sol.trajectory.Derivative(0, 0, Side::kRight), -1.0, 1e-14);
  // At t = 1 only u'' jumps: u' = -u(t - 1) is continuous, -1 from both sides.
  EXPECT_NEAR(sol.trajectory.Derivative(1, 0, Side::kLeft), -1.0, 1e-12);
  EXPECT_NEAR(sol.trajectory.Derivative(1, 0, Side::kRight), -1.0, 1e-12);
  // The solver steps onto the propagated breakpoints t = 1, 2, ... instead of smearing the kinks across steps.
  EXPECT_GE(sol.stats.breakpoints, 5);
}

TEST(DelaySolver, UnitDelayErrorFollowsTolerance) {
  const UnitDelayExact exact(10);
  const auto rows = Sweep(UnitDelayProblem(), 10.0, exact);
  PrintTable("1. u' = -u(t-1), u = 1 for t <= 0, on [0, 10]", rows);
  ExpectConvergence(rows, 0.2);  // measured error/tol <= 0.07
}

// ---------------------------------------------------------------------------------------------------------------
// 2. Neutral, with a vanishing delay: y'(t) = 1 + y(t) - 2 y(t/2)^2 - y'(t - pi), y = cos t for t <= 0.
//    Exact y = cos t on [0, pi] (1 + cos t - 2 cos^2(t/2) = 0 and -y'(t - pi) = sin(t - pi) = -sin t).

TEST(DelaySolver, NeutralVanishingDelayMatchesCosine) {
  const DelaySolution sol = SolveDelayProblem(NeutralCosineProblem(), kPi, Tolerance(1e-10));
  EXPECT_LE(MaxError(sol, [](double t) { return std::cos(t); }, 0, kPi), 1e-11);  // measured 2.6e-12
  // The derivative of the stored quartic pieces is one order less accurate than their values.
  EXPECT_LE(MaxDerivativeError(sol, [](double t) { return -std::sin(t); }, 0, kPi), 2e-9);  // measured 5.3e-10
}

TEST(DelaySolver, NeutralVanishingDelayErrorFollowsTolerance) {
  const auto rows = Sweep(NeutralCosineProblem(), kPi, [](double t) { return std::cos(t); });
  PrintTable("2. y' = 1 + y - 2 y(t/2)^2 - y'(t-pi), y = cos t for t <= 0, on [0, pi]", rows);
  ExpectConvergence(rows, 2.0);  // measured error/tol <= 0.66 (at tol 1e-4)
}

// ---------------------------------------------------------------------------------------------------------------
// 3. State-dependent neutral: u'(t) = -u'(t - u(t)^2/4), u = 1 - t for t <= 0. Exact u = t + 1: the delayed time
//    t - (t+1)^2/4 = -(t-1)^2/4 stays in the history (u' = -1 there), reaching t0 = 0 only at t = 1.

DelayProblem StateDependentNeutralProblem() {
  DelayProblem p;
  p.history = [](double t, double* x, double* d) {
    x[0] = 1 - Clamp(t, 0.0);
    d[0] = -1;
  };
  p.rhs = [](double t, const State& x, const PastView& past, const Mode&, State& dxdt) {
    dxdt[0] = -past.Derivative(t - x[0] * x[0] / 4, 0, t);
  };
  p.neutral = true;
  return p;
}

TEST(DelaySolver, StateDependentNeutralMatchesLine) {
  const DelaySolution sol = SolveDelayProblem(StateDependentNeutralProblem(), 1.0, Tolerance(1e-10));
  EXPECT_LE(MaxError(sol, [](double t) { return t + 1; }, 0, 1), 1e-13);
  // Rounding in the values divided by the first step (1e-4) when differentiating the pieces: ~1e-12.
  EXPECT_LE(MaxDerivativeError(sol, [](double) { return 1.0; }, 0, 1), 1e-11);
  // At t = 1 the delayed time reaches 0 (up to rounding); the step-end look-up must take the left limit there
  // (the history's u' = -1, so u'(1) = 1), not the first piece's u' = +1.
  EXPECT_NEAR(sol.trajectory.Derivative(1, 0, Side::kLeft), 1.0, 1e-12);
}

TEST(DelaySolver, StateDependentNeutralIsExactAtEveryTolerance) {
  const auto rows = Sweep(StateDependentNeutralProblem(), 1.0, [](double t) { return t + 1; });
  PrintTable("3. u' = -u'(t - u^2/4), u = 1 - t for t <= 0, on [0, 1]", rows);
  // The solution is linear, which every Runge-Kutta step and every stored quartic reproduces: the error is
  // rounding at every tolerance, so there is no convergence to measure.
  for (const SweepRow& r : rows) EXPECT_LE(r.error, 1e-13) << "tol " << r.tol;
}

// ---------------------------------------------------------------------------------------------------------------
// 4. Hayashi's state-dependent neutral problem (tests/support/delay_problems.hpp) with a = 0.3:
//    u'(t) = cos t (1 + u(t u^2)) + 0.3 u u'(t u^2) + 0.7 sin t cos(t sin^2 t) - sin(t + t sin^2 t),
//    u = sin t for t <= 0; exact u = sin t on [0, pi]. The delay t (1 - u^2) vanishes at t = 0 and t = pi/2.

TEST(DelaySolver, HayashiMatchesSine) {
  const DelaySolution sol = SolveDelayProblem(HayashiProblem(0.3), kPi, Tolerance(1e-10));
  EXPECT_LE(MaxError(sol, [](double t) { return std::sin(t); }, 0, kPi), 1e-10);  // measured 3.1e-11
  EXPECT_LE(MaxDerivativeError(sol, [](double t) { return std::cos(t); }, 0, kPi), 3e-9);  // measured 1.1e-9
}

// The Hayashi sweep with parameter a, error bound c * tol; returns the rows.
std::vector<SweepRow> ExpectHayashiFollowsTolerance(double a, double c) {
  const auto rows = Sweep(HayashiProblem(a), kPi, [](double t) { return std::sin(t); });
  PrintTable("Hayashi, a = " + std::to_string(a) + ", u = sin t, on [0, pi]", rows);
  ExpectConvergence(rows, c);
  return rows;
}

TEST(DelaySolver, HayashiErrorFollowsTolerance) {
  // Measured error/tol <= 1.05 (at 1e-4). Before the steps iterated on their own trials, look-ups near the
  // vanishing delay at pi/2 read an extrapolation and loose tolerances overshot (21 tol at 1e-4).
  ExpectHayashiFollowsTolerance(0.3, 3.0);

  // Yardstick: RADAR5 reaches a dense error of about 1e-7 with about 400 right-hand-side evaluations.
  const DelaySolution sol = SolveDelayProblem(HayashiProblem(0.3), kPi, Tolerance(5e-7));
  const SweepRow yardstick{5e-7, MaxError(sol, [](double t) { return std::sin(t); }, 0, kPi), sol.stats.steps,
                           sol.stats.derivative_evaluations, std::nan("")};
  PrintTable("4. Hayashi at a tolerance that gives < 1e-7 (RADAR5: ~1e-7 with ~400 evaluations)", {yardstick});
  EXPECT_LE(yardstick.error, 1e-7);  // measured 3.3e-8
  EXPECT_LE(yardstick.evals, 300);   // measured 252
}

// ---------------------------------------------------------------------------------------------------------------
// 5. A switched right-hand side: u'(t) = -1 - u(t) + 2 [u(t/2) < 0], u = 1 for t <= 0. The indicator is the
//    mode; the witness u(t/2) (mode 0) or -u(t/2) (mode 1) flips it when u(t/2) changes sign. Exact:
//    2 e^-t - 1 on [0, 2 ln 2], 1 - 6 e^-t on [2 ln 2, 2 ln 6], 66 e^-t - 1 on [2 ln 6, 2 ln 66].

const double kSwitch1 = 2 * std::log(2.0);
const double kSwitch2 = 2 * std::log(6.0);
const double kSwitchedEnd = 2 * std::log(66.0);

double SwitchedExact(double t) {
  if (t <= kSwitch1) return 2 * std::exp(-t) - 1;
  if (t <= kSwitch2) return 1 - 6 * std::exp(-t);
  return 66 * std::exp(-t) - 1;
}

DelayProblem SwitchedProblem() {
  DelayProblem p;
  p.history = [](double, double* x, double* d) {
    x[0] = 1;
    d[0] = 0;
  };
  p.initial_mode = {0};  // [u(0) < 0] = 0
  p.rhs = [](double, const State& x, const PastView&, const Mode& mode, State& dxdt) {
    dxdt[0] = -1 - x[0] + 2 * mode[0];
  };
  p.witnesses = {[](double t, const State&, const PastView& past, const Mode& mode) {
    const double half = past.Value(t / 2, 0, t);
    return mode[0] == 0 ? half : -half;
  }};
  p.on_event = [](int, double, State&, Mode& mode) { mode[0] = 1 - mode[0]; };
  return p;
}

// Error of the first two event times; +inf if either is missing.
double EventTimeError(const DelaySolution& sol) {
  if (sol.event_times.size() < 2) return std::numeric_limits<double>::infinity();
  return std::max(std::abs(sol.event_times[0] - kSwitch1), std::abs(sol.event_times[1] - kSwitch2));
}

TEST(DelaySolver, SwitchedByEventsMatchesPiecewiseExponential) {
  const DelaySolution sol = SolveDelayProblem(SwitchedProblem(), kSwitchedEnd, Tolerance(1e-10));
  EXPECT_LE(MaxError(sol, SwitchedExact, 0, kSwitchedEnd), 3e-11);  // measured 8.1e-12
  ASSERT_GE(sol.event_times.size(), 2u);
  EXPECT_NEAR(sol.event_times[0], kSwitch1, 1e-8);
  EXPECT_NEAR(sol.event_times[1], kSwitch2, 1e-8);
  // The third sign change of u(t/2) falls exactly on t_end; rounding decides whether it is seen.
  for (std::size_t k = 2; k < sol.event_times.size(); ++k) EXPECT_NEAR(sol.event_times[k], kSwitchedEnd, 1e-6);
  // u' jumps by +-2 at each event: -1 - u = -1/2 -> 1 - u = 3/2 at 2 ln 2 (u = -1/2), 1/6 -> -11/6 at 2 ln 6
  // (u = 5/6); the pieces end and start exactly at the located event time, keeping both limits.
  const double e1 = sol.event_times[0], e2 = sol.event_times[1];
  EXPECT_NEAR(sol.trajectory.Derivative(e1, 0, Side::kLeft), -0.5, 1e-10);
  EXPECT_NEAR(sol.trajectory.Derivative(e1, 0, Side::kRight), 1.5, 1e-10);
  EXPECT_NEAR(sol.trajectory.Derivative(e2, 0, Side::kLeft), 1.0 / 6, 1e-10);
  EXPECT_NEAR(sol.trajectory.Derivative(e2, 0, Side::kRight), -11.0 / 6, 1e-10);
}

TEST(DelaySolver, SwitchedByEventsErrorFollowsTolerance) {
  std::vector<SweepRow> rows;
  for (double tol : kSweepTolerances) {
    const DelaySolution sol = SolveDelayProblem(SwitchedProblem(), kSwitchedEnd, Tolerance(tol));
    rows.push_back({tol, MaxError(sol, SwitchedExact, 0, kSwitchedEnd), sol.stats.steps,
                    sol.stats.derivative_evaluations, EventTimeError(sol)});
  }
  PrintTable("5. u' = -1 - u + 2 [u(t/2) < 0], u = 1 for t <= 0, on [0, 2 ln 66]", rows, "event error");
  ExpectConvergence(rows, 1.0);  // measured error/tol <= 0.33 (at tol 1e-4)
  // The events are located on the interpolated u(t/2): their error follows the tolerance too (measured <= 0.05 tol).
  for (const SweepRow& r : rows) EXPECT_LE(r.extra, 0.2 * r.tol + 1e-12) << "tol " << r.tol;
}


// ---------------------------------------------------------------------------------------------------------------
// 6. Hayashi's problem with a = 0.9: near t = pi/2 the delay vanishes while the neutral coefficient reaches 0.9, so
//    look-ups fall inside the step and the step's trials contract only by ~0.9 per redo.

TEST(DelaySolver, HayashiStrongNeutralMatchesSine) {
  const DelaySolution sol = SolveDelayProblem(HayashiProblem(0.9), kPi, Tolerance(1e-10));
  EXPECT_LE(MaxError(sol, [](double t) { return std::sin(t); }, 0, kPi), 5e-10);  // measured 1.1e-10
  EXPECT_GT(sol.stats.trial_redos, 0);  // the vanishing delay was read from the step's own trials
}

TEST(DelaySolver, HayashiStrongNeutralErrorFollowsTolerance) {
  ExpectHayashiFollowsTolerance(0.9, 10.0);  // measured error/tol <= 4 (at 1e-4)
  // At a loose tolerance the solution stays near sin t (before: 2.1e-5 at 1e-8, divergence at 1e-3).
  const DelaySolution loose = SolveDelayProblem(HayashiProblem(0.9), kPi, Tolerance(1e-3));
  EXPECT_LE(MaxError(loose, [](double t) { return std::sin(t); }, 0, kPi), 1e-2);  // measured 1.4e-3
}

// ---------------------------------------------------------------------------------------------------------------
// 7. The first step of ddex4 reads y(t/2) inside itself; it is iterated, not extrapolated, so the error does not
//    depend on the initial step (before: 4.7e-4 at tol 1e-8 with initial step 0.1).

TEST(DelaySolver, VanishingDelayErrorDoesNotDependOnInitialStep) {
  for (double initial_step : {1e-6, 1e-4, 1e-2, 0.1, 0.5}) {
    IntegratorOptions o = Tolerance(1e-8);
    o.initial_step = initial_step;
    const DelaySolution sol = SolveDelayProblem(NeutralCosineProblem(), kPi, o);
    // Measured 3.2e-10 ... 3.6e-10 over initial steps 1e-6 ... 0.5.
    EXPECT_LE(MaxError(sol, [](double t) { return std::cos(t); }, 0, kPi), 1e-9) << "initial step " << initial_step;
  }
}

// ---------------------------------------------------------------------------------------------------------------
// 8. Paul's y' = y(y(t)): breakpoints where the state-dependent argument y(t) crosses earlier ones (2 and
//    2 + 2 ln 2). Declared as a deviating argument, the solver locates them and steps onto them.

TEST(DelaySolver, PaulLocatesStateDependentBreakpoints) {
  const DelaySolution sol = SolveDelayProblem(PaulProblem(true), kPaulEnd, Tolerance(1e-10));
  EXPECT_LE(MaxError(sol, PaulExact, kPaulStart, kPaulEnd), 1e-11);  // measured 1.2e-12
  auto near = [&](double b) {
    return std::any_of(sol.breakpoints.begin(), sol.breakpoints.end(), [&](double t) { return std::abs(t - b) < 1e-9; });
  };
  EXPECT_TRUE(near(kPaulKink1));
  EXPECT_TRUE(near(kPaulKink2));
  // At 2, y' = y(y(t)) = 1/2 is continuous; y'' jumps from 0 to 1/4, and the pieces meet there exactly.
  EXPECT_NEAR(sol.trajectory.Derivative(kPaulKink1, 0, Side::kLeft), 0.5, 1e-9);
  EXPECT_NEAR(sol.trajectory.Derivative(kPaulKink1, 0, Side::kRight), 0.5, 1e-9);
}

TEST(DelaySolver, PaulErrorFollowsTolerance) {
  const auto rows = Sweep(PaulProblem(true), kPaulEnd, PaulExact);
  PrintTable("8. Paul, y' = y(y(t)), y = 1/2 for t <= 1, on [1, 3 + 2 ln 2], argument declared", rows);
  ExpectConvergence(rows, 0.5);  // measured error/tol <= 0.13 (RADAR5's dense error stalls at 1.5e-6)
}

// ---------------------------------------------------------------------------------------------------------------
// 9. Echoes stay few: y' = -(1/n) sum y(t - tau_k) on [0, 80] with three incommensurate delays costs at most three
//    times what one delay costs, also when the problem is flagged neutral (before: 37 606 breakpoints and 296 140
//    evaluations against 2 669). Each run is checked against a tight one, so dropped echoes cost no accuracy.

TEST(DelaySolver, ThreeIncommensurateDelaysCostAtMostThreeTimesOne) {
  const std::vector<double> one{1.0}, three{1.0, std::sqrt(2.0), std::sqrt(3.0)};
  for (bool flag_neutral : {false, true}) {
    long evals[2];
    int k = 0;
    for (const auto& delays : {one, three}) {
      const DelayProblem p = AveragedDelaysProblem(delays, flag_neutral);
      const DelaySolution sol = SolveDelayProblem(p, 80, Tolerance(1e-8));
      const DelaySolution reference = SolveDelayProblem(AveragedDelaysProblem(delays, false), 80, Tolerance(1e-12));
      double worst = 0;
      for (int i = 0; i <= 8000; ++i) worst = std::max(worst, std::abs(sol.Value(i * 0.01, 0) - reference.Value(i * 0.01, 0)));
      std::cout << "[ measured ] " << delays.size() << " delay(s)" << (flag_neutral ? ", flagged neutral" : "")
                << ": " << sol.stats.derivative_evaluations << " evaluations, " << sol.stats.breakpoints
                << " breakpoints, max error " << worst << "\n";
      EXPECT_LE(worst, 1e-7) << delays.size() << " delays";
      evals[k++] = sol.stats.derivative_evaluations;
    }
    EXPECT_LE(evals[1], 3 * evals[0]) << (flag_neutral ? "flagged neutral" : "retarded");
  }
}

// ---------------------------------------------------------------------------------------------------------------
// 10. Failures say what happened.

TEST(DelaySolver, StopsWhereTheSolutionCeasesToExist) {
  IntegratorOptions o = Tolerance(1e-8);
  o.max_evaluations = 200000;  // a safety net: the test expects the specific diagnosis well before this
  const double t_star = CeasesToExistTime();
  try {
    SolveDelayProblem(CeasesToExistProblem(), 3.0, o);
    ADD_FAILURE() << "no error; the solution ceases to exist at " << t_star;
  } catch (const NumericalError& e) {
    std::cout << "[ measured ] " << e.what() << " (exact " << t_star << ")\n";
    EXPECT_NE(std::string(e.what()).find("ceases to exist"), std::string::npos) << e.what();
    EXPECT_NEAR(e.time(), t_star, 1e-3);
  }
}

TEST(DelaySolver, RejectsNonPositiveTolerances) {
  const auto refused = [](const IntegratorOptions& o) {
    return testing::RefusedParameter([&] { SolveDelayProblem(UnitDelayProblem(), 1.0, o); });
  };
  for (double bad : {0.0, -1e-8, std::nan("")}) {
    IntegratorOptions o;
    o.abs_tol = bad;
    EXPECT_EQ(refused(o), "abs_tol");
    o = IntegratorOptions{};
    o.rel_tol = bad;
    EXPECT_EQ(refused(o), "rel_tol");
  }
}

// The message of a NumericalError thrown by solving p to t_end (empty if none).
std::string FailureOf(const DelayProblem& p, double t_end, const IntegratorOptions& o) {
  try {
    SolveDelayProblem(p, t_end, o);
  } catch (const NumericalError& e) {
    return e.what();
  }
  return "";
}

TEST(DelaySolver, NamesBlowUpAndBudgets) {
  DelayProblem blow_up;  // y' = y(t) y(t - 1/2), y = 1 before 0: y' = y until 1/2, then faster; infinite before 2
  blow_up.history = [](double, double* x, double* d) {
    x[0] = 1;
    d[0] = 0;
  };
  blow_up.rhs = [](double t, const State& x, const PastView& past, const Mode&, State& dxdt) {
    dxdt[0] = x[0] * x[0] * past.Value(t - 0.5, 0, t);
  };
  blow_up.constant_delays = {0.5};
  const std::string diverged = FailureOf(blow_up, 10.0, Tolerance(1e-8));
  EXPECT_NE(diverged.find("blow"), std::string::npos) << diverged;

  IntegratorOptions o = Tolerance(1e-8);
  o.max_evaluations = 100;
  const std::string evaluations = FailureOf(UnitDelayProblem(), 10.0, o);
  EXPECT_NE(evaluations.find("evaluation budget"), std::string::npos) << evaluations;
  o = Tolerance(1e-8);
  o.max_steps = 10;
  const std::string steps = FailureOf(UnitDelayProblem(), 10.0, o);
  EXPECT_NE(steps.find("step budget"), std::string::npos) << steps;
}

}  // namespace
}  // namespace drillwave::integration
