#include "drillwave/estimation/smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "drillwave/recordings/signals.hpp"

namespace drillwave::estimation {

Smoothed SmoothQuadratic(const std::vector<double>& x, double dt, int half_width) {
  const long n = static_cast<long>(x.size()), m = std::max(half_width, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Smoothed s{std::vector<double>(x.size(), nan), std::vector<double>(x.size(), nan), 1, 0};
  if (m == 0) {
    s.value = x;
    for (long i = 1; i + 1 < n; ++i) s.derivative[i] = (x[i + 1] - x[i - 1]) / (2 * dt);
    s.derivative_noise_gain = std::sqrt(0.5) / dt;
    return s;
  }
  // Savitzky-Golay weights of a quadratic at the centre: value c_k = (3(3m^2 + 3m - 1) - 15 k^2) / ((2m+3)(2m+1)(2m-1)),
  // slope d_k = k / sum k^2 (the quadratic term does not enter the centre's slope).
  const double md = static_cast<double>(m);
  const double norm = (2 * md + 3) * (2 * md + 1) * (2 * md - 1) / 3.0;
  double sum_k2 = 0, gain2 = 0;
  std::vector<double> c(2 * m + 1), d(2 * m + 1);
  for (long k = -m; k <= m; ++k) sum_k2 += static_cast<double>(k * k);
  for (long k = -m; k <= m; ++k) {
    c[k + m] = (3 * md * md + 3 * md - 1 - 5 * static_cast<double>(k * k)) / norm;
    d[k + m] = static_cast<double>(k) / (sum_k2 * dt);
    gain2 += c[k + m] * c[k + m];
  }
  s.noise_gain = std::sqrt(gain2);
  s.derivative_noise_gain = 1 / (dt * std::sqrt(sum_k2));
  for (long i = m; i + m < n; ++i) {
    double v = 0, dv = 0;
    for (long k = -m; k <= m; ++k) {
      v += c[k + m] * x[i + k];
      dv += d[k + m] * x[i + k];
    }
    s.value[i] = v;  // NaN in the window stays NaN
    s.derivative[i] = dv;
  }
  return s;
}

Smoothed SmoothPolynomial(const std::vector<double>& x, double dt, int half_width, int order) {
  const long n = static_cast<long>(x.size()), m = std::max(half_width, 1);
  const int p = std::clamp(order, 1, static_cast<int>(2 * m));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Smoothed s{std::vector<double>(x.size(), nan), std::vector<double>(x.size(), nan), 1, 0};
  // The centre's value and slope are the first two rows of the least-squares fit's pseudo-inverse.
  Eigen::MatrixXd vandermonde(2 * m + 1, p + 1);
  for (long k = -m; k <= m; ++k)
    for (int j = 0; j <= p; ++j) vandermonde(k + m, j) = std::pow(static_cast<double>(k), j);
  const Eigen::MatrixXd fit = vandermonde.completeOrthogonalDecomposition().pseudoInverse();
  const Eigen::VectorXd c = fit.row(0).transpose(), d = fit.row(1).transpose() / dt;
  s.noise_gain = c.norm();
  s.derivative_noise_gain = d.norm();
  for (long i = m; i + m < n; ++i) {
    double v = 0, dv = 0;
    for (long k = -m; k <= m; ++k) {
      v += c[k + m] * x[i + k];
      dv += d[k + m] * x[i + k];
    }
    s.value[i] = v;
    s.derivative[i] = dv;
  }
  return s;
}

double NoiseStd(const std::vector<double>& x) {
  std::vector<double> d;
  for (std::size_t i = 1; i < x.size(); ++i)
    if (std::isfinite(x[i]) && std::isfinite(x[i - 1])) d.push_back(std::abs(x[i] - x[i - 1]));
  if (d.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(d.begin(), d.begin() + static_cast<long>(d.size() / 2), d.end());
  return 1.4826 * d[d.size() / 2] / std::sqrt(2.0);
}

double MedianAbs(const std::vector<double>& x) {
  std::vector<double> a;
  for (double v : x)
    if (std::isfinite(v)) a.push_back(std::abs(v));
  return a.empty() ? 0.0 : recordings::Median(a);
}

}  // namespace drillwave::estimation
