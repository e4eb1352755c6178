#pragma once
// Bounded derivative-free minimization for fits that run a model per evaluation (DESIGN.md §5): NLopt's Subplex
// (a Nelder-Mead on subspaces, robust to the small noise a feature objective keeps) inside the unit cube the
// parameters are mapped onto, from the given start and further seeded points, each with an equal share of the budget
// (so the starts are independent, and may run side by side with the same result), and the curvature at the best
// point for the uncertainty of each parameter.
#include <functional>
#include <string>
#include <vector>

namespace drillwave::diagnosis {

struct MinimizeOptions {
  int max_evaluations = 40;    // over all starts, each an equal share
  int starts = 2;              // the given start, then seeded random points in the cube
  int threads = 1;             // starts run side by side (f must then be safe to call from several threads)
  double initial_step = 0.15;  // of the unit cube
  double x_tolerance = 0.01;   // of the unit cube
  unsigned seed = 1;

  // Counts >= 1; initial_step and x_tolerance in (0, 1] (core/validity.hpp).
  bool IsValid(std::string* error) const;
};

struct MinimizeResult {
  std::vector<double> best;  // in [0, 1]^n
  double value = 0;
  int evaluations = 0;
};

using UnitObjective = std::function<double(const std::vector<double>&)>;

// Minimizes f over [0, 1]^n from `start` (n = start.size() >= 1; n = 0 evaluates f once). Throws ParameterError for
// options that are not valid.
MinimizeResult MinimizeInUnitCube(const UnitObjective& f, const std::vector<double>& start,
                                  const MinimizeOptions& options = {});

// Standard deviations of the parameters (in unit-cube coordinates) from the curvature of chi2(u) = weight * f(u)
// at u: sigma_i = sqrt(2 / d2chi2/du_i^2) from central differences of step h (a change of chi2 by 1 is one
// standard deviation); NaN where the curvature is not positive (the parameter is not identified).
std::vector<double> CurvatureSigma(const UnitObjective& f, const std::vector<double>& u, double f_at_u, double weight,
                                   double h = 0.05);

}  // namespace drillwave::diagnosis
