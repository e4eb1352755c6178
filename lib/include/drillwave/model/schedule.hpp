#pragma once
// A piecewise-linear input signal of time (top-drive speed set-point, torque, weight on bit, voltage).
// Knots are (time, value); a repeated time makes a jump. Constant before the first and after the last knot.
// Its knots are breakpoints for the integrator.
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace drillwave::model {

class Schedule {
 public:
  Schedule() : Schedule(0.0) {}
  explicit Schedule(double constant);
  explicit Schedule(std::vector<std::pair<double, double>> knots);  // times non-decreasing, at least one knot

  // JSON: a number (constant) or {"knots": [[t0, v0], [t1, v1], ...]}; errors name json_path.
  static Schedule FromJson(const nlohmann::json& j, const std::string& json_path);
  nlohmann::json ToJson() const;

  // Right-continuous value and slope (at a jump or kink time: the value after it).
  double Value(double t) const { return Evaluate(t, false).first; }
  double Slope(double t) const { return Evaluate(t, false).second; }
  // Left limits, for look-ups at the end of an integration step.
  double ValueBefore(double t) const { return Evaluate(t, true).first; }
  double SlopeBefore(double t) const { return Evaluate(t, true).second; }
  // Value and slope on the side the caller asks for.
  std::pair<double, double> Evaluate(double t, bool left_limit) const;

  const std::vector<std::pair<double, double>>& knots() const { return knots_; }
  // The first knot time later than t (+inf if none): the next breakpoint this input puts into a run.
  double NextKnotAfter(double t) const;
  bool IsConstant() const { return knots_.size() == 1; }

 private:
  std::vector<std::pair<double, double>> knots_;
};

}  // namespace drillwave::model
