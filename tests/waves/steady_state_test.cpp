// Steady drilling: with a dissipative top the string turns rigidly at z' = Omega - T(z')/beta (DESIGN.md §1).
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "drillwave/waves/network_simulation.hpp"

namespace drillwave::waves {
namespace {

constexpr double kBeta = 2000, kOmega = 20;

double FinalBitSpeed(const bitrock::FrictionLaw& law) {
  Network net;
  net.sections.push_back(Section::Torsional(1172, 79.3e9, 8000, 1.19e-5));
  Node top;
  top.drive = Drive::kSpeedDashpot;
  top.drive_damping = kBeta;
  top.setpoint = model::Schedule({{0.0, 0.0}, {2.0, kOmega}});
  Node bit;
  bit.inertia = 89;
  bit.friction = law;
  net.nodes = {top, bit};
  NetworkRunOptions options;
  options.t_end_s = 60;
  options.output_interval_s = 0.1;
  options.integrator.abs_tol = options.integrator.rel_tol = 1e-10;
  return SimulateNetwork(net, options).trajectory.bit_speed_rad_s.back();
}

// Root of v = Omega - T(v) / beta by bisection (T increasing on the bracket for these laws).
double SteadySpeed(const bitrock::FrictionLaw& law) {
  double lo = 1e-9, hi = kOmega;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (mid - kOmega + law.SlipTorque(mid) / kBeta > 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(SteadyState, StribeckBitSettlesAtTheBalanceSpeed) {
  const bitrock::FrictionLaw law(bitrock::Stribeck{97347, 0.155575, 0.5, 0.8, 0.9, 1.0, 0.03});
  const double simulated = FinalBitSpeed(law), expected = SteadySpeed(law);
  std::cout << "[ measured ] Stribeck: steady bit speed " << simulated << " vs root " << expected << "\n";
  EXPECT_NEAR(simulated, expected, 1e-6 * expected);
}

TEST(SteadyState, ViscousBitSettlesAtTheClosedForm) {
  const double c = 800;
  const double simulated = FinalBitSpeed(bitrock::FrictionLaw(bitrock::Viscous{c}));
  const double expected = kBeta * kOmega / (kBeta + c);
  std::cout << "[ measured ] viscous: steady bit speed " << simulated << " vs " << expected << "\n";
  EXPECT_NEAR(simulated, expected, 1e-6 * expected);
}

}  // namespace
}  // namespace drillwave::waves
