#pragma once
// Stick–slip statistics over a time window, shared by every kind whose bit (or disc) can stick.
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace drillwave::cases {

struct StuckInterval {
  double begin_s, end_s;  // end = +inf while still stuck at the end of the run
};

struct StickSlipStatistics {
  double stick_slip_period_s = 0;  // mean interval between successive stick onsets in the window; NaN if < 2
  // Period of the oscillation read from the speed itself: mean interval between the upward crossings of the level
  // halfway between the mean and the maximum speed, each counted once the speed has fallen back below the mean.
  // A short re-stick inside a cycle adds a stick onset but no such crossing. NaN without an oscillation.
  double oscillation_period_s = 0;
  int stick_onsets = 0;
  double stick_fraction = 0;       // time stuck / window length
  double speed_max = 0, speed_min = 0, speed_mean = 0;  // rad/s
  // The industry's stick-slip severity: (max - min) / (2 mean) of the speed over each 20-s window laid from the start
  // of the statistics window (the whole window if it is shorter), the median over those windows. 0 for a steady
  // speed, 1 for a full stick-slip swing from rest to twice the mean. NaN where a window's mean speed is not > 0.
  double severity = 0;
  int severity_windows = 0;
  nlohmann::json ToJson() const;   // NaN -> null
};

// speed samples (time, value) give max/min; the mean speed is exact from the angle at the window ends.
constexpr double kSeverityWindowS = 20;

// The windows of the severity over [begin, end]: 20 s each from begin (the part left over at the end is left out),
// or [begin, end] whole if it is shorter; none if it is empty.
std::vector<std::pair<double, double>> SeverityWindows(double begin, double end);

// The severity above over [begin, end], from speed samples; the mean of each window is exact from the angle when it is
// given (non-empty), else the mean of the samples.
double StickSlipSeverity(const std::vector<double>& time_s, const std::vector<double>& speed_rad_s,
                         const std::vector<double>& angle_rad, double begin, double end, int* windows = nullptr);

StickSlipStatistics ComputeStickSlipStatistics(const std::vector<StuckInterval>& stuck,
                                               const std::vector<double>& time_s,
                                               const std::vector<double>& speed_rad_s,
                                               const std::vector<double>& angle_rad, double window_begin_s,
                                               double window_end_s);

}  // namespace drillwave::cases
