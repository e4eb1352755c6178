#include "drillwave/diagnosis/minimize.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <nlopt.hpp>

#include "drillwave/core/parallel.hpp"
#include "drillwave/core/validity.hpp"

namespace drillwave::diagnosis {

bool MinimizeOptions::IsValid(std::string* error) const {
  auto in_unit_cube = [&](const char* parameter, double value) {
    return (value > 0 && value <= 1) ||
           Invalid(error, parameter, "expected a share of the unit cube in (0, 1], got " + ReadableNumber(value));
  };
  return WholeField(error, "max_evaluations", max_evaluations, 1) && WholeField(error, "starts", starts, 1) &&
         WholeField(error, "threads", threads, 1) && in_unit_cube("initial_step", initial_step) &&
         in_unit_cube("x_tolerance", x_tolerance);
}

MinimizeResult MinimizeInUnitCube(const UnitObjective& f, const std::vector<double>& start,
                                  const MinimizeOptions& o) {
  ThrowIfInvalid(o);
  MinimizeResult result;
  result.best = start;
  for (double& x : result.best) x = std::clamp(x, 0.0, 1.0);
  result.value = f(result.best);
  result.evaluations = 1;
  const unsigned n = static_cast<unsigned>(start.size());
  if (n == 0) return result;

  // The start points, drawn up front: the given one, then seeded random ones.
  const int starts = o.starts;
  std::vector<std::vector<double>> points(static_cast<std::size_t>(starts), result.best);
  std::mt19937 random(o.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int s = 1; s < starts; ++s)
    for (double& xi : points[static_cast<std::size_t>(s)]) xi = unit(random);
  const int share = std::max(1, (o.max_evaluations - result.evaluations) / starts);

  struct Context {
    const UnitObjective* f;
    MinimizeResult* result;
    int budget;
  };
  auto objective = [](const std::vector<double>& u, std::vector<double>&, void* data) {
    auto* c = static_cast<Context*>(data);
    if (c->result->evaluations >= c->budget) throw nlopt::forced_stop();
    const double value = (*c->f)(u);
    ++c->result->evaluations;
    if (value < c->result->value) c->result->value = value, c->result->best = u;
    return std::isfinite(value) ? value : std::numeric_limits<double>::max();
  };
  auto from = [&](std::size_t s) {
    MinimizeResult local{points[s], std::numeric_limits<double>::infinity(), 0};
    Context context{&f, &local, share};
    nlopt::opt opt(nlopt::LN_SBPLX, n);
    opt.set_lower_bounds(std::vector<double>(n, 0.0));
    opt.set_upper_bounds(std::vector<double>(n, 1.0));
    opt.set_min_objective(objective, &context);
    opt.set_xtol_abs(o.x_tolerance);
    opt.set_initial_step(o.initial_step);
    opt.set_maxeval(share);
    std::vector<double> x = points[s];
    double value = 0;
    try {
      opt.optimize(x, value);
    } catch (const nlopt::forced_stop&) {
    } catch (const nlopt::roundoff_limited&) {  // the noise of the objective reached: what was found stands
    }
    return local;
  };
  for (const MinimizeResult& local : ParallelMap(points.size(), o.threads, from)) {
    result.evaluations += local.evaluations;
    if (local.value < result.value) result.value = local.value, result.best = local.best;  // ties: the earlier start
  }
  return result;
}

std::vector<double> CurvatureSigma(const UnitObjective& f, const std::vector<double>& u, double f_at_u, double weight,
                                   double h) {
  std::vector<double> sigma(u.size(), std::nan(""));
  for (std::size_t i = 0; i < u.size(); ++i) {
    std::vector<double> up = u, down = u;
    // A one-sided box edge: step inwards twice instead (second difference of three points on one side).
    double a = -h, b = h;
    if (u[i] + h > 1) a = -2 * h, b = -h;
    if (u[i] - h < 0) a = h, b = 2 * h;
    up[i] = u[i] + b, down[i] = u[i] + a;
    const double fa = f(down), fb = f(up);
    // Second derivative through the three points (a, fa), (0, f_at_u), (b, fb).
    const double d2 = 2 * (fa / (a * (a - b)) + f_at_u / (a * b) + fb / (b * (b - a)));
    const double curvature = weight * d2;
    if (curvature > 0 && std::isfinite(curvature)) sigma[i] = std::sqrt(2 / curvature);
  }
  return sigma;
}

}  // namespace drillwave::diagnosis
