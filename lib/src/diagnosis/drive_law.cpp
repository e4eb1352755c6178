#include "drillwave/diagnosis/drive_law.hpp"

#include <algorithm>
#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>
#include <complex>
#include <limits>

#include "drillwave/core/constants.hpp"

namespace drillwave::diagnosis {

double DriveLaw::Stiffness() const {
  const double w = 2 * kPi * frequency_hz;
  return w > 0 ? std::hypot(proportional, integral / w) : std::nan("");
}

double DriveLaw::LogStiffnessStd() const {
  if (segments < 1 || coherence <= 0) return std::numeric_limits<double>::infinity();
  return std::sqrt(std::max(0.0, 1 - coherence)) / (std::sqrt(coherence) * std::sqrt(2.0 * segments));
}

double DriveLaw::Phase() const {
  const double w = 2 * kPi * frequency_hz;
  return w > 0 ? std::atan2(-integral / w, proportional) : std::nan("");
}

DriveLaw IdentifyDriveLaw(const std::vector<double>& time_s, const std::vector<double>& speed_error_rad_s,
                          const std::vector<double>& torque_Nm, double begin_s, double end_s, double segment_s) {
  DriveLaw law;
  if (time_s.size() != speed_error_rad_s.size() || time_s.size() != torque_Nm.size() || time_s.size() < 2) return law;
  std::size_t first = 0, last = 0;  // [first, last)
  while (first < time_s.size() && time_s[first] < begin_s) ++first;
  last = first;
  while (last < time_s.size() && time_s[last] <= end_s) ++last;
  const double dt = (time_s.back() - time_s.front()) / static_cast<double>(time_s.size() - 1);
  if (!(dt > 0)) return law;
  const auto n = static_cast<std::size_t>(std::lround(segment_s / dt));
  if (n < 8 || last - first < 2 * n - n / 2) return law;  // two segments at 50 % overlap

  // The bins of the band, and a table of e^{-2 pi i m / n}: bin k of sample j is entry (k j) mod n.
  const auto k_low = static_cast<std::size_t>(std::ceil(kDriveBandLowHz * n * dt));
  const auto k_high = std::min(n / 2, static_cast<std::size_t>(std::floor(kDriveBandHighHz * n * dt)));
  if (k_low < 1 || k_high < k_low) return law;
  std::vector<std::complex<double>> turn(n);
  std::vector<double> hann(n);
  for (std::size_t j = 0; j < n; ++j) {
    turn[j] = std::polar(1.0, -2 * kPi * static_cast<double>(j) / static_cast<double>(n));
    hann[j] = 0.5 - 0.5 * std::cos(2 * kPi * static_cast<double>(j) / static_cast<double>(n));
  }
  const std::size_t bins = k_high - k_low + 1;
  std::vector<double> s_ee(bins, 0.0), s_tt(bins, 0.0);
  std::vector<std::complex<double>> s_te(bins, 0.0);
  std::vector<double> e(n), t(n);
  for (std::size_t start = first; start + n <= last; start += n / 2) {
    double e_mean = 0, t_mean = 0;
    for (std::size_t j = 0; j < n; ++j) e_mean += speed_error_rad_s[start + j] / n, t_mean += torque_Nm[start + j] / n;
    for (std::size_t j = 0; j < n; ++j)
      e[j] = hann[j] * (speed_error_rad_s[start + j] - e_mean), t[j] = hann[j] * (torque_Nm[start + j] - t_mean);
    for (std::size_t b = 0; b < bins; ++b) {
      const std::size_t k = k_low + b;
      std::complex<double> ek = 0, tk = 0;
      for (std::size_t j = 0; j < n; ++j) {
        const std::complex<double>& z = turn[(k * j) % n];
        ek += e[j] * z, tk += t[j] * z;
      }
      s_ee[b] += std::norm(ek), s_tt[b] += std::norm(tk), s_te[b] += tk * std::conj(ek);
    }
    ++law.segments;
  }
  const std::size_t peak = static_cast<std::size_t>(std::max_element(s_tt.begin(), s_tt.end()) - s_tt.begin());
  if (!(s_ee[peak] > 0 && s_tt[peak] > 0)) return DriveLaw{};
  for (std::size_t b = 0; b < bins; ++b) {
    if (!(s_ee[b] > 0 && s_tt[b] > 0)) continue;
    const double coherence = std::norm(s_te[b]) / (s_ee[b] * s_tt[b]);
    if (coherence >= kMinDriveCoherence)
      law.coherent.push_back(
          {static_cast<double>(k_low + b) / (static_cast<double>(n) * dt), s_te[b] / s_ee[b], coherence});
  }
  const std::complex<double> h = s_te[peak] / s_ee[peak];
  const double w = 2 * kPi * static_cast<double>(k_low + peak) / (static_cast<double>(n) * dt);
  law.frequency_hz = w / (2 * kPi);
  law.proportional = h.real();
  law.integral = -w * h.imag();
  law.coherence = std::norm(s_te[peak]) / (s_ee[peak] * s_tt[peak]);
  return law;
}

namespace {

struct PiFit {
  double proportional = 0, integral = 0, residual = std::numeric_limits<double>::infinity();
};

// The weighted least-squares PI for one lag: H (1 + i w tau) = P - i I / w, each bin's equations scaled by 1 / (|H|
// sigma), so the residual is the sum of squared relative misfits in the bins' own spreads.
PiFit FitPiBehind(const std::vector<DriveLawBin>& bins, const std::vector<double>& sigma, double tau) {
  // The normal equations are diagonal: P from the real parts, I from the imaginary ones.
  double a11 = 0, a22 = 0, b1 = 0, b2 = 0;
  for (std::size_t i = 0; i < bins.size(); ++i) {
    const double w = 2 * kPi * bins[i].frequency_hz, weight = 1 / (std::abs(bins[i].h) * sigma[i]);
    const std::complex<double> target = bins[i].h * std::complex<double>(1, w * tau);
    a11 += weight * weight, b1 += weight * weight * target.real();
    a22 += weight * weight / (w * w), b2 += weight * weight * (-target.imag() / w);
  }
  PiFit fit;
  fit.proportional = b1 / a11, fit.integral = b2 / a22;
  fit.residual = 0;
  for (std::size_t i = 0; i < bins.size(); ++i) {
    const double w = 2 * kPi * bins[i].frequency_hz;
    const std::complex<double> model =
        std::complex<double>(fit.proportional, -fit.integral / w) / std::complex<double>(1, w * tau);
    fit.residual += std::norm((bins[i].h - model) / (std::abs(bins[i].h) * sigma[i]));
  }
  return fit;
}

}  // namespace

LaggedPi FitLaggedPi(const DriveLaw& law, double max_lag_s) {
  LaggedPi out;
  const std::vector<DriveLawBin>& bins = law.coherent;
  if (bins.size() < 3 || law.segments < 2 || !(max_lag_s >= 2e-3)) return out;
  std::vector<double> sigma(bins.size());
  for (std::size_t i = 0; i < bins.size(); ++i)
    sigma[i] = std::sqrt(1 - bins[i].coherence) / (std::sqrt(bins[i].coherence) * std::sqrt(2.0 * law.segments));
  // A bin read without scatter (coherence 1: a noiseless twin) would take every weight: its spread is floored.
  for (double& s : sigma) s = std::max(s, 1e-6);
  constexpr double kStep = 1e-3;
  const int steps = static_cast<int>(std::lround(max_lag_s / kStep));
  std::vector<PiFit> profile;  // the residual with P and I fitted at each lag of the grid
  for (int k = 0; k <= steps; ++k) profile.push_back(FitPiBehind(bins, sigma, kStep * k));
  const PiFit& pi = profile.front();
  const auto at = static_cast<std::size_t>(
      std::min_element(profile.begin(), profile.end(),
                       [](const PiFit& a, const PiFit& b) { return a.residual < b.residual; }) -
      profile.begin());
  const PiFit& best = profile[at];
  out.proportional = best.proportional, out.integral = best.integral, out.lag_s = kStep * static_cast<double>(at);
  out.bins = static_cast<int>(bins.size());
  const double dof = 2.0 * static_cast<double>(bins.size()) - 3;
  // The standard error from the profile's curvature at its minimum (one-sided at a minimum on tau = 0): Var(tau) =
  // 2 s^2 / RSS'' with s^2 = RSS / dof, the residual's own scatter.
  const double curvature =
      at == 0 ? 2 * (profile[1].residual - best.residual) / (kStep * kStep)
      : at + 1 < profile.size()
          ? (profile[at + 1].residual - 2 * best.residual + profile[at - 1].residual) / (kStep * kStep)
          : 0.0;
  out.lag_std_s =
      curvature > 0 ? std::sqrt(2 * (best.residual / dof) / curvature) : std::numeric_limits<double>::infinity();
  const double gain = pi.residual - best.residual;
  if (!(gain > 0)) return out;  // no lag fits better than none
  if (!(best.residual > 0)) {   // a lag that fits exactly
    out.f_statistic = std::numeric_limits<double>::infinity(), out.p_value = 0;
    return out;
  }
  out.f_statistic = gain / (best.residual / dof);
  const boost::math::fisher_f_distribution<double> f(1.0, dof);
  out.p_value = boost::math::cdf(boost::math::complement(f, out.f_statistic));
  return out;
}

}  // namespace drillwave::diagnosis
