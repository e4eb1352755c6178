#include "drillwave/cases/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "drillwave/core/median.hpp"
#include "drillwave/core/sampled.hpp"
#include "drillwave/io/json_number.hpp"

namespace drillwave::cases {
namespace {

// See StickSlipStatistics::oscillation_period_s. Crossing times are interpolated linearly between samples.
double OscillationPeriod(const std::vector<double>& t, const std::vector<double>& v, double begin, double end,
                         double mean, double max, double min) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // A swing of less than a thousandth of the speed scale is no oscillation (it is the solver's noise).
  if (!(max - min > 1e-3 * std::max({std::abs(max), std::abs(min), 1e-9}))) return nan;
  const double level = 0.5 * (mean + max);
  std::vector<double> crossings;
  bool armed = false;
  for (std::size_t i = 1; i < t.size(); ++i) {
    if (t[i - 1] < begin || t[i] > end) continue;
    if (v[i] < mean) armed = true;
    if (armed && v[i - 1] < level && v[i] >= level) {
      crossings.push_back(t[i - 1] + (level - v[i - 1]) / (v[i] - v[i - 1]) * (t[i] - t[i - 1]));
      armed = false;
    }
  }
  return crossings.size() >= 2 ? (crossings.back() - crossings.front()) / (crossings.size() - 1) : nan;
}

// (max - min) / (2 mean) of the speed over [a, b].
double WindowSeverity(const std::vector<double>& t, const std::vector<double>& v, const std::vector<double>& angle,
                      double a, double b) {
  double max = -std::numeric_limits<double>::infinity(), min = -max, sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < a || t[i] > b) continue;
    max = std::max(max, v[i]), min = std::min(min, v[i]), sum += v[i], ++n;
  }
  if (n == 0) return std::numeric_limits<double>::quiet_NaN();
  const double mean =
      angle.empty() ? sum / n : (InterpolateSampled(t, angle, b) - InterpolateSampled(t, angle, a)) / (b - a);
  return mean > 0 ? (max - min) / (2 * mean) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

nlohmann::json StickSlipStatistics::ToJson() const {
  return {{"stick_slip_period_s", io::FiniteOrNull(stick_slip_period_s)},
          {"oscillation_period_s", io::FiniteOrNull(oscillation_period_s)},
          {"stick_onsets", stick_onsets},
          {"stick_fraction", stick_fraction},
          {"bit_speed_max_rad_s", speed_max},
          {"bit_speed_min_rad_s", speed_min},
          {"bit_speed_mean_rad_s", speed_mean},
          {"stick_slip_severity", io::FiniteOrNull(severity)},
          {"stick_slip_severity_windows", severity_windows}};
}

std::vector<std::pair<double, double>> SeverityWindows(double begin, double end) {
  const double length = end - begin;
  const int count = std::max(1, static_cast<int>(std::floor(length / kSeverityWindowS * (1 + 1e-12))));
  const double width = count == 1 ? length : kSeverityWindowS;
  std::vector<std::pair<double, double>> windows;
  for (int k = 0; k < count && length > 0; ++k) windows.emplace_back(begin + k * width, begin + (k + 1) * width);
  return windows;
}

double StickSlipSeverity(const std::vector<double>& time_s, const std::vector<double>& speed_rad_s,
                         const std::vector<double>& angle_rad, double begin, double end, int* windows) {
  std::vector<double> per_window;
  for (const auto& [a, b] : SeverityWindows(begin, end)) {
    const double s = WindowSeverity(time_s, speed_rad_s, angle_rad, a, b);
    if (std::isnan(s)) return std::numeric_limits<double>::quiet_NaN();  // a window that does not turn forward
    per_window.push_back(s);
  }
  if (windows) *windows = static_cast<int>(per_window.size());
  return Median(per_window);
}

StickSlipStatistics ComputeStickSlipStatistics(const std::vector<StuckInterval>& stuck,
                                               const std::vector<double>& time_s,
                                               const std::vector<double>& speed_rad_s,
                                               const std::vector<double>& angle_rad, double window_begin_s,
                                               double window_end_s) {
  StickSlipStatistics s;
  const double length = window_end_s - window_begin_s;
  std::vector<double> onsets;
  double stuck_time = 0;
  for (const StuckInterval& iv : stuck) {
    if (iv.begin_s >= window_begin_s && iv.begin_s < window_end_s) onsets.push_back(iv.begin_s);
    const double a = std::max(iv.begin_s, window_begin_s), b = std::min(iv.end_s, window_end_s);
    if (b > a) stuck_time += b - a;
  }
  s.stick_onsets = static_cast<int>(onsets.size());
  s.stick_slip_period_s = onsets.size() >= 2 ? (onsets.back() - onsets.front()) / (onsets.size() - 1)
                                             : std::numeric_limits<double>::quiet_NaN();
  s.stick_fraction = length > 0 ? stuck_time / length : 0;
  s.speed_max = -std::numeric_limits<double>::infinity();
  s.speed_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < time_s.size(); ++i) {
    if (time_s[i] < window_begin_s || time_s[i] > window_end_s) continue;
    s.speed_max = std::max(s.speed_max, speed_rad_s[i]);
    s.speed_min = std::min(s.speed_min, speed_rad_s[i]);
  }
  if (!angle_rad.empty() && length > 0)
    s.speed_mean = (InterpolateSampled(time_s, angle_rad, window_end_s) - InterpolateSampled(time_s, angle_rad, window_begin_s)) / length;
  s.severity = StickSlipSeverity(time_s, speed_rad_s, angle_rad, window_begin_s, window_end_s, &s.severity_windows);
  s.oscillation_period_s =
      OscillationPeriod(time_s, speed_rad_s, window_begin_s, window_end_s, s.speed_mean, s.speed_max, s.speed_min);
  return s;
}

}  // namespace drillwave::cases
