// The wave network against closed-form d'Alembert solutions: a lossless uniform string whose top speed steps from
// 0 to Omega0 at t = 0 (imposed-speed top: reflection -1), with a free bit (reflection +1: a staircase) and with an
// inertial bit (piecewise exponential-polynomial solution built below in closed form).
#include <cmath>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/waves/network_simulation.hpp"

namespace drillwave::waves {
namespace {

constexpr double kOmega0 = 10.0;

Network LosslessString(double bit_inertia) {
  Network net;
  net.sections.push_back(Section::Torsional(1172, 79.3e9, 8000, 1.19e-5));
  Node top;
  top.name = "top";
  top.drive = Drive::kPrescribedSpeed;
  top.setpoint = model::Schedule({{0.0, 0.0}, {0.0, kOmega0}});  // a jump at t = 0
  Node bit;
  bit.name = "bit";
  bit.inertia = bit_inertia;
  net.nodes = {top, bit};
  return net;
}

NetworkRunOptions Tight(double t_end) {
  NetworkRunOptions o;
  o.t_end_s = t_end;
  o.output_interval_s = 1e-3;
  o.integrator.abs_tol = 1e-12;
  o.integrator.rel_tol = 1e-12;
  return o;
}

// Free bit: the step arrives at L/c, doubles on reflection at the free end, and returns to zero after the
// imposed-speed top has reflected it with the opposite sign: 0, 2 Omega0, 0, 2 Omega0, ... changing at odd
// multiples of tau.
TEST(DalembertExact, FreeBitFollowsTheStaircase) {
  const Network net = LosslessString(0.0);
  const double tau = net.sections[0].travel_time_s;
  const NetworkRun run = SimulateNetwork(net, Tight(40 * tau));
  const auto& tr = run.trajectory;
  int checked = 0;
  double worst = 0;
  for (std::size_t i = 0; i < tr.time_s.size(); ++i) {
    const double phase = tr.time_s[i] / tau;
    const double frac = phase - std::floor(phase);
    if (std::abs(frac) < 1e-6 || std::abs(frac - 1) < 1e-6) continue;  // on a jump
    const int k = static_cast<int>(std::floor((phase + 1) / 2));  // which round trip
    const double exact = phase < 1 ? 0.0 : (k % 2 == 1 ? 2 * kOmega0 : 0.0);
    worst = std::max(worst, std::abs(tr.bit_speed_rad_s[i] - exact) / kOmega0);
    ++checked;
  }
  std::cout << "[ measured ] free bit: max relative deviation " << worst << " over " << checked << " samples, "
            << run.stats.steps << " steps\n";
  EXPECT_GT(checked, 1000);
  EXPECT_LT(worst, 1e-8) << "largest relative deviation from the staircase";
  // First arrival exactly at L / c.
  EXPECT_NEAR(tau, 1172 / std::sqrt(79.3e9 / 8000), 1e-15);
}

// exp-polynomial c + sum_j p_j s^j e^{-k s} on one interval of length 2 tau (local time s).
struct ExpPoly {
  double constant = 0;
  std::vector<double> poly;
  double operator()(double s, double k) const {
    double acc = 0, sj = 1;
    for (double p : poly) {
      acc += p * sj;
      sj *= s;
    }
    return constant + acc * std::exp(-k * s);
  }
};

// Inertial bit: I v' = Z (2 D - v), D(t) the down wave at the bit. With the imposed-speed top,
// D_n = Omega0 - v_{n-1} + D_{n-1} on successive intervals of length 2 tau starting at tau, and
// v_n(s) = 2A + e^{-ks} [v_n(0) - 2A + sum_j 2k p_j s^{j+1}/(j+1)] for D_n = A + sum_j p_j s^j e^{-ks}.
TEST(DalembertExact, InertialBitMatchesClosedForm) {
  const double inertia = 89.0;
  const Network net = LosslessString(inertia);
  const double tau = net.sections[0].travel_time_s, z = net.sections[0].impedance, k = z / inertia;
  const int intervals = 8;
  std::vector<ExpPoly> v(intervals), d(intervals);
  for (int n = 0; n < intervals; ++n) {
    ExpPoly dn;
    if (n == 0) {
      dn.constant = kOmega0;
    } else {
      dn.constant = kOmega0 - v[n - 1].constant + d[n - 1].constant;
      dn.poly.assign(std::max(v[n - 1].poly.size(), d[n - 1].poly.size()), 0.0);
      for (std::size_t j = 0; j < v[n - 1].poly.size(); ++j) dn.poly[j] -= v[n - 1].poly[j];
      for (std::size_t j = 0; j < d[n - 1].poly.size(); ++j) dn.poly[j] += d[n - 1].poly[j];
    }
    const double v_start = n == 0 ? 0.0 : v[n - 1](2 * tau, k);
    ExpPoly vn;
    vn.constant = 2 * dn.constant;
    vn.poly.assign(dn.poly.size() + 1, 0.0);
    vn.poly[0] = v_start - 2 * dn.constant;
    for (std::size_t j = 0; j < dn.poly.size(); ++j) vn.poly[j + 1] += 2 * k * dn.poly[j] / (j + 1);
    v[n] = vn;
    d[n] = dn;
  }
  const NetworkRun run = SimulateNetwork(net, Tight(tau + 2 * tau * intervals));
  const auto& tr = run.trajectory;
  double worst = 0;
  for (std::size_t i = 0; i < tr.time_s.size(); ++i) {
    const double t = tr.time_s[i];
    double exact = 0;
    if (t > tau) {
      const int n = std::min(intervals - 1, static_cast<int>((t - tau) / (2 * tau)));
      exact = v[n](t - tau - 2 * tau * n, k);
    }
    worst = std::max(worst, std::abs(tr.bit_speed_rad_s[i] - exact) / kOmega0);
  }
  std::cout << "[ measured ] inertial bit: max relative deviation " << worst << ", " << run.stats.steps << " steps\n";
  EXPECT_LT(worst, 1e-8) << "largest relative deviation from the closed form over " << intervals << " round trips";
}

}  // namespace
}  // namespace drillwave::waves
