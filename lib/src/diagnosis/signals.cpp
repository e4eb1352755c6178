#include "drillwave/diagnosis/signals.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace drillwave::diagnosis {

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

namespace {
// The median of a sorted window and the median of its absolute deviations from it (the MAD), by walking outwards from
// the middle: the deviations below and above the median are each sorted already.
std::pair<double, double> MedianAndMad(const std::vector<double>& sorted) {
  const std::size_t n = sorted.size(), mid = n / 2;
  const double median = n % 2 == 1 ? sorted[mid] : 0.5 * (sorted[mid - 1] + sorted[mid]);
  // Merge the two sorted runs of deviations, |below| from mid - 1 down and above from mid up, to their middle.
  long below = static_cast<long>(mid) - 1, above = static_cast<long>(mid);
  double previous = 0, current = 0;
  for (std::size_t taken = 0; taken <= mid; ++taken) {
    const double down = below >= 0 ? median - sorted[below] : std::numeric_limits<double>::infinity();
    const double up = above < static_cast<long>(n) ? sorted[above] - median : std::numeric_limits<double>::infinity();
    previous = current;
    if (down <= up) current = down, --below;
    else current = up, ++above;
  }
  return {median, n % 2 == 1 ? current : 0.5 * (previous + current)};
}
}  // namespace

HampelResult HampelFilter(const std::vector<double>& x, int half_window, double threshold, double min_deviation,
                          double grow_threshold) {
  if (half_window < 1) throw std::invalid_argument("Hampel half window must be >= 1");
  const int n = static_cast<int>(x.size());
  HampelResult r{x, std::vector<char>(x.size(), 0)};
  std::vector<double> median(x.size()), sigma(x.size());
  // The window kept sorted as it slides: one value leaves and one enters per sample (a copy and a partial sort per
  // sample took 7 % of diagnose's time).
  std::vector<double> window;
  int window_lo = 0, window_hi = -1;  // the window holds x[window_lo..window_hi]
  for (int i = 0; i < n; ++i) {
    const int lo = std::max(0, i - half_window), hi = std::min(n - 1, i + half_window);
    for (; window_lo < lo; ++window_lo) {
      auto leaving = std::lower_bound(window.begin(), window.end(), x[window_lo]);
      if (leaving == window.end() || !(*leaving == x[window_lo]))  // a NaN is found by no comparison
        leaving = std::find_if(window.begin(), window.end(), [](double v) { return std::isnan(v); });
      if (leaving != window.end()) window.erase(leaving);
    }
    for (; window_hi < hi; ++window_hi)
      window.insert(std::upper_bound(window.begin(), window.end(), x[window_hi + 1]), x[window_hi + 1]);
    const auto [m, mad] = MedianAndMad(window);
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

}  // namespace drillwave::diagnosis
