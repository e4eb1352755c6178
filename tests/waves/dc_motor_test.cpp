// A DC motor at the top of the string (chapter eq. 2.15): its steady states in closed form.
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "drillwave/waves/network_simulation.hpp"

namespace drillwave::waves {
namespace {

constexpr double kK = 50, kR = 0.05, kL = 0.005, kC = 300;  // N·m/A, ohm, H, bit damper N·m·s/rad

// 1172 m of pipe between a DC motor top (inertia 500 kg m^2) and a massless bit held back by a damper kC, which
// absorbs the waves (kC is close to the pipe's impedance, 300 N·m·s): an inertial bit would reflect the start's
// high-frequency waves, and so would the motor, whose inductance makes it a spring above R/L = 10 rad/s.
Network MotorString(Drive drive, double setpoint, double voltage_limit = 0) {
  Network net;
  net.sections.push_back(Section::Torsional(1172, 79.3e9, 8000, 1.19e-5));
  Node top;
  top.name = "top";
  top.inertia = 500;
  top.drive = drive;
  top.motor = {kK, kR, kL, voltage_limit};
  top.pi.kp = 200, top.pi.ki = 100;  // V·s/rad, V/rad (speed controller only)
  top.setpoint = model::Schedule({{0.0, setpoint}});
  Node bit;
  bit.name = "bit";
  bit.ground_damping = kC;
  net.nodes = {top, bit};
  return net;
}

NetworkRun Settle(const Network& net) {
  NetworkRunOptions o;
  o.t_end_s = 200;
  o.output_interval_s = 0.5;
  o.integrator.abs_tol = o.integrator.rel_tol = 1e-10;
  return SimulateNetwork(net, o);
}

// Open loop at V0: k I = c w and V0 = R I + k w, so w = k V0 / (k^2 + R c): the motor's torque-speed line meets the
// load line.
TEST(DcMotor, OpenLoopSettlesWhereTheTorqueSpeedLineMeetsTheLoad) {
  const double v0 = 500;
  const NetworkRun run = Settle(MotorString(Drive::kDcMotorVoltage, v0));
  const double w = kK * v0 / (kK * kK + kR * kC), current = kC * w / kK;
  const auto& tr = run.trajectory;
  std::cout << "[ measured ] open loop at " << v0 << " V: top " << tr.top_speed_rad_s.back() << " rad/s, bit "
            << tr.bit_speed_rad_s.back() << " rad/s, current " << tr.top_current_a.back() << " A (closed form " << w
            << " rad/s, " << current << " A)\n";
  EXPECT_NEAR(tr.top_speed_rad_s.back(), w, 1e-6 * w);
  EXPECT_NEAR(tr.bit_speed_rad_s.back(), w, 1e-6 * w);
  EXPECT_NEAR(tr.top_current_a.back(), current, 1e-6 * current);
  EXPECT_NEAR(tr.top_torque_nm.back(), kC * w, 1e-6 * kC * w);  // the string carries the load torque
}

// Under the speed controller the integral removes the speed error: w = setpoint, I = c w / k.
TEST(DcMotor, SpeedControllerHoldsTheSetpoint) {
  const double omega = 10;
  const NetworkRun run = Settle(MotorString(Drive::kDcMotorSpeed, omega));
  const auto& tr = run.trajectory;
  EXPECT_NEAR(tr.top_speed_rad_s.back(), omega, 1e-6 * omega);
  EXPECT_NEAR(tr.bit_speed_rad_s.back(), omega, 1e-6 * omega);
  EXPECT_NEAR(tr.top_current_a.back(), kC * omega / kK, 1e-6 * kC * omega / kK);
}

// A voltage limit below what the set-point needs (R I + k w = 560 V at 10 rad/s) leaves the motor on its
// torque-speed line at the limit.
TEST(DcMotor, VoltageLimitLeavesTheMotorOnItsTorqueSpeedLine) {
  const double limit = 400;
  const NetworkRun run = Settle(MotorString(Drive::kDcMotorSpeed, 10, limit));
  const double w = kK * limit / (kK * kK + kR * kC);
  EXPECT_NEAR(run.trajectory.top_speed_rad_s.back(), w, 1e-6 * w);
}

}  // namespace
}  // namespace drillwave::waves
