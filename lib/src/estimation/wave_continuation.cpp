#include "drillwave/estimation/wave_continuation.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace drillwave::estimation {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double UniformSpacing(const std::vector<double>& t) {
  if (t.size() < 4) throw std::invalid_argument("wave continuation: fewer than 4 samples");
  const double dt = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
  for (std::size_t i = 1; i < t.size(); ++i)
    if (std::abs(t[i] - t[i - 1] - dt) > 1e-6 * dt + 1e-9 * std::abs(t[i]))
      throw std::invalid_argument("wave continuation: the time grid is not uniform");
  return dt;
}

}  // namespace

std::vector<double> Shifted(const std::vector<double>& x, double dt, double shift_s) {
  const long n = static_cast<long>(x.size());
  std::vector<double> y(x.size(), kNaN);
  const double offset = shift_s / dt;
  const long whole = static_cast<long>(std::floor(offset));
  const double u = offset - static_cast<double>(whole);
  for (long i = 0; i < n; ++i) {
    const long j = i + whole;  // x(t_i + shift) lies between x[j] and x[j + 1]
    if (j < 0 || j >= n || (u > 0 && j + 1 >= n)) continue;
    if (u == 0) {
      y[i] = x[j];
      continue;
    }
    // Catmull-Rom with the end points repeated at the span's edges.
    const double p0 = x[j > 0 ? j - 1 : j], p1 = x[j], p2 = x[j + 1], p3 = x[j + 2 < n ? j + 2 : j + 1];
    y[i] = p1 + 0.5 * u * (p2 - p0 + u * (2 * p0 - 5 * p1 + 4 * p2 - p3 + u * (3 * (p1 - p2) + p3 - p0)));
  }
  return y;
}

double TravelTime(const std::vector<WavePiece>& pieces) {
  double tau = 0;
  for (const WavePiece& p : pieces) tau += p.travel_time_s;
  return tau;
}

WaveEnd ContinueDownward(const std::vector<double>& time_s, const std::vector<double>& top_velocity,
                         const std::vector<double>& top_force, const std::vector<WavePiece>& pieces) {
  if (top_velocity.size() != time_s.size() || top_force.size() != time_s.size())
    throw std::invalid_argument("wave continuation: series of different lengths");
  const double dt = UniformSpacing(time_s);
  std::vector<double> v = top_velocity, f = top_force;
  const std::size_t n = v.size();
  // Half a piece: the node's waves split, the down-going one from earlier, the up-going one from later.
  auto half = [&](double impedance, double delay) {
    std::vector<double> down(n), up(n);
    for (std::size_t i = 0; i < n; ++i) {
      down[i] = 0.5 * (v[i] + f[i] / impedance);
      up[i] = 0.5 * (v[i] - f[i] / impedance);
    }
    const std::vector<double> d = Shifted(down, dt, -delay), u = Shifted(up, dt, delay);
    for (std::size_t i = 0; i < n; ++i) {
      v[i] = d[i] + u[i];
      f[i] = impedance * (d[i] - u[i]);
    }
  };
  for (const WavePiece& p : pieces) {
    if (!(p.impedance > 0) || !(p.travel_time_s > 0) || !(p.shunt_damping >= 0))
      throw std::invalid_argument("wave continuation: a piece needs impedance > 0, travel time > 0, damping >= 0");
    half(p.impedance, 0.5 * p.travel_time_s);
    // The dashpot to the hole takes c v of the force carried down (a massless node).
    for (std::size_t i = 0; i < n; ++i) f[i] -= p.shunt_damping * v[i];
    half(p.impedance, 0.5 * p.travel_time_s);
  }
  return {v, f};
}

}  // namespace drillwave::estimation
