// The rig's two-mass top: motor (rotary-table) inertia behind a compliant gear, top-drive inertia at the string.
// With a bit damper equal to the pipe's impedance the string absorbs every wave, so the top sees a dashpot Z and the
// top is a linear three-state system whose exact solution and natural frequency are known.
#include <cmath>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/core/constants.hpp"
#include "drillwave/waves/network_simulation.hpp"
#include "two_mass_reference.hpp"

namespace drillwave::waves {
namespace {

constexpr double kTopInertia = 500, kMotorInertia = 10, kRatio = 8;  // kg m^2, kg m^2 on the motor shaft, turns
constexpr double kStiffness = 3e5, kGearDamping = 20;                 // on the top drive's side

Network RigString(double kp, double ki, double setpoint, double initial_speed) {
  Network net;
  net.sections.push_back(Section::Torsional(1172, 79.3e9, 8000, 1.19e-5));
  Node top;
  top.name = "top";
  top.inertia = kTopInertia;
  top.drive = Drive::kPiSpeedController;
  top.pi.kp = kp, top.pi.ki = ki;
  top.setpoint = model::Schedule(setpoint);
  top.gear = {kRatio, kStiffness, kGearDamping, kMotorInertia};
  Node bit;
  bit.name = "bit";
  bit.ground_damping = net.sections.front().impedance;  // matched: no wave comes back up
  net.nodes = {top, bit};
  net.initial.speed_rad_s = initial_speed;
  return net;
}

NetworkRun Simulate(const Network& net, double t_end, double interval) {
  NetworkRunOptions o;
  o.t_end_s = t_end;
  o.output_interval_s = interval;
  o.integrator.abs_tol = o.integrator.rel_tol = 1e-10;
  return SimulateNetwork(net, o);
}

// Turning at 10 rad/s with the gear wound up to carry Z w, the motor loses its torque at t = 0 (PI gains 0): the
// top's speed, the motor's and the gear torque follow exp(A t) of the three-state system to the tolerance, and the
// oscillation's zero crossings are those of its complex eigenvalues, near sqrt(k (1/J_m' + 1/J)) of the two masses.
TEST(RigTwoMass, FreeMotionIsTheExactSolutionOfTheTwoMassSystemOnADashpot) {
  const double w0 = 10;
  const Network net = RigString(0, 0, 0, w0);
  const double z = net.sections.front().impedance;
  const NetworkRun run = Simulate(net, 3, 1e-4);
  const testing::TwoMassOnDashpot rig{kRatio * kRatio * kMotorInertia, kStiffness, kGearDamping, kTopInertia, z};
  const Eigen::Vector3d y0(w0, z * w0 / kStiffness, w0);
  const auto& tr = run.trajectory;
  double worst = 0;
  for (std::size_t n = 0; n < tr.time_s.size(); ++n) {
    const Eigen::Vector3d y = rig.Response(tr.time_s[n], y0, 0.0);
    worst = std::max({worst, std::abs(tr.top_speed_rad_s[n] - y(2)), std::abs(tr.motor_speed_rad_s[n] / kRatio - y(0)),
                      std::abs(tr.gear_torque_nm[n] - rig.GearTorque(y)) / z});
  }
  // Zero crossings of the relative acceleration (central differences of w_m' - w over 0.1 ms samples, linear
  // interpolation between them): a damped sinusoid's crossings are pi / w_d apart, and differentiating scales the
  // slow rigid-body mode (|lambda| = 0.26 / s), which would shift the crossings of the speed itself by 2e-4, down
  // by |lambda| / w_d.
  std::vector<double> relative_acceleration(tr.time_s.size(), 0.0), crossings;
  for (std::size_t n = 1; n + 1 < tr.time_s.size(); ++n)
    relative_acceleration[n] = (tr.motor_speed_rad_s[n + 1] / kRatio - tr.top_speed_rad_s[n + 1] -
                                tr.motor_speed_rad_s[n - 1] / kRatio + tr.top_speed_rad_s[n - 1]) / 2e-4;
  for (std::size_t n = 2; n + 1 < tr.time_s.size(); ++n) {
    const double r0 = relative_acceleration[n - 1], r1 = relative_acceleration[n];
    if ((r0 < 0) != (r1 < 0)) crossings.push_back(tr.time_s[n - 1] + 1e-4 * r0 / (r0 - r1));
  }
  ASSERT_GE(crossings.size(), 11u);
  const double measured = kPi * (crossings.size() - 1) / (crossings.back() - crossings.front());
  const double damped = rig.DampedFrequency(), undamped = rig.UndampedFrequency();
  std::cout << "[ measured ] largest deviation from exp(A t): " << worst << " rad/s; two-mass mode " << measured
            << " rad/s (eigenvalue " << damped << ", undamped closed form " << undamped << ")\n";
  EXPECT_LT(worst, 1e-7 * w0);
  EXPECT_NEAR(measured, damped, 1e-5 * damped);
  EXPECT_NEAR(damped, undamped, 2e-3 * undamped);  // the dashpot Z and the gear damping shift it slightly
}

// Under the PI on the motor's speed the string turns at the set-point; the gear carries the load torque with the
// twist Z w / k, and the motor turns ratio times faster.
TEST(RigTwoMass, SpeedControllerHoldsTheSetpointThroughTheGear) {
  const double omega = 10;
  const Network net = RigString(2000, 1000, omega, 0);
  const double load = net.sections.front().impedance * omega;
  const NetworkRun run = Simulate(net, 60, 0.5);
  const auto& tr = run.trajectory;
  EXPECT_NEAR(tr.top_speed_rad_s.back(), omega, 1e-6 * omega);
  EXPECT_NEAR(tr.bit_speed_rad_s.back(), omega, 1e-6 * omega);
  EXPECT_NEAR(tr.motor_speed_rad_s.back(), kRatio * omega, 1e-6 * kRatio * omega);
  EXPECT_NEAR(tr.gear_torque_nm.back(), load, 1e-6 * load);
}

// A rigid gear puts ratio^2 J_m on the top: the same run as a top of that inertia without a gear.
TEST(RigTwoMass, RigidGearAddsTheReferredMotorInertia) {
  Network geared = RigString(2000, 1000, 10, 0);
  geared.nodes.front().gear.stiffness = 0;
  Network plain = geared;
  plain.nodes.front().gear = model::Gear{};
  plain.nodes.front().inertia = kTopInertia + kRatio * kRatio * kMotorInertia;
  const NetworkRun a = Simulate(geared, 5, 0.05), b = Simulate(plain, 5, 0.05);
  ASSERT_EQ(a.trajectory.top_speed_rad_s.size(), b.trajectory.top_speed_rad_s.size());
  for (std::size_t n = 0; n < a.trajectory.top_speed_rad_s.size(); ++n)
    EXPECT_DOUBLE_EQ(a.trajectory.top_speed_rad_s[n], b.trajectory.top_speed_rad_s[n]);
}

// A DC motor of constant K behind a rigid gear of ratio n is a motor of constant n K (torque n K I, back-emf n K w)
// on a top heavier by n^2 J_m: the same run, under the speed controller in volts through a set-point ramp.
TEST(RigTwoMass, RigidGearRefersADcMotorToTheTop) {
  Network geared = RigString(0, 0, 10, 10);
  Node& top = geared.nodes.front();
  top.drive = Drive::kDcMotorSpeed;
  top.pi.kp = 200, top.pi.ki = 100;  // V s/rad, V/rad
  top.motor = {50, 0.05, 0.005, 0};
  top.setpoint = model::Schedule({{0.5, 10.0}, {1.0, 12.0}});
  top.gear.stiffness = top.gear.damping = 0;
  Network referred = geared;
  referred.nodes.front().gear = model::Gear{};
  referred.nodes.front().motor.motor_constant = 50 * kRatio;
  referred.nodes.front().inertia = kTopInertia + kRatio * kRatio * kMotorInertia;
  const NetworkRun a = Simulate(geared, 5, 0.05), b = Simulate(referred, 5, 0.05);
  ASSERT_EQ(a.trajectory.top_speed_rad_s.size(), b.trajectory.top_speed_rad_s.size());
  for (std::size_t n = 0; n < a.trajectory.top_speed_rad_s.size(); ++n) {
    EXPECT_NEAR(a.trajectory.top_speed_rad_s[n], b.trajectory.top_speed_rad_s[n], 1e-12 * 10);
    EXPECT_NEAR(a.trajectory.top_current_a[n], b.trajectory.top_current_a[n], 1e-9 * (1 + std::abs(b.trajectory.top_current_a[n])));
  }
}

}  // namespace
}  // namespace drillwave::waves
