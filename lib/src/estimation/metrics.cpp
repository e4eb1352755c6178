#include "drillwave/estimation/metrics.hpp"

#include <algorithm>
#include <cmath>

namespace drillwave::estimation {

SeriesError CompareSeries(const std::vector<double>& t, const std::vector<double>& estimate,
                          const std::vector<double>& measured, double begin_s, double end_s) {
  SeriesError e;
  double sum = 0, sum2 = 0, mean = 0;
  for (std::size_t i = 0; i < t.size() && i < estimate.size() && i < measured.size(); ++i) {
    if (t[i] < begin_s || t[i] > end_s || !std::isfinite(estimate[i]) || !std::isfinite(measured[i])) continue;
    const double d = estimate[i] - measured[i];
    sum += d;
    sum2 += d * d;
    mean += measured[i];
    ++e.samples;
  }
  if (e.samples == 0) return e;
  const double n = static_cast<double>(e.samples);
  e.rms = std::sqrt(sum2 / n);
  e.bias = sum / n;
  e.measured_mean = mean / n;
  return e;
}

std::vector<double> Advanced(const std::vector<double>& measured, std::size_t shift) {
  std::vector<double> y(measured.size(), NAN);
  for (std::size_t i = 0; i + shift < measured.size(); ++i) y[i] = measured[i + shift];
  return y;
}

TelemetryLag ReadTelemetryLag(const std::vector<double>& t, const std::vector<double>& estimate,
                              const std::vector<double>& measured, double begin_s, double end_s, double max_lag_s) {
  TelemetryLag lag;
  if (t.size() < 2 || estimate.size() != t.size() || measured.size() != t.size()) return lag;
  const double dt = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
  const auto max_shift = static_cast<std::size_t>(std::max(0.0, max_lag_s) / dt);
  double in_window = 0;
  for (double ti : t) in_window += ti >= begin_s && ti <= end_s;
  // A lag is read on at least half the window's samples (a lag past the recording's end leaves a few).
  const double enough = std::max(8.0, 0.5 * in_window);
  auto correlation = [&](std::size_t shift) {
    double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    for (std::size_t i = 0; i + shift < t.size(); ++i) {
      if (t[i] < begin_s || t[i] > end_s) continue;
      const double a = estimate[i], b = measured[i + shift];
      if (!std::isfinite(a) || !std::isfinite(b)) continue;
      n += 1, sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b;
    }
    const double va = saa - sa * sa / n, vb = sbb - sb * sb / n;
    return n >= enough && va > 0 && vb > 0 ? (sab - sa * sb / n) / std::sqrt(va * vb) : NAN;
  };
  lag.correlation_at_zero = correlation(0);
  lag.correlation = lag.correlation_at_zero;
  std::size_t best = 0;
  for (std::size_t shift = 1; shift <= max_shift; ++shift) {
    const double r = correlation(shift);
    if (r > lag.correlation) lag.correlation = r, best = shift;
  }
  lag.lag_s = static_cast<double>(best) * dt;
  lag.found = std::isfinite(lag.correlation) && lag.correlation >= kMinTelemetryCorrelation &&
              lag.lag_s >= kMinTelemetryLagS && best < max_shift &&
              1 - lag.correlation <= 0.25 * (1 - lag.correlation_at_zero);
  return lag;
}

StuckScore ScoreStuck(const std::vector<double>& t, const std::vector<double>& speed, const std::vector<char>& stuck,
                      const std::vector<double>& measured, double threshold, double begin_s, double end_s) {
  StuckScore s;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < begin_s || t[i] > end_s || !std::isfinite(speed[i]) || !std::isfinite(measured[i])) continue;
    const bool truth = std::abs(measured[i]) < threshold, guess = stuck[i] != 0;
    ++s.samples;
    s.measured_stuck += truth;
    s.true_positive += truth && guess;
    s.false_positive += !truth && guess;
    s.false_negative += truth && !guess;
  }
  const double tp = static_cast<double>(s.true_positive);
  const double fp = static_cast<double>(s.false_positive), fn = static_cast<double>(s.false_negative);
  s.precision = tp + fp > 0 ? tp / (tp + fp) : (fn > 0 ? 0.0 : 1.0);
  s.recall = tp + fn > 0 ? tp / (tp + fn) : 1.0;
  s.f1 = 2 * tp + fp + fn > 0 ? 2 * tp / (2 * tp + fp + fn) : 1.0;
  return s;
}

std::vector<StuckEvent> StuckEvents(const std::vector<double>& t, const std::vector<char>& stuck) {
  std::vector<StuckEvent> events;
  std::size_t i = 0;
  const std::size_t n = std::min(t.size(), stuck.size());
  while (i < n) {
    if (!stuck[i]) {
      ++i;
      continue;
    }
    std::size_t j = i;
    // A single free sample inside a stuck run is noise across the threshold, not a slip.
    while (j + 1 < n && (stuck[j + 1] || (j + 2 < n && stuck[j + 2]))) ++j;
    if (j > i) events.push_back({t[i], t[j]});
    i = j + 1;
  }
  return events;
}

std::vector<SeverityWindow> SeverityIndex(const std::vector<double>& t, const std::vector<double>& speed,
                                          const std::vector<char>& stuck, double window_s) {
  std::vector<SeverityWindow> windows;
  std::size_t i = 0;
  while (i < t.size() && !std::isfinite(speed[i])) ++i;
  while (i < t.size()) {
    SeverityWindow w;
    w.begin_s = t[i];
    double lo = INFINITY, hi = -INFINITY, sum = 0;
    std::size_t count = 0, stuck_count = 0, j = i;
    for (; j < t.size() && t[j] < w.begin_s + window_s && std::isfinite(speed[j]); ++j) {
      lo = std::min(lo, speed[j]);
      hi = std::max(hi, speed[j]);
      sum += speed[j];
      stuck_count += stuck[j] != 0;
      ++count;
    }
    if (count == 0 || t[j - 1] - w.begin_s < 0.5 * window_s) break;  // a short tail is no window
    w.end_s = t[j - 1];
    const double mean = sum / static_cast<double>(count);
    w.severity = mean > 0 ? (hi - lo) / (2 * mean) : 0.0;
    w.stuck_fraction = static_cast<double>(stuck_count) / static_cast<double>(count);
    windows.push_back(w);
    i = j;
    if (i < t.size() && !std::isfinite(speed[i])) break;
  }
  return windows;
}

}  // namespace drillwave::estimation
