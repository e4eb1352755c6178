#include "drillwave/diagnosis/drive_law.hpp"

#include <algorithm>
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
  const std::complex<double> h = s_te[peak] / s_ee[peak];
  const double w = 2 * kPi * static_cast<double>(k_low + peak) / (static_cast<double>(n) * dt);
  law.frequency_hz = w / (2 * kPi);
  law.proportional = h.real();
  law.integral = -w * h.imag();
  law.coherence = std::norm(s_te[peak]) / (s_ee[peak] * s_tt[peak]);
  return law;
}

}  // namespace drillwave::diagnosis
