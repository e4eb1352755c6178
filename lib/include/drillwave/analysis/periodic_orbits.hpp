#pragma once
// Periodic orbits of autonomous piecewise-smooth ODEs: single shooting with Newton (period unknown, a Poincaré-type
// phase condition), Floquet multipliers from the monodromy matrix, and pseudo-arclength continuation in one parameter
// with fold detection and branch start at a Hopf point.
//
// The monodromy matrix is integrated with the orbit: the variational equations Phi' = Df_m(x) Phi within each mode m,
// and at every switch (stick, slip, reversal of a Filippov friction contact) the saltation matrix
//   S = I + (f+ - f-) n^T / (n^T f-),   n = grad h, h the switching function, f-/f+ the fields before/after
// (Leine & Nijmeijer, "Dynamics and Bifurcations of Non-Smooth Mechanical Systems", Springer 2004, ch. 3 and 7; the
// sticking phase is the mode in which the stuck speed is held at zero, so a stick-slip cycle has a zero multiplier).
// Jacobians and switch gradients default to central differences; fields may override them.
#include <complex>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "drillwave/integration/options.hpp"

namespace drillwave::analysis {

// x' = f_m(x) in mode m; switching functions h_k(m, x) end mode m when they go from > 0 to <= 0.
class PiecewiseSmoothField {
 public:
  virtual ~PiecewiseSmoothField() = default;
  virtual int Dimension() const = 0;
  virtual Eigen::VectorXd Derivatives(int mode, const Eigen::VectorXd& x) const = 0;
  // The mode a trajectory starting at x begins in (a smooth field: 0).
  virtual int ModeAt(const Eigen::VectorXd&) const { return 0; }
  virtual int NumSwitches() const { return 0; }
  virtual double Switch(int /*mode*/, int /*k*/, const Eigen::VectorXd&) const { return 1; }
  // The mode after switch k fired at x in `mode` (may equal `mode`: nothing happens).
  virtual int ModeAfter(int mode, int /*k*/, const Eigen::VectorXd&) const { return mode; }
  // Puts x exactly onto the constraint of `mode` (e.g. a stuck speed to 0); the crossing point already lies on it up
  // to the event tolerance, so this changes x by that much and the saltation matrix needs no reset term.
  virtual void Project(int /*mode*/, Eigen::VectorXd&) const {}
  virtual Eigen::MatrixXd Jacobian(int mode, const Eigen::VectorXd& x) const;
  virtual Eigen::RowVectorXd SwitchGradient(int mode, int k, const Eigen::VectorXd& x) const;
  // Equilibria the field knows in closed form or by its own root search (used to start continuation); may be empty.
  virtual std::vector<Eigen::VectorXd> Equilibria() const { return {}; }
};

struct ShootingOptions {
  double abs_tol = 1e-11, rel_tol = 1e-11;  // integrator tolerances of every flow
  double newton_tol = 1e-8;                  // max-norm of the residual (state units) at convergence
  int max_newton = 25;
  int samples_per_period = 2000;             // resolution of the orbit's extrema

