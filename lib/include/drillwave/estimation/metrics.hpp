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

// The delay of a downhole channel behind the bit (telemetry, chapter sect. 2.7): the lag in [0, max_lag_s] at which
// measured(t + lag) correlates best with the estimate, over the samples with time in [begin_s, end_s] where both are
// finite (at least half the window's: a lag that runs past the recording's end is not read). It is taken for a delay
// (found) where it explains most of their mismatch: 1 - r at the lag at most a quarter of 1 - r at zero (the
// standardized mismatch's rms halves), r at least kMinTelemetryCorrelation, the lag at least kMinTelemetryLagS and
// short of max_lag_s (a peak on the search's edge may lie past it). Correlation, not the rms of
// the difference, so that a gain or bias of the estimate does not move it; a periodic motion correlates with itself a
// period later, and the quarter rule keeps that from reading as a delay (train rec30: 0.983 at 5.7 s against 0.967 at
// zero, no delay).
inline constexpr double kMinTelemetryCorrelation = 0.8;
// A recording of window means is half a sample late, and the continued waves' timing is good to a few samples.
inline constexpr double kMinTelemetryLagS = 0.1;
struct TelemetryLag {
  double lag_s = 0;
  double correlation = 0, correlation_at_zero = 0;
  bool found = false;
};
TelemetryLag ReadTelemetryLag(const std::vector<double>& time_s, const std::vector<double>& estimate,
                              const std::vector<double>& measured, double begin_s, double end_s, double max_lag_s);

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
