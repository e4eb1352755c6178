#pragma once
// How good an estimate is against a measurement (where a recording has the downhole channels), and what it says about
// stick-slip: events and a severity index over windows.
#include <cstddef>
#include <vector>

namespace drillwave::estimation {

struct SeriesError {
  double rms = 0, bias = 0;  // of estimate - measurement over samples where both are finite
  double measured_mean = 0;  // for relative figures
  std::size_t samples = 0;
};

// Over samples with time in [begin_s, end_s].
SeriesError CompareSeries(const std::vector<double>& time_s, const std::vector<double>& estimate,
                          const std::vector<double>& measured, double begin_s, double end_s);

// The delay of a downhole channel behind the bit (telemetry, chapter sect. 2.7), read as the shift in [0, max_lag_s]
// that minimises the RMS of estimate(t) - measured(t + shift); 0 when no shift lowers it by more than a tenth.
double DownholeDelay(const std::vector<double>& time_s, const std::vector<double>& estimate,
                     const std::vector<double>& measured, double max_lag_s);

// measured(t + shift) on the same grid (NaN past the end).
std::vector<double> Advanced(const std::vector<double>& measured, std::size_t shift_samples);

struct StuckScore {
  std::size_t true_positive = 0, false_positive = 0, false_negative = 0, measured_stuck = 0, samples = 0;
  double precision = 0, recall = 0, f1 = 0;  // 1 where there is nothing to find and nothing was found
};

// Stuck samples of the estimate against |measured speed| < threshold, over [begin_s, end_s] where the estimate is
// available (finite `estimated_speed`).
StuckScore ScoreStuck(const std::vector<double>& time_s, const std::vector<double>& estimated_speed,
                      const std::vector<char>& estimated_stuck, const std::vector<double>& measured_speed,
                      double threshold, double begin_s, double end_s);

struct StuckEvent {
  double begin_s = 0, end_s = 0;
};
// Runs of stuck samples (gaps of one sample closed, runs of a single sample dropped).
std::vector<StuckEvent> StuckEvents(const std::vector<double>& time_s, const std::vector<char>& stuck);

struct SeverityWindow {
  double begin_s = 0, end_s = 0;
  double severity = 0;       // (max - min) / (2 mean) of the bit speed: 0 smooth, 1 and more stick-slip
  double stuck_fraction = 0;
};
// Consecutive windows of window_s over the finite part of the estimate.
std::vector<SeverityWindow> SeverityIndex(const std::vector<double>& time_s, const std::vector<double>& speed,
                                          const std::vector<char>& stuck, double window_s);

}  // namespace drillwave::estimation
