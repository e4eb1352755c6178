#include "drillwave/diagnosis/features.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <map>
#include <unsupported/Eigen/FFT>

#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/validity.hpp"
#include "drillwave/diagnosis/recording.hpp"
#include "drillwave/io/json_number.hpp"

namespace drillwave::diagnosis {
namespace {

const double kNaN = std::nan("");

bool InCorrelogram(const std::string& name) { return name.rfind(kEnvelopeCorrelation, 0) == 0; }

// Centred moving average over 2 half + 1 samples (shorter at the ends).
std::vector<double> MovingAverage(const std::vector<double>& x, int half) {
  if (half <= 0) return x;
  std::vector<double> prefix(x.size() + 1, 0.0), out(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) prefix[i + 1] = prefix[i] + x[i];
  const long n = static_cast<long>(x.size());
  for (long i = 0; i < n; ++i) {
    const long lo = std::max(0L, i - half), hi = std::min(n - 1, i + half);
    out[i] = (prefix[hi + 1] - prefix[lo]) / (hi - lo + 1);
  }
  return out;
}

// Least-squares slope of y on x over the samples where `use` holds; NaN with fewer than 16 or no spread in x.
template <class Use>
double Slope(const std::vector<double>& x, const std::vector<double>& y, Use use) {
  double n = 0, sx = 0, sy = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (use(i)) n += 1, sx += x[i], sy += y[i];
  if (n < 16) return kNaN;
  const double mx = sx / n, my = sy / n;
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (use(i)) sxx += (x[i] - mx) * (x[i] - mx), sxy += (x[i] - mx) * (y[i] - my);
  return sxx > 0 ? sxy / sxx : kNaN;
}

// Normalized correlations of a(t) with b(t + lag) for lags of k samples, each over the samples both series cover and
// normalized by the two series' energies there. All lags come from one FFT (the direct sums over every lag of the
// axial lag's 11 s and the periods' seconds took 9 % of diagnose's time).
class Correlogram {
 public:
  // a and b of one length.
  Correlogram(const std::vector<double>& a, const std::vector<double>& b)
      : n_(static_cast<long>(a.size())), a2_(a.size() + 1, 0.0), b2_(b.size() + 1, 0.0) {
    for (std::size_t i = 0; i < a.size(); ++i) a2_[i + 1] = a2_[i] + a[i] * a[i], b2_[i + 1] = b2_[i] + b[i] * b[i];
    padded_ = 1;
    while (padded_ < 2 * a.size()) padded_ *= 2;  // no wrap-around between positive and negative lags
    std::vector<double> pa(padded_, 0.0), pb(padded_, 0.0);
    std::copy(a.begin(), a.end(), pa.begin());
    std::copy(b.begin(), b.end(), pb.begin());
    Eigen::FFT<double> fft;
    std::vector<std::complex<double>> fa, fb;
    fft.fwd(fa, pa);
    fft.fwd(fb, pb);
    for (std::size_t i = 0; i < fa.size(); ++i) fa[i] = std::conj(fa[i]) * fb[i];
    fft.inv(cross_, fa);  // cross_[k mod padded] = sum_i a[i] b[i + k]
  }

  double At(long k) const {
    if (k <= -n_ || k >= n_) return 0.0;
    const double sab = cross_[static_cast<std::size_t>(k >= 0 ? k : static_cast<long>(padded_) + k)];
    const double saa = k >= 0 ? a2_[n_ - k] : a2_[n_] - a2_[-k];
    const double sbb = k >= 0 ? b2_[n_] - b2_[k] : b2_[n_ + k];
    return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0.0;
  }