  // Tolerances finite and > 0, max_newton and samples_per_period >= 1 (core/validity.hpp).
  bool IsValid(std::string* error) const;
};

struct FlowResult {
  Eigen::VectorXd x;          // state at the end
  int mode = 0;               // mode at the end
  Eigen::MatrixXd sensitivity;  // dx(T)/dx0 (empty unless asked for)
  std::vector<double> time_s;   // samples (t, state) along the way
  std::vector<Eigen::VectorXd> states;
  int switches = 0;             // mode changes
};

// Integrates x0 over [0, duration] from its ModeAt mode, with the sensitivity (variational equations and saltation
// matrices) if asked for. Throws NumericalError on failure; ParameterError for options that are not valid, as every
// function here that takes options.
FlowResult Flow(const PiecewiseSmoothField& field, const Eigen::VectorXd& x0, double duration, bool sensitivity,
                const ShootingOptions& options = {});

struct PeriodicOrbit {
  Eigen::VectorXd x0;   // a point on the orbit (where the phase condition holds)
  double period = 0;
  Eigen::MatrixXd monodromy;
  Eigen::VectorXcd multipliers;   // every eigenvalue of the monodromy, by decreasing modulus
  double max_nontrivial = 0;      // largest |mu| once the trivial multiplier (closest to 1) is removed
  bool stable = false;            // max_nontrivial < 1
  int switches = 0;               // mode changes per period (0: smooth; stick-slip: >= 2)
  std::vector<double> time_s;     // one period, sampled
  std::vector<Eigen::VectorXd> states;
  double residual = 0;            // max-norm of x(T) - x0 at the end of Newton
  int newton_iterations = 0;
};

// Newton on (x0, T): x(T; x0) = x0 and f(x_ref) . (x0 - x_ref) = 0 with x_ref = the guess. Throws NumericalError if
// it does not converge.
PeriodicOrbit FindPeriodicOrbit(const PiecewiseSmoothField& field, const Eigen::VectorXd& guess, double period_guess,
                                const ShootingOptions& options = {});

// Monodromy by central differences of the event-resolved flow over the orbit's period (the check on the saltation
// matrices): column j = (x(T; x0 + h e_j) - x(T; x0 - h e_j)) / 2h.
Eigen::MatrixXd FiniteDifferenceMonodromy(const PiecewiseSmoothField& field, const Eigen::VectorXd& x0, double period,
                                          double h, const ShootingOptions& options = {});

// Fills multipliers, max_nontrivial, stable from orbit.monodromy.
void ClassifyMultipliers(PeriodicOrbit& orbit);

// ---- Continuation in one parameter p --------------------------------------------------------------------------

using FieldFamily = std::function<std::shared_ptr<const PiecewiseSmoothField>(double p)>;

struct EquilibriumPoint {
  double p = 0;
  Eigen::VectorXd x;
  Eigen::VectorXcd eigenvalues;   // of the Jacobian, by decreasing real part
  bool stable = false;
};

struct HopfPoint {
  double p = 0;
  Eigen::VectorXd x;             // the equilibrium
  double omega = 0;              // frequency of the critical pair [rad/s]
  Eigen::VectorXcd eigenvector;  // for i omega
};

// Equilibria of family(p) on the given grid (every equilibrium the field lists, matched to branches by order), with
// their eigenvalues; Hopf points where the largest real part of a complex pair changes sign between neighbours,
// located by bisection in p to `p_tol`.
struct EquilibriumBranches {
  std::vector<EquilibriumPoint> points;  // in grid order
  std::vector<HopfPoint> hopf;
};
EquilibriumBranches ContinueEquilibria(const FieldFamily& family, const std::vector<double>& grid, double p_tol = 1e-9);

struct ContinuationOptions {
  double p_min = -1e300, p_max = 1e300;  // the branch stops when it leaves [p_min, p_max]
  double initial_step = 0.02, min_step = 1e-5, max_step = 0.5;  // arclength in the scaled norm below
  double p_scale = 1;          // arclength norm: |dx|^2 + dT^2 + (dp / p_scale)^2 ... with p measured in p_scale units
  int max_points = 400;
  double hopf_amplitude = 1e-3;  // first step off a Hopf point (state units along the critical eigenvector)
  double end_amplitude = 2e-4;   // a branch ends at an equilibrium when its orbit shrinks below this (peak-to-peak)
  int amplitude_component = -1;  // the state whose range is the amplitude measure (-1: the last)
  double dp_fd = 1e-7;           // relative step of the finite difference in p
  ShootingOptions shooting;
  std::function<void(int points, double p, double period)> progress;  // after each point, if set

  // p_min < p_max; steps finite with 0 < min_step <= initial_step <= max_step; p_scale, hopf_amplitude and dp_fd
  // finite and > 0, end_amplitude finite and >= 0; max_points >= 1; amplitude_component >= -1 (below the field's
  // dimension is the field's to say); valid shooting options (core/validity.hpp).
  bool IsValid(std::string* error) const;
};

struct BranchPoint {
  double p = 0;
  PeriodicOrbit orbit;
  double amplitude_min = 0, amplitude_max = 0;  // range of the amplitude component over the orbit
  double dp_ds = 0;                             // p-component of the unit tangent (sign change: fold)
};

struct FoldPoint {
  double p = 0, period = 0, amplitude_max = 0, amplitude_min = 0;
  double critical_multiplier = 0;  // the nontrivial multiplier closest to +1 there
};

struct PeriodicBranch {
  std::vector<BranchPoint> points;
  std::vector<FoldPoint> folds;
  std::string end;  // why it stopped: "left the parameter range", "reached the equilibrium at a Hopf point", ...
};

// Starts at the Hopf point (amplitude options.hopf_amplitude along the critical eigenvector, period 2 pi / omega) and
// follows the branch of periodic orbits by pseudo-arclength continuation on (x0, T, p); folds are where dp/ds
// changes sign, located by a secant on dp/ds.
PeriodicBranch ContinueFromHopf(const FieldFamily& family, const HopfPoint& hopf, const ContinuationOptions& options);

}  // namespace drillwave::analysis
