#include "drillwave/recordings/signals.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "drillwave/core/sorted_window.hpp"

namespace drillwave::recordings {

double Mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? std::nan("") : s / v.size();
}

double Std(const std::vector<double>& v) {
  const double m = Mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return v.empty() ? std::nan("") : std::sqrt(s / v.size());
}

HampelResult HampelFilter(const std::vector<double>& x, int half_window, double threshold, double min_deviation,
                          double grow_threshold) {
  if (half_window < 1) throw std::invalid_argument("Hampel half window must be >= 1");
  const int n = static_cast<int>(x.size());
  HampelResult r{x, std::vector<char>(x.size(), 0)};
  std::vector<double> median(x.size()), sigma(x.size());
  // The window kept sorted as it slides: one value leaves and one enters per sample, its MAD selected in O(log n)
  // (a copy and a partial sort per sample took 7 % of diagnose's time, the merge to the MAD's place half of inspect's).
  SortedWindow window;
  int window_lo = 0, window_hi = -1;  // the window holds x[window_lo..window_hi]
  for (int i = 0; i < n; ++i) {
    const int lo = std::max(0, i - half_window), hi = std::min(n - 1, i + half_window);
    for (; window_lo < lo; ++window_lo) window.Erase(x[window_lo]);
    for (; window_hi < hi; ++window_hi) window.Insert(x[window_hi + 1]);
    const auto [m, mad] = window.MedianAndMad();
    median[i] = m;
    sigma[i] = 1.4826 * mad;
    const double d = std::abs(x[i] - median[i]);
    if (d > threshold * sigma[i] && d > min_deviation) r.flagged[i] = 1;
  }
  auto outside = [&](int i) {
    const double d = std::abs(x[i] - median[i]);
    return d > grow_threshold * sigma[i] && d > min_deviation;
  };
  for (int i = 1; i < n; ++i)  // grow forwards, then backwards
    if (r.flagged[i - 1] && !r.flagged[i] && outside(i)) r.flagged[i] = 2;
  for (int i = n - 2; i >= 0; --i)
    if (r.flagged[i + 1] && !r.flagged[i] && outside(i)) r.flagged[i] = 2;
  for (int i = 0; i < n; ++i)
    if (r.flagged[i]) r.flagged[i] = 1, r.cleaned[i] = median[i];
  return r;
}

MaskedRecording MaskArtefacts(const Recording& rec, const std::vector<char>* whole) {
  MaskedRecording out{rec, {}, whole ? *whole : std::vector<char>(rec.names.size(), 0)};
  if (out.whole.size() != rec.names.size()) throw std::invalid_argument("MaskArtefacts: one decision per channel");
  const int half_window = std::max(2, static_cast<int>(std::lround(0.1 / rec.sample_interval_s)));
  for (std::size_t j = 0; j < rec.names.size(); ++j) {
    std::vector<double> magnitude(rec.channels[j].size());
    for (std::size_t i = 0; i < magnitude.size(); ++i) magnitude[i] = std::abs(rec.channels[j][i]);
    const HampelResult h = HampelFilter(rec.channels[j], half_window, 5, 0.05 * Median(magnitude), 2);
    const auto flagged = std::count(h.flagged.begin(), h.flagged.end(), 1);
    if (!whole) out.whole[j] = TooManyForArtefacts(static_cast<std::size_t>(flagged), h.flagged.size());
    if (!out.whole[j]) out.recording.channels[j] = h.cleaned;
    out.masked.push_back({rec.names[j], out.whole[j] ? 0 : static_cast<int>(flagged)});
    out.flagged.push_back(out.whole[j] ? std::vector<char>(h.flagged.size(), 0) : h.flagged);
  }
  return out;
}

std::vector<Interval> Runs(const std::vector<double>& time_s, const std::vector<char>& on, int merge_gap,
                           double min_duration_s) {
  std::vector<std::pair<std::size_t, std::size_t>> runs;  // first, last index
  for (std::size_t i = 0; i < on.size(); ++i) {
    if (!on[i]) continue;
    if (!runs.empty() && i - runs.back().second <= static_cast<std::size_t>(merge_gap) + 1)
      runs.back().second = i;
    else
      runs.push_back({i, i});
  }
  std::vector<Interval> out;
  for (const auto& [a, b] : runs)
    if (time_s[b] - time_s[a] >= min_duration_s) out.push_back({time_s[a], time_s[b]});
  return out;
}

double Correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = std::min(a.size(), b.size());
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < n; ++i) ma += a[i], mb += b[i];
  ma /= n, mb /= n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : std::nan("");
}

}  // namespace drillwave::recordings