 private:
  long n_;
  std::size_t padded_ = 1;
  std::vector<double> a2_, b2_;  // prefix sums of the squares
  std::vector<double> cross_;
};

std::vector<double> Demeaned(std::vector<double> v) {
  const double m = Mean(v);
  for (double& x : v) x -= m;
  return v;
}

// The oscillation period: the first maximum of the autocorrelation after its first zero crossing, if it stands
// above 0.3 (a clear repetition), else NaN (no oscillation worth the name).
double Period(const std::vector<double>& x, double dt, double max_period_s) {
  const std::vector<double> y = Demeaned(x);
  const long max_lag = std::min<long>(static_cast<long>(max_period_s / dt), static_cast<long>(y.size()) / 2);
  const long stride = std::max(1L, static_cast<long>(0.01 / dt));  // lags every 10 ms at most
  bool crossed = false;
  double best = 0.3, best_lag = kNaN, previous = 1;
  const Correlogram autocorrelation(y, y);
  for (long k = stride; k <= max_lag; k += stride) {
    const double c = autocorrelation.At(k);
    if (!crossed) {
      crossed = c < 0;
    } else if (c > best) {
      best = c, best_lag = k * dt;
    } else if (std::isfinite(best_lag) && c < previous && c < best - 0.05) {
      break;  // past the first peak
    }
    previous = c;
  }
  return best_lag;
}

// The amplitude of the sinusoid of frequency hz in x (one DFT bin, mean removed).
double Amplitude(const std::vector<double>& x, double dt, double hz) {
  const double mean = Mean(x), w = 2 * kPi * hz * dt;
  double re = 0, im = 0;
  for (std::size_t i = 0; i < x.size(); ++i) re += (x[i] - mean) * std::cos(w * i), im -= (x[i] - mean) * std::sin(w * i);
  return 2 * std::hypot(re, im) / x.size();
}

// The rms of x's content (mean removed) in each band between consecutive edges_hz ([e0, e1], (e1, e2], ...): the
// Hann-windowed periodogram summed over the band (Parseval), one spectrum for all. The band's edge is sharp where a
// moving average's side lobes pass a stick-slip cycle's harmonics: on rec10's fit window the surface torque's 2-10 Hz
// content was 0.246 kN m in the model against 0.054 recorded (the Kelvin-Voigt damping the model lacked), where a
// 0.5-s moving average's residual read 0.32 against 0.23.
std::vector<double> BandRms(const std::vector<double>& x, double dt, const std::vector<double>& edges_hz) {
  const std::size_t n = x.size();
  // Zero-padded to a power of two: the padded periodogram samples the same windowed spectrum more finely, and the
  // FFT of a length with a large prime factor is quadratic (a 47.5-s window at 100 Hz has 4751 samples, a prime:
  // 80 % of diagnose's time went into it).
  std::size_t padded = 1;
  while (padded < n) padded *= 2;
  const double mean = Mean(x);
  std::vector<double> windowed(padded, 0.0);
  double window_power = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = 0.5 - 0.5 * std::cos(2 * kPi * (i + 0.5) / n);
    windowed[i] = w * (x[i] - mean);
    window_power += w * w;
  }
  std::vector<std::complex<double>> spectrum;
  Eigen::FFT<double> fft;
  fft.fwd(spectrum, windowed);
  std::vector<double> rms(edges_hz.size() - 1, 0.0);
  const double bin_hz = 1 / (padded * dt);
  for (std::size_t k = 1; 2 * k < padded; ++k)  // both signs of each frequency; the Nyquist bin is left out
    for (std::size_t b = 0; b + 1 < edges_hz.size(); ++b)
      if ((b == 0 ? k * bin_hz >= edges_hz[b] : k * bin_hz > edges_hz[b]) && k * bin_hz <= edges_hz[b + 1])
        rms[b] += 2 * std::norm(spectrum[k]);
  for (double& r : rms) r = std::sqrt(r / (padded * window_power));
  return rms;
}

// The lag in [0, period) at which the bit speed follows the surface torque most closely.
double Lag(const std::vector<double>& torque, const std::vector<double>& bit, double dt, double period) {
  if (!std::isfinite(period)) return kNaN;
  const std::vector<double> a = Demeaned(torque), b = Demeaned(bit);
  const long stride = std::max(1L, static_cast<long>(0.01 / dt));
  double best = -2, best_lag = kNaN;
  const Correlogram correlation(a, b);
  for (long k = 0; k * dt < period && k < static_cast<long>(a.size()) / 2; k += stride) {
    const double c = correlation.At(k);
    if (c > best) best = c, best_lag = k * dt;
  }
  return best_lag;
}

// The lag in [min_lag, max_lag] at which the weight on bit follows the hook load's fast part most closely, as the
// peak of their negative correlation: a rising weight on bit sends a compression wave up the string that lowers the
// hook load L / c_a later, so without telemetry the weight on bit leads by the axial travel time; a delay of the
// downhole channels adds itself to the lag. Broadband content (the fast part: the slow stick-slip cycle would
// repeat the peak a period later), and lags up to a third of the window (the overlap stays two thirds of it). NaN
// where the peak correlation stays below min_correlation.
double AxialLag(const std::vector<double>& hook_fast, const std::vector<double>& wob_fast, double dt, double min_lag,
                double max_lag, double min_correlation) {
  const std::vector<double> a = Demeaned(hook_fast), b = Demeaned(wob_fast);
  const long n = static_cast<long>(a.size());
  const long lo = static_cast<long>(std::ceil(min_lag / dt)), hi = std::min(static_cast<long>(max_lag / dt), n / 3);
  double best = -2, best_lag = kNaN;
  const Correlogram correlation(a, b);
  for (long k = std::max(lo, -n / 3); k <= hi; ++k) {
    const double c = -correlation.At(k);
    if (c > best) best = c, best_lag = k * dt;
  }
  return best >= min_correlation ? best_lag : kNaN;
}

// The strength of a channel's fast motion: the rms of its fast part over envelope_window_s, less its own moving
// average over envelope_detrend_s (so that a bounce building up over tens of seconds does not correlate everything
// with everything).
std::vector<double> Envelope(const std::vector<double>& fast, double dt, const FeatureOptions& o) {
  std::vector<double> power(fast.size());
  for (std::size_t i = 0; i < fast.size(); ++i) power[i] = fast[i] * fast[i];
  std::vector<double> e = MovingAverage(power, static_cast<int>(std::lround(0.5 * o.envelope_window_s / dt)));
  for (double& v : e) v = std::sqrt(v);
  const std::vector<double> trend = MovingAverage(e, static_cast<int>(std::lround(0.5 * o.envelope_detrend_s / dt)));
  for (std::size_t i = 0; i < e.size(); ++i) e[i] -= trend[i];
  return e;
}

std::map<std::string, double> Measure(const Recording& r, std::size_t first, std::size_t last,
                                      const FeatureOptions& o) {
  std::map<std::string, double> f;
  const double dt = r.sample_interval_s;
  const int smooth_half = static_cast<int>(std::lround(0.5 * o.smoothing_s / dt));
  const int fast_half = static_cast<int>(std::lround(0.5 * o.fast_window_s / dt));
  std::vector<double> bit, top, torque, bit_torque, hook_fast, wob_fast;
  std::vector<std::vector<double>> smoothed;
  for (std::size_t j = 0; j < r.names.size(); ++j) {
    const std::vector<double> raw(r.channels[j].begin() + first, r.channels[j].begin() + last);
    const std::vector<double> x = MovingAverage(raw, smooth_half);
    const std::vector<double> slow = MovingAverage(x, fast_half);
    std::vector<double> fast(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) fast[i] = x[i] - slow[i];
    f[r.names[j] + " mean"] = Mean(raw);
    f[r.names[j] + " std"] = Std(x);
    const FastBands bands = FastBandsOf(o);
    if (r.names[j] == o.top_speed || r.names[j] == o.top_torque) {
      const std::vector<double> halves = BandRms(raw, dt, {bands.low_hz, bands.split_hz, bands.high_hz});
      f[r.names[j] + kFastLow] = halves[0];
      f[r.names[j] + kFastHigh] = halves[1];
    } else {
      f[r.names[j] + kFast] = BandRms(raw, dt, {bands.low_hz, bands.high_hz})[0];
    }
    if (r.names[j] == o.bit_speed) bit = x;
    if (r.names[j] == o.top_speed) top = x;
    if (r.names[j] == o.top_torque) torque = x;
    if (!o.bit_torque.empty() && r.names[j] == o.bit_torque) bit_torque = x;
    if (r.names[j] == o.hook_load) hook_fast = fast;
    if (r.names[j] == o.weight_on_bit) wob_fast = fast;
    smoothed.push_back(x);
  }
  if (!hook_fast.empty() && !wob_fast.empty()) {
    f["hook_to_wob_lag_s"] = AxialLag(hook_fast, wob_fast, dt, o.min_axial_lag_s, o.max_axial_lag_s, o.min_axial_correlation);
    const std::vector<double> hook_envelope = Envelope(hook_fast, dt, o), wob_envelope = Envelope(wob_fast, dt, o);
    const Correlogram envelopes(hook_envelope, wob_envelope);
    for (double lag : o.envelope_lags_s)
      f[EnvelopeCorrelationName(lag)] = envelopes.At(static_cast<long>(std::lround(lag / dt)));
  }
  if (!bit.empty()) {
    double mean_abs = 0;
    for (double v : bit) mean_abs += std::abs(v) / bit.size();
    const double threshold = std::max(o.stuck_floor, o.stuck_fraction * mean_abs);
    double stuck = 0;
    for (double v : bit) stuck += std::abs(v) < threshold ? 1.0 / bit.size() : 0.0;
    f["stick_fraction"] = stuck;
    f["period_s"] = Period(bit, dt, o.max_period_s);
    if (!torque.empty()) f["torque_to_bit_lag_s"] = Lag(torque, bit, dt, f["period_s"]);
    if (!bit_torque.empty()) {
      f[kFrictionSlope] = Slope(bit, bit_torque, [&](std::size_t i) { return bit[i] >= threshold; });
      if (!top.empty()) f[kDriveDroop] = Slope(bit_torque, top, [](std::size_t) { return true; });
    }
    // The line at the bit's mean rotation frequency in every channel: a whirling unbalance forces it.
    const double rotation_hz = Mean(bit) / 60;  // the bit speed in rpm
    for (std::size_t j = 0; j < r.names.size(); ++j)
      f[r.names[j] + " rotation_amplitude"] = Amplitude(smoothed[j], dt, rotation_hz);
  }
  return f;
}

// The floor under each feature's scale: how close a model can be asked to come whatever the spread.
double Floor(const std::string& name, double value, const std::map<std::string, double>& whole, double dt) {
  auto ends_with = [&](const std::string& s) {
    return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
  };
  if (name == "stick_fraction") return 0.03;
  // A period is read to 5 % and to no better than five samples (0.05 s at the synthetic recordings' 100 Hz, 5 ms at
  // the rig's 1 kHz, where the 5 % then rules).
  if (name == "period_s") {
    const double sample = std::round(dt * 1e6) / 1e6;  // the logger's interval, to the microsecond
    return std::max(0.05 * std::abs(value), 5 * sample);
  }
  if (name == "hook_to_wob_lag_s") return 0.1;  // as the torque-to-bit lag's: ten samples
  if (InCorrelogram(name)) return 0.05;  // a correlation: what 400 independent samples resolve
  if (name == "torque_to_bit_lag_s") {
    const auto p = whole.find("period_s");
    return std::max(0.1, p != whole.end() && std::isfinite(p->second) ? 0.05 * p->second : 0.0);
  }
  if (ends_with(" mean")) return std::max(0.02 * std::abs(value), 1e-9);
  // spreads: 10 % of themselves, and at least half a percent of the channel's level (a 1 % noise floor's half)
  const std::string channel = name.substr(0, name.rfind(' '));
  const auto level = whole.find(channel + " mean");
  return std::max({0.1 * std::abs(value), level != whole.end() ? 0.005 * std::abs(level->second) : 0.0, 1e-9});
}

}  // namespace

