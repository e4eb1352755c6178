#include "drillwave/analysis/fatigue.hpp"

#include <cmath>
#include <limits>

namespace drillwave::analysis {

std::vector<double> Reversals(const std::vector<double>& history) {
  std::vector<double> points;
  for (double value : history) {
    if (!points.empty() && value == points.back()) continue;  // a plateau is one point
    // Extend a monotone run instead of keeping its inner points.
    if (points.size() >= 2 && (points.back() - points[points.size() - 2]) * (value - points.back()) > 0)
      points.back() = value;
    else
      points.push_back(value);
  }
  return points;
}

std::vector<RainflowCycle> RainflowCount(const std::vector<double>& history) {
  std::vector<RainflowCycle> cycles;
  std::vector<double> stack;  // reversals not yet discarded; stack[0] is the starting point S
  auto half_or_full = [&](double a, double b, double count) {
    cycles.push_back({std::abs(a - b), 0.5 * (a + b), count});
  };
  for (double point : Reversals(history)) {
    stack.push_back(point);
    while (stack.size() >= 3) {
      const std::size_t n = stack.size();
      const double x = std::abs(stack[n - 1] - stack[n - 2]);  // the range under consideration
      const double y = std::abs(stack[n - 2] - stack[n - 3]);  // the previous range
      if (x < y) break;
      if (n == 3) {  // Y holds the starting point: half a cycle, the start moves to Y's second point
        half_or_full(stack[0], stack[1], 0.5);
        stack.erase(stack.begin());
      } else {
        half_or_full(stack[n - 3], stack[n - 2], 1.0);
        stack.erase(stack.end() - 3, stack.end() - 1);
      }
    }
  }
  for (std::size_t i = 1; i < stack.size(); ++i) half_or_full(stack[i - 1], stack[i], 0.5);
  return cycles;
}

double SnCurve::CyclesToFailure(double amplitude_Pa) const {
  if (amplitude_Pa <= 0 || amplitude_Pa < endurance_limit_Pa) return std::numeric_limits<double>::infinity();
  return std::pow(amplitude_Pa / coefficient_Pa, 1 / exponent);
}

SnCurve SnCurve::MildSteel() {
  const double ultimate = 400e6, endurance = 0.5 * ultimate, at_1e3 = 0.9 * ultimate;
  return {at_1e3 * at_1e3 / endurance, -std::log10(at_1e3 / endurance) / 3, endurance};
}

double MinerDamage(const std::vector<RainflowCycle>& cycles, const SnCurve& curve) {
  double damage = 0;
  for (const RainflowCycle& c : cycles) damage += c.count / curve.CyclesToFailure(0.5 * c.range);
  return damage;
}

}  // namespace drillwave::analysis
