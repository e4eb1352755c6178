// The BHA's lateral motion at the bit node (model::JeffcottBha, failure seed eqs. 21-23) in the wave network: at a
// constant bit speed the whirl settles at the closed-form radius, and the torque that keeps the bit turning is what
// the lateral damper dissipates.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/waves/network_simulation.hpp"

namespace drillwave::waves {
namespace {

struct Whirl {
  double radius, largest, bit_speed, top_torque, energy_drift;
};

// A 1000 m string under a dissipative top matched to its impedance (torsional waves leave at the top instead of
// ringing), turning at omega from the start, with a Jeffcott BHA at the bit; means over [20, 25] s.
Whirl SteadyWhirl(const model::JeffcottBha& bha, double omega) {
  Network net;
  net.sections.push_back(Section::Torsional(1000, 79.3e9, 8000, 1.19e-5));
  Node top;
  top.name = "top";
  top.drive = Drive::kSpeedDashpot;
  top.drive_damping = net.sections.front().impedance;
  top.setpoint = model::Schedule(omega);
  Node bit;
  bit.name = "bit";
  bit.inertia = 89;
  bit.lateral = bha;
  net.nodes = {top, bit};
  net.initial.speed_rad_s = omega;
  NetworkRunOptions options;
  options.t_end_s = 25;
  options.output_interval_s = 1e-3;
  options.integrator.abs_tol = options.integrator.rel_tol = 1e-10;
  const NetworkRun run = SimulateNetwork(net, options);
  const NetworkTrajectory& tr = run.trajectory;
  Whirl w{0, 0, 0, 0, 0};
  int n = 0;
  for (std::size_t i = 0; i < tr.time_s.size(); ++i) {
    if (tr.time_s[i] < 20) continue;
    w.radius += tr.lateral_displacement_m[i], w.bit_speed += tr.bit_speed_rad_s[i], w.top_torque += tr.top_torque_nm[i];
    w.largest = std::max(w.largest, tr.lateral_displacement_m[i]);
    ++n;
  }
  w.radius /= n, w.bit_speed /= n, w.top_torque /= n;
  return w;
}

// m e w^2 / sqrt((k - (M + m) w^2)^2 + (c w)^2), written out here (not JeffcottBha::WhirlAmplitude).
double ClosedFormRadius(const model::JeffcottBha& b, double w) {
  const double total = b.mass + b.unbalance_mass;
  return b.unbalance_mass * b.eccentricity * w * w /
         std::sqrt(std::pow(b.stiffness - total * w * w, 2) + std::pow(b.damping * w, 2));
}

TEST(JeffcottBit, SteadyWhirlIsTheClosedFormAndItsDragIsTheTopTorque) {
  model::JeffcottBha bha;
  bha.mass = 5000, bha.stiffness = 1.246e6, bha.damping = 7900, bha.unbalance_mass = 50, bha.eccentricity = 0.05;
  for (double omega : {12.0, 15.70796, 20.0}) {  // below, at and above the lateral natural frequency
    const Whirl w = SteadyWhirl(bha, omega);
    const double r = ClosedFormRadius(bha, w.bit_speed);
    // In steady whirl the damper dissipates c |r'|^2 = c w^2 r^2: the torque c w r^2 on the bit.
    const double drag = bha.damping * w.bit_speed * r * r;
    std::printf("[ measured ] omega %.5f: bit %.6f rad/s, whirl radius %.7g m (largest %.7g) vs closed form %.7g "
                "(%+.2e); top torque %.6g N·m vs c w r^2 = %.6g\n",
                omega, w.bit_speed, w.radius, w.largest, r, w.radius / r - 1, w.top_torque, drag);
    EXPECT_NEAR(w.radius, r, 1e-5 * r);
    EXPECT_NEAR(w.largest, r, 1e-4 * r);
    EXPECT_NEAR(w.top_torque, drag, 1e-4 * drag);
  }
}

// Without an unbalance (m = 0) the lateral BHA stays at rest and the bit turns as without it.
TEST(JeffcottBit, NoUnbalanceNoWhirl) {
  model::JeffcottBha bha;
  bha.mass = 5000, bha.stiffness = 1.246e6, bha.damping = 7900;
  const Whirl w = SteadyWhirl(bha, 12);
  EXPECT_EQ(w.largest, 0.0);
  EXPECT_NEAR(w.bit_speed, 12, 1e-12);
}

}  // namespace
}  // namespace drillwave::waves