FastBands FastBandsOf(const FeatureOptions& o) {
  const double low = 1 / o.fast_window_s, high = 0.5 / o.smoothing_s;
  return {low, std::sqrt(low * high), high};
}

std::string EnvelopeCorrelationName(double lag_s) {
  char text[32];
  std::snprintf(text, sizeof text, "%+.1fs", lag_s);
  return kEnvelopeCorrelation + std::string(text);
}

const Feature* FeatureSet::Find(const std::string& name) const {
  for (const Feature& f : features)
    if (f.name == name) return &f;
  return nullptr;
}

double FeatureSet::Value(const std::string& name) const {
  const Feature* f = Find(name);
  return f ? f->value : kNaN;
}

bool FeatureOptions::IsValid(std::string* error) const {
  auto lags_finite = [&] {
    return std::all_of(envelope_lags_s.begin(), envelope_lags_s.end(),
                       [&](double lag) { return FiniteField(error, "envelope_lags_s", lag); });
  };
  return FiniteField(error, "min_axial_lag_s", min_axial_lag_s) &&
         FiniteField(error, "max_axial_lag_s", max_axial_lag_s) &&
         OrderedFields(error, "min_axial_lag_s", min_axial_lag_s, "max_axial_lag_s", max_axial_lag_s,
                       "the lags looked at must end after they begin") &&
         ((min_axial_correlation >= 0 && min_axial_correlation <= 1) ||
          Invalid(error, "min_axial_correlation",
                  "expected a correlation in [0, 1], got " + ReadableNumber(min_axial_correlation))) &&
         lags_finite() && PositiveField(error, "envelope_window_s", envelope_window_s) &&
         PositiveField(error, "envelope_detrend_s", envelope_detrend_s) && WholeField(error, "parts", parts, 1) &&
         PositiveField(error, "smoothing_s", smoothing_s) && PositiveField(error, "fast_window_s", fast_window_s) &&
         OrderedFields(error, "2 smoothing_s", 2 * smoothing_s, "fast_window_s", fast_window_s,
                       "the fast band, from 1 / fast_window_s to 1 / (2 smoothing_s), must have some width") &&
         FractionField(error, "stuck_fraction", stuck_fraction) &&
         NonNegativeField(error, "stuck_floor", stuck_floor) && PositiveField(error, "max_period_s", max_period_s);
}

