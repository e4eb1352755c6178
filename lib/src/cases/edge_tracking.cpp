#include "drillwave/cases/edge_tracking.hpp"

#include <algorithm>
#include <cmath>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/io/json_reader.hpp"

namespace drillwave::cases {

namespace {

struct Outcome {
  bool sticks;
  RunResult result;
};

Outcome RunAt(const nlohmann::json& document, const std::string& pointer, double value) {
  nlohmann::json doc = document;
  io::SetByPointer(doc, pointer, value);
  CaseRun run = RunCase(ParseCase(doc));
  const bool sticks = run.summary.value("stick_onsets", 0) > 0;
  return {sticks, std::move(run.result)};
}

}  // namespace

EdgeResult TrackEdge(const nlohmann::json& document, const EdgeSpec& spec) {
  EdgeResult r;
  r.decays = spec.decays, r.sticks = spec.sticks;
  Outcome low = RunAt(document, spec.pointer, spec.decays), high = RunAt(document, spec.pointer, spec.sticks);
  r.runs = 2;
  if (low.sticks || !high.sticks)
    throw InputError(spec.pointer, "the values " + Significant(spec.decays, 10) + " and " +
                                       Significant(spec.sticks, 10) + " do not straddle the boundary: the first " +
                                       (low.sticks ? "sticks" : "does not stick") + ", the second " +
                                       (high.sticks ? "sticks" : "does not stick"));
  r.edge = std::move(low.result);
  while (std::abs(r.sticks - r.decays) > spec.tolerance * std::max(1.0, std::abs(r.decays))) {
    const double mid = 0.5 * (r.decays + r.sticks);
    if (mid == r.decays || mid == r.sticks) break;
    Outcome o = RunAt(document, spec.pointer, mid);
    ++r.runs;
    if (o.sticks) {
      r.sticks = mid;
    } else {
      r.decays = mid;
      r.edge = std::move(o.result);
    }
  }
  return r;
}

ShadowedCycle FindShadowedCycle(const std::vector<double>& t, const std::vector<double>& y, double t_from) {
  // Local maxima and the least value between consecutive maxima.
  std::vector<std::size_t> peaks;
  for (std::size_t i = 1; i + 1 < t.size(); ++i)
    if (t[i] >= t_from && y[i] > y[i - 1] && y[i] >= y[i + 1]) peaks.push_back(i);
  std::vector<double> amplitude;
  for (std::size_t k = 0; k + 1 < peaks.size(); ++k) {
    const double low = *std::min_element(y.begin() + peaks[k], y.begin() + peaks[k + 1]);
    amplitude.push_back(std::max(y[peaks[k]], y[peaks[k + 1]]) - low);
  }
  // Peak times refined by the parabola through the sample and its neighbours.
  auto peak_time = [&](std::size_t i) {
    const double a = y[i - 1], b = y[i], c = y[i + 1], den = a - 2 * b + c;
    const double shift = den < 0 ? 0.5 * (a - c) / den : 0.0;
    return t[i] + shift * 0.5 * (t[i + 1] - t[i - 1]);
  };
  ShadowedCycle best;
  // The decayed tail (an oscillation at round-off level) is steady too: only cycles of at least 1 % of the largest.
  const double largest = amplitude.empty() ? 0.0 : *std::max_element(amplitude.begin(), amplitude.end());
  for (std::size_t k = 1; k + 1 < amplitude.size(); ++k) {
    if (!(amplitude[k] > 0.01 * largest)) continue;
    const double change = std::abs(amplitude[k + 1] - amplitude[k - 1]) / (2 * amplitude[k]);
    if (!best.found || change < best.relative_change) {
      best.found = true;
      best.relative_change = change;
      best.amplitude = amplitude[k];
      best.time_s = peak_time(peaks[k]);
      best.period_s = peak_time(peaks[k + 1]) - best.time_s;
    }
  }
  return best;
}

}  // namespace drillwave::cases
