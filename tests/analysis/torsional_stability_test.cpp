// Linearized stability of the saldivar string (one section, dissipative top, Stribeck bit) against direct
// simulation: the rightmost characteristic root's real part must equal the growth rate of a small perturbation of
// the steady sliding state in the wave-network engine, on both sides of the Hopf point.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/analysis/torsional_linearization.hpp"
#include "drillwave/waves/network_simulation.hpp"

namespace drillwave::analysis {
namespace {

waves::Network SaldivarString(double top_speed) {
  waves::Network net;
  net.sections.push_back(waves::Section::Torsional(1172, 79.3e9, 8000, 1.19e-5));
  waves::Node top;
  top.drive = waves::Drive::kSpeedDashpot;
  top.drive_damping = 2000;
  top.setpoint = model::Schedule(top_speed);
  waves::Node bit;
  bit.inertia = 89;
  bit.friction = bitrock::FrictionLaw(bitrock::Stribeck{97347, 0.155575, 0.5, 0.8, 0.9, 1.0, 0.03});
  net.nodes = {top, bit};
  return net;
}

// Growth rate of |w_bit - w0| from its successive local maxima in [t0, t1] (least-squares slope of their logs).
double MeasuredGrowthRate(double top_speed, double w0, double kick, double t0, double t1) {
  waves::Network net = SaldivarString(top_speed);
  net.initial.speed_rad_s = w0 + kick;  // rigid rotation off the equilibrium: excites every mode
  waves::NetworkRunOptions options;
  options.t_end_s = t1;
  options.output_interval_s = 1e-3;
  options.integrator.abs_tol = options.integrator.rel_tol = 1e-11;
  const waves::NetworkRun run = waves::SimulateNetwork(net, options);
  const auto& t = run.trajectory.time_s;
  const auto& w = run.trajectory.bit_speed_rad_s;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 1; i + 1 < t.size(); ++i) {
    const double a = std::abs(w[i - 1] - w0), b = std::abs(w[i] - w0), c = std::abs(w[i + 1] - w0);
    if (t[i] < t0 || !(b > a && b >= c)) continue;
    sx += t[i], sy += std::log(b), sxx += t[i] * t[i], sxy += t[i] * std::log(b);
    ++n;
  }
  EXPECT_GE(n, 10);
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

TEST(TorsionalStability, RightmostRootIsTheGrowthRateOfTheSimulatedString) {
  for (double top_speed : {8.0, 9.0}) {
    const waves::Network net = SaldivarString(top_speed);
    const auto points = SteadySlidingStates(net, top_speed);
    ASSERT_EQ(points.size(), 1u);
    const TorsionalOperatingPoint& p = points[0];
    // The steady state balances the top's dashpot against the bit: beta (Omega - w0) = T(w0).
    EXPECT_NEAR(2000 * (top_speed - p.bit_speed_rad_s), p.bit_torque_Nm, 1e-9 * p.bit_torque_Nm);
    const Spectrum sp = ComputeSpectrum(LinearizeTorsionalString(net, p));
    const double predicted = sp.spectral_abscissa;
    const double measured = MeasuredGrowthRate(top_speed, p.bit_speed_rad_s, 1e-3, 15, 60);
    std::printf("[ measured ] Omega = %g rad/s: w0 = %.6f rad/s, dT/dw = %.3f N m s; rightmost root %.5f%+.5fi, "
                "essential %.5f; simulated growth rate %.5f 1/s\n", top_speed, p.bit_speed_rad_s,
                p.torque_slope_Nms_per_rad, predicted, sp.roots[0].s.imag(), sp.essential_abscissa, measured);
    EXPECT_NEAR(measured, predicted, 0.01 * std::abs(predicted) + 1e-3);
    EXPECT_EQ(sp.stable, top_speed > 8.5);
  }
}

// The Hopf point of the steady sliding state, by bisection on the spectral abscissa, lies where the simulated
// perturbation turns from decaying to growing; the root chain of the neutral difference operator stays at
// ln|U| / (2 tau) throughout (U = (beta - Z)/(beta + Z)).
TEST(TorsionalStability, HopfPointOfTheSaldivarString) {
  auto abscissa = [](double top_speed) {
    const waves::Network net = SaldivarString(top_speed);
    return ComputeSpectrum(LinearizeTorsionalString(net, SteadySlidingStates(net, top_speed).back()));
  };
  double lo = 7, hi = 10;
  for (int i = 0; i < 50; ++i) (abscissa(0.5 * (lo + hi)).spectral_abscissa > 0 ? lo : hi) = 0.5 * (lo + hi);
  const Spectrum at_hopf = abscissa(hi);
  const double z = waves::Section::Torsional(1172, 79.3e9, 8000, 1.19e-5).impedance;
  const double tau = waves::Section::Torsional(1172, 79.3e9, 8000, 1.19e-5).travel_time_s;
  std::printf("[ measured ] saldivar string: steady sliding loses stability below Omega = %.6f rad/s (frequency "
              "%.5f rad/s); essential abscissa %.6f\n", hi, at_hopf.roots[0].s.imag(), at_hopf.essential_abscissa);
  EXPECT_NEAR(at_hopf.essential_abscissa, std::log((2000 - z) / (2000 + z)) / (2 * tau), 1e-12);
  EXPECT_GT(hi, 8.0);
  EXPECT_LT(hi, 9.0);
  // Just above: decays in simulation; just below: grows.
  const double above = hi * 1.02, below = hi * 0.98;
  const double w_above = SteadySlidingStates(SaldivarString(above), above).back().bit_speed_rad_s;
  const double w_below = SteadySlidingStates(SaldivarString(below), below).back().bit_speed_rad_s;
  EXPECT_LT(MeasuredGrowthRate(above, w_above, 1e-3, 15, 60), 0);
  EXPECT_GT(MeasuredGrowthRate(below, w_below, 1e-3, 15, 60), 0);
}

}  // namespace
}  // namespace drillwave::analysis