FeatureSet MeasureFeatures(const Recording& r, double begin_s, double end_s, const FeatureOptions& o) {
  ThrowIfInvalid(o);
  std::size_t first = r.time_s.size(), last = 0;
  for (std::size_t i = 0; i < r.time_s.size(); ++i)
    if (r.time_s[i] >= begin_s && r.time_s[i] <= end_s) first = std::min(first, i), last = i + 1;
  const int parts = o.parts;
  if (first >= last || last - first < static_cast<std::size_t>(8 * parts))
    throw ParameterError("window", "fewer than " + std::to_string(8 * parts) + " samples of " + r.source + " in [" +
                                     ReadableNumber(begin_s) + ", " + ReadableNumber(end_s) + "] s");
  const std::map<std::string, double> whole = Measure(r, first, last, o);
  std::vector<std::map<std::string, double>> part_features;
  const std::size_t n = last - first;
  for (int p = 0; p < parts; ++p)
    part_features.push_back(Measure(r, first + n * p / parts, first + n * (p + 1) / parts, o));

  FeatureSet set;
  set.begin_s = r.time_s[first];
  set.end_s = r.time_s[last - 1];
  for (const auto& [name, value] : whole) {
    std::vector<double> values;
    for (const auto& pf : part_features)
      if (std::isfinite(pf.at(name))) values.push_back(pf.at(name));
    // The spread of a window's feature between two runs of the same physics: the parts' spread times sqrt(2/parts)
    // (a difference of two means over `parts` parts).
    const double spread = values.size() >= 2 ? Std(values) * std::sqrt(2.0 * values.size() / (values.size() - 1) / parts)
                                             : 0.0;
    set.features.push_back({name, value, std::max(spread, Floor(name, value, whole, r.sample_interval_s))});
  }
  return set;
}

