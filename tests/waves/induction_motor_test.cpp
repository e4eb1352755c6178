// An induction motor at the top of the string (chapter eqs. 2.18-2.19, written in the supply frame): its steady
// states against the per-phase equivalent circuit, which the simulator never uses.
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "drillwave/waves/network_simulation.hpp"
#include "equivalent_circuit.hpp"

namespace drillwave::waves {
namespace {

using testing::CircuitPoint;
using testing::EquivalentCircuit;
constexpr double kC = 300;     // bit damper [N·m·s/rad], about the pipe's impedance: it absorbs the waves
constexpr double kRatio = 8;   // gear: motor turns per string turn
constexpr double kTwoPi = 6.283185307179586;

// The string speed where the motor's torque-speed curve, through the gear, meets the damper's load line c w:
// bisection between the pull-out region and synchronous speed, where the curve falls steeply through the line.
double OperatingSpeed(const model::InductionMotor& m, double f) {
  const double w_sync = kTwoPi * f / m.pole_pairs / kRatio;
  auto excess = [&](double w) { return kRatio * EquivalentCircuit(m, f, kRatio * w).torque - kC * w; };
  EXPECT_GT(excess(0.9 * w_sync), 0);
  return testing::Bisect(excess, 0.9 * w_sync, w_sync * (1 - 1e-12));
}

Network MotorString(const model::InductionMotor& machine, const model::Schedule& supply_hz) {
  Network net;
  net.sections.push_back(Section::Torsional(1172, 79.3e9, 8000, 1.19e-5));
  Node top;
  top.name = "top";
  top.inertia = 500;
  top.drive = Drive::kInductionMotor;
  top.induction = machine;
  top.gear.ratio = kRatio;
  top.gear.motor_inertia = 10;  // rigid gear: 640 kg m^2 more at the top
  top.setpoint = supply_hz;
  Node bit;
  bit.name = "bit";
  bit.ground_damping = kC;
  net.nodes = {top, bit};
  return net;
}

NetworkRun Settle(const Network& net, double t_end) {
  NetworkRunOptions o;
  o.t_end_s = t_end;
  o.output_interval_s = 0.5;
  o.integrator.abs_tol = o.integrator.rel_tol = 1e-10;
  return SimulateNetwork(net, o);
}

// The model's own steady state (fluxes that hold still) has the circuit's torque at every slip, motoring and
// generating: the supply-frame two-axis equations and the phasor circuit are two forms of one machine.
TEST(InductionMotor, SteadyFluxesGiveTheEquivalentCircuitTorque) {
  const model::InductionMotor m = testing::IllustrativeMachine();
  for (double f : {5.0, 30.0, 60.0})
    for (double slip : {-0.2, -0.01, 0.003, 0.05, 0.3, 1.0}) {
      const double w = (1 - slip) * kTwoPi * f / m.pole_pairs;
      const auto psi = m.SteadyFluxes(f, w);
      for (double rate : m.FluxRates(psi, f, w)) EXPECT_NEAR(rate, 0, 1e-12 * 690);
      const CircuitPoint c = EquivalentCircuit(m, f, w);
      EXPECT_NEAR(m.Torque(psi), c.torque, 1e-9 * std::abs(c.torque)) << f << " Hz, slip " << slip;
      EXPECT_NEAR(m.StatorCurrentRms(psi), c.stator_current, 1e-9 * c.stator_current);
    }
}

// The supply frequency that gives a torque at a speed, motoring and generating: the circuit's torque there.
TEST(InductionMotor, SteadySupplyFrequencyGivesTheAskedTorque) {
  const model::InductionMotor m = testing::IllustrativeMachine();
  const double w = 100;
  for (double torque : {-3000.0, 500.0, 4000.0})
    EXPECT_NEAR(EquivalentCircuit(m, m.SteadySupplyFrequency(torque, w), w).torque, torque, 1e-9 * 4000) << torque;
  EXPECT_NEAR(m.SteadySupplyFrequency(0, w), m.pole_pairs * w / kTwoPi, 1e-12);  // no torque: synchronous
  EXPECT_THROW(m.SteadySupplyFrequency(1e6, 100), std::domain_error);  // beyond the pull-out torque
}

// Started at rest at 30 Hz, the string settles where the torque-speed curve meets the load line.
TEST(InductionMotor, SettlesWhereTheTorqueSpeedCurveMeetsTheLoadLine) {
  const model::InductionMotor m = testing::IllustrativeMachine();
  const double f = 30;
  const NetworkRun run = Settle(MotorString(m, model::Schedule(f)), 60);
  const double w = OperatingSpeed(m, f);
  const CircuitPoint c = EquivalentCircuit(m, f, kRatio * w);
  const auto& tr = run.trajectory;
  std::cout << "[ measured ] " << f << " Hz: top " << tr.top_speed_rad_s.back() << " rad/s, bit " << tr.bit_speed_rad_s.back()
            << " rad/s, stator " << tr.top_current_a.back() << " A rms (equivalent circuit: " << w << " rad/s, slip "
            << 1 - kRatio * w * m.pole_pairs / (kTwoPi * f) << ", " << c.stator_current << " A)\n";
  EXPECT_NEAR(tr.top_speed_rad_s.back(), w, 1e-6 * w);
  EXPECT_NEAR(tr.bit_speed_rad_s.back(), w, 1e-6 * w);
  EXPECT_NEAR(tr.top_torque_nm.back(), kC * w, 1e-6 * kC * w);
  EXPECT_NEAR(tr.top_current_a.back(), c.stator_current, 1e-6 * c.stator_current);
}

// A supply ramp into the voltage limit: above 50 Hz the line voltage stays at 575 V (field weakening), and the speed
// follows the circuit with the limited voltage.
TEST(InductionMotor, VoltageLimitWeakensTheFieldAboveTheBaseFrequency) {
  model::InductionMotor m = testing::IllustrativeMachine();
  m.voltage_limit = 575;
  const double f = 70;
  const NetworkRun run = Settle(MotorString(m, model::Schedule({{0.0, 0.0}, {10.0, f}})), 60);
  const double w = OperatingSpeed(m, f);
  EXPECT_NEAR(run.trajectory.top_speed_rad_s.back(), w, 1e-6 * w);
  model::InductionMotor unlimited = testing::IllustrativeMachine();
  EXPECT_GT(std::abs(OperatingSpeed(unlimited, f) - w), 1e-4 * w);  // the limit matters at this point
}

// Under the speed controller (a torque demand to a slip-compensating V/f drive) the string turns at the set-point,
// and the motor sits on its torque-speed curve where it carries the load c Omega: the supply frequency and stator
// current are the equivalent circuit's there. Started at rest, and started turning at the set-point (then held).
TEST(InductionMotor, SpeedControllerHoldsTheSetpointOnTheTorqueSpeedCurve) {
  const model::InductionMotor m = testing::IllustrativeMachine();
  const double omega = 10, shaft = kRatio * omega;
  const double synchronous_hz = m.pole_pairs * shaft / kTwoPi;
  const double f = testing::Bisect(
      [&](double hz) { return kC * omega / kRatio - EquivalentCircuit(m, hz, shaft).torque; }, synchronous_hz * (1 + 1e-12),
      synchronous_hz + 1);
  const double current = EquivalentCircuit(m, f, shaft).stator_current;
  for (double start : {0.0, omega}) {
    Network net = MotorString(m, model::Schedule(omega));
    net.nodes.front().drive = Drive::kInductionMotorSpeed;
    net.nodes.front().pi.kp = 2000, net.nodes.front().pi.ki = 1000;
    net.initial.speed_rad_s = start;
    const NetworkRun run = Settle(net, start == 0 ? 200 : 5);
    const auto& tr = run.trajectory;
    double drift = 0;
    for (double v : tr.top_speed_rad_s) drift = std::max(drift, std::abs(v - omega));
    std::cout << "[ measured ] from " << start << " rad/s: top " << tr.top_speed_rad_s.back() << " rad/s, stator "
              << tr.top_current_a.back() << " A (circuit at " << f << " Hz: " << current << " A)"
              << (start > 0 ? ", largest drift " : "") << (start > 0 ? std::to_string(drift) : "") << "\n";
    EXPECT_NEAR(tr.top_speed_rad_s.back(), omega, 1e-6 * omega);
    EXPECT_NEAR(tr.top_current_a.back(), current, 1e-6 * current);
    if (start > 0) {
      EXPECT_LT(drift, 1e-7 * omega);
    }
  }
}

}  // namespace
}  // namespace drillwave::waves
