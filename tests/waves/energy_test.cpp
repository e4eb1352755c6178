// A lossless string keeps its energy: after a torque pulse at an inertial top, nothing is dissipated, so the
// kinetic energy of the end inertias plus the energy of the waves in flight must stay constant over 1000
// reflections. Re-interpolating the waves at every pass would leak or create energy; this test would show it.
#include <algorithm>
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "drillwave/waves/network_simulation.hpp"

namespace drillwave::waves {
namespace {

Network PulsedFreeString(bool with_collars) {
  Network net;
  net.sections.push_back(Section::Torsional(1000, 79.3e9, 8000, 1.19e-5));
  if (with_collars) net.sections.push_back(Section::Torsional(172, 79.3e9, 8000, 8.0e-5));  // an impedance step
  Node top;
  top.name = "top";
  top.inertia = 500;
  top.drive = Drive::kTorque;
  top.setpoint = model::Schedule({{0.0, 0.0}, {0.0, 2000.0}, {0.2, 2000.0}, {0.2, 0.0}});
  Node junction;
  junction.name = "junction";
  Node bit;
  bit.name = "bit";
  bit.inertia = 89;
  net.nodes = {top, junction, bit};
  if (!with_collars) net.nodes = {top, bit};
  return net;
}

// Largest relative change of the stored energy after the pulse, over the given number of round trips.
double EnergyDrift(bool with_collars, double round_trips) {
  const Network net = PulsedFreeString(with_collars);
  double round_trip = 0;
  for (const Section& s : net.sections) round_trip += 2 * s.travel_time_s;
  NetworkRunOptions options;
  options.t_end_s = round_trips * round_trip;
  options.output_interval_s = round_trip / 7.3;
  options.record_energy = true;
  options.integrator.abs_tol = 1e-10;
  options.integrator.rel_tol = 1e-10;
  const NetworkRun run = SimulateNetwork(net, options);
  const auto& tr = run.trajectory;
  double reference = -1, drift = 0;
  for (std::size_t i = 0; i < tr.time_s.size(); ++i) {
    if (tr.time_s[i] < 0.25) continue;
    if (reference < 0) reference = tr.energy_j[i];
    drift = std::max(drift, std::abs(tr.energy_j[i] - reference) / reference);
  }
  std::cout << "[ measured ] " << (with_collars ? "pipe + collars" : "uniform string") << ": energy " << reference
            << " J, largest relative drift " << drift << " over " << round_trips << " round trips ("
            << run.stats.steps << " steps)\n";
  EXPECT_GT(reference, 100.0);  // the pulse did put energy in
  return drift;
}

TEST(WaveEnergy, LosslessStringKeepsItsEnergyOver1000Reflections) {
  EXPECT_LT(EnergyDrift(false, 500), 1e-8);  // 500 round trips: 1000 reflections at each end
}

// With an impedance step every pass splits a wave in two; merged by arrival time their echoes stay few enough to
// follow for as long as with the uniform string.
TEST(WaveEnergy, StringWithCollarsKeepsItsEnergyOver1000Reflections) { EXPECT_LT(EnergyDrift(true, 500), 1e-8); }

// A drive behind a compliant gear stores its motor's kinetic energy and the gear's elastic energy once: turning
// rigidly at the start with nothing to carry, the stored energy is 1/2 (J_top + n^2 J_m + J_bit + rho J L) w^2, and
// with no gains, dampers or friction it stays there. (The motor and the gear were once counted twice.)
TEST(WaveEnergy, MotorBehindACompliantGearIsCountedOnce) {
  Network net;
  net.sections.push_back(Section::Torsional(1000, 79.3e9, 8000, 1.19e-5));
  Node top;
  top.name = "top";
  top.inertia = 500;
  top.drive = Drive::kPiSpeedController;  // kp = ki = 0: no torque
  top.setpoint = model::Schedule(10.0);
  top.gear = {4.0, 2.0e5, 0.0, 30.0};  // ratio, stiffness, damping, motor inertia
  Node bit;
  bit.name = "bit";
  bit.inertia = 89;
  net.nodes = {top, bit};
  net.initial.speed_rad_s = 10;
  NetworkRunOptions options;
  options.t_end_s = 2.0;
  options.output_interval_s = 0.1;
  options.record_energy = true;
  const NetworkRun run = SimulateNetwork(net, options);
  const double expected = 0.5 * (500 + 16 * 30 + 89 + net.sections[0].inertia()) * 10 * 10;
  for (double e : run.trajectory.energy_j) EXPECT_NEAR(e, expected, 1e-9 * expected);
}

}  // namespace
}  // namespace drillwave::waves