namespace {
// Whether the recording's envelopes answer each other clearly enough for their correlogram to be asked of a model.
bool CorrelogramCounts(const FeatureSet& recording) {
  double peak = 0;
  for (const Feature& f : recording.features)
    if (InCorrelogram(f.name) && std::isfinite(f.value)) peak = std::max(peak, std::abs(f.value));
  return peak >= kMinEnvelopeCorrelation;
}
}  // namespace

double FeatureDistance(const FeatureSet& model, const FeatureSet& recording) {
  double sum = 0, correlogram_sum = 0;
  int count = 0, correlogram_count = 0;
  const bool correlogram_counts = CorrelogramCounts(recording);
  for (const Feature& r : recording.features) {
    const double m = model.Value(r.name);
    const bool rf = std::isfinite(r.value), mf = std::isfinite(m);
    if (!rf && !mf) continue;
    const double z = rf && mf ? (m - r.value) / r.scale : 3.0;
    if (InCorrelogram(r.name)) {
      if (correlogram_counts) correlogram_sum += z * z, ++correlogram_count;
      continue;
    }
    // The axial lag is the highest of the correlation's peaks over seconds of lags: a model more than three scales
    // off has picked another peak (a regime of its own), and how far that peak lies says nothing more.
    sum += r.name == "hook_to_wob_lag_s" ? std::min(z * z, 9.0) : z * z;
    ++count;
  }
  // The envelopes' correlogram is one shape read at several lags: it counts as one feature, its lags' mean.
  if (correlogram_count) sum += correlogram_sum / correlogram_count, ++count;
  return count ? sum / count : 0.0;
}

double DistanceDifferenceStd(const FeatureSet& a, const FeatureSet& b, const FeatureSet& recording,
                             double noise_variance) {
  double slopes = 0, correlogram_slope = 0;  // sum of the terms' squared slopes in n; the correlogram's mean |slope|
  int count = 0, correlogram_count = 0;
  const bool correlogram_counts = CorrelogramCounts(recording);
  for (const Feature& r : recording.features) {
    const double va = a.Value(r.name), vb = b.Value(r.name);
    const bool rf = std::isfinite(r.value), af = std::isfinite(va), bf = std::isfinite(vb);
    if (!rf && !af && !bf) continue;
    if (InCorrelogram(r.name)) {
      if (!correlogram_counts) continue;
      ++correlogram_count;
      if (rf && af && bf) correlogram_slope += 2 * std::abs(va - vb) / r.scale;
      continue;
    }
    ++count;
    if (!rf) continue;  // each model's term is 0 or 9 whatever the noise
    // A term held at its cap (a missing value, an axial lag on another peak) is a constant: its slope is 0.
    const bool lag = r.name == "hook_to_wob_lag_s";
    const auto moving = [&](bool finite, double v) {
      const double z = finite ? (v - r.value) / r.scale : 0.0;
      return finite && !(lag && std::abs(z) >= 3.0) ? z : 0.0;
    };
    const double slope = 2 * (moving(af, va) - moving(bf, vb));
    slopes += slope * slope;
  }
  if (correlogram_count) {
    const double slope = correlogram_slope / correlogram_count;
    slopes += slope * slope, ++count;
  }
  return count ? std::sqrt(std::max(noise_variance, 0.0) * slopes) / count : 0.0;
}

double LargestDifferenceInScales(const FeatureSet& a, const FeatureSet& b, const FeatureSet& recording) {
  double largest = 0, correlogram_sum = 0;
  int correlogram_count = 0;
  const bool correlogram_counts = CorrelogramCounts(recording);
  for (const Feature& r : recording.features) {
    const double va = a.Value(r.name), vb = b.Value(r.name);
    const bool af = std::isfinite(va), bf = std::isfinite(vb);
    if (!af && !bf) continue;
    const double d = af && bf ? std::abs(va - vb) / r.scale : 3.0;
    if (InCorrelogram(r.name)) {
      if (correlogram_counts) correlogram_sum += d * d, ++correlogram_count;
      continue;
    }
    largest = std::max(largest, d);
  }
  if (correlogram_count) largest = std::max(largest, std::sqrt(correlogram_sum / correlogram_count));
  return largest;
}

CorrelogramDifference CompareCorrelograms(const FeatureSet& model, const FeatureSet& recording) {
  CorrelogramDifference d{kNaN, kNaN};
  if (!CorrelogramCounts(recording)) return d;
  double sum = 0, largest = -1;
  int count = 0;
  for (const Feature& r : recording.features) {
    const double m = model.Value(r.name);
    if (!InCorrelogram(r.name) || !std::isfinite(r.value) || !std::isfinite(m)) continue;
    const double z = (m - r.value) / r.scale;
    sum += z * z, ++count;
    if (std::abs(z) > largest)
      largest = std::abs(z), d.largest_at_lag_s = std::stod(r.name.substr(std::string(kEnvelopeCorrelation).size()));
  }
  if (count) d.rms_scales = std::sqrt(sum / count);
  return d;
}

double FeatureCount(const FeatureSet& s) {
  double n = 0;
  bool correlogram = false;
  for (const Feature& f : s.features) {
    if (!std::isfinite(f.value)) continue;
    if (InCorrelogram(f.name))
      correlogram = true;
    else
      ++n;
  }
  return n + (correlogram && CorrelogramCounts(s) ? 1 : 0);
}

double OffBottomShare(const Recording& r, double begin_s, double end_s, const FeatureOptions& o) {
  ThrowIfInvalid(o);
  const auto wob = std::find(r.names.begin(), r.names.end(), o.weight_on_bit);
  if (wob == r.names.end()) return kNaN;
  std::vector<double> x;
  for (std::size_t i = 0; i < r.time_s.size(); ++i)
    if (r.time_s[i] >= begin_s && r.time_s[i] <= end_s) x.push_back(r.channels[wob - r.names.begin()][i]);
  if (x.empty()) return kNaN;
  x = MovingAverage(x, static_cast<int>(std::lround(0.5 * o.smoothing_s / r.sample_interval_s)));
  double level = 0;
  for (double v : x) level += std::abs(v) / x.size();
  double off = 0;
  for (double v : x) off += v < kOffBottomLevel * level ? 1.0 / x.size() : 0.0;
  return off;
}

double NoiseStd(const std::vector<double>& x) {
  if (x.size() < 8) return 0;
  std::vector<double> d2(x.size() - 2);
  for (std::size_t i = 0; i + 2 < x.size(); ++i) d2[i] = x[i + 2] - 2 * x[i + 1] + x[i];
  const double median = Median(d2);
  for (double& v : d2) v = std::abs(v - median);
  return 1.4826 * Median(d2) / std::sqrt(6.0);
}

nlohmann::json FeatureSetToJson(const FeatureSet& model, const FeatureSet& recording) {
  nlohmann::json list = nlohmann::json::array();
  for (const Feature& r : recording.features) {
    const double m = model.Value(r.name);
    list.push_back({{"feature", r.name},
                    {"recording", io::FiniteOrNull(r.value)},
                    {"model", io::FiniteOrNull(m)},
                    {"scale", r.scale},
                    {"difference_in_scales", io::FiniteOrNull((m - r.value) / r.scale)}});
  }
  return {{"window_s", {recording.begin_s, recording.end_s}}, {"features", list}};
}

}  // namespace drillwave::diagnosis
