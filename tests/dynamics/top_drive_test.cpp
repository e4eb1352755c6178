// The drive at a string's end as a component (dynamics::TopDrive): its steady start holds still under its own rates
// for every kind of drive, and puts the steady torque into its node; a DC motor's two speed loops (a PI in volts, a
// PI commanding torque with the set-point's back-emf fed forward) both end on k I = the steady torque.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/dynamics/top_drive.hpp"
#include "equivalent_circuit.hpp"

namespace drillwave::dynamics {
namespace {

using model::Drive;
using Side = integration::Side;
constexpr double kSpeed = 6.0;     // rad/s at the node
constexpr double kTorque = 9.0e3;  // N·m into the node in steady rotation
constexpr int kStates = 12;

struct Bench {
  model::Schedule setpoint{kSpeed};
  model::PiController pi{2.0e4, 5.0e4};
  model::TopDriveLaw law;
  model::InductionMotor induction = testing::IllustrativeMachine();
  TopDriveParts parts;
  TopDrive::Slots slots;

  explicit Bench(Drive drive, bool compliant_gear = false) {
    parts.drive = drive;
    parts.setpoint = &setpoint;
    parts.pi = &pi, parts.law = &law;
    parts.dc = {40.0, 0.05, 0.01, 0.0};  // k referred to the node, R, L
    parts.induction = &induction;
    parts.gear.ratio = TopDrive::HasInductionMotor(drive) ? 8.0 : 1.0;
    if (compliant_gear) parts.gear.stiffness = 4e5, parts.gear.damping = 800, parts.gear.motor_inertia = 12;
    parts.inertia = 900;
    slots.integral = TopDrive::HasSpeedLoop(drive) ? 0 : -1;
    slots.current = TopDrive::HasDcMotor(drive) ? 1 : -1;
    slots.flux = TopDrive::HasInductionMotor(drive) ? 2 : -1;
    slots.motor_speed = compliant_gear ? 6 : -1;
  }
};

// The rates at the steady start (scaled by each state's size) and the torque into the node there.
struct Steady {
  double worst_rate, torque;
};
Steady AtSteadyStart(const Bench& b) {
  const TopDrive drive(b.parts, b.slots, kSpeed, kTorque);
  std::vector<double> x(kStates, 0.0), dx(kStates, 0.0);
  drive.SteadyStart(kTorque, x);
  const auto string_torque = [](double, double) { return kTorque; };
  const auto no_wave = [](double, double) { return PiTopDrive::TopWave{}; };
  const double vd = drive.DriveSpeed(x, kSpeed);
  const TopDrive::Reading in = drive.Read(x, vd, 0.0, Side::kRight, string_torque, no_wave);
  drive.Rates(x, kSpeed, 0.0, Side::kRight, in, dx);
  double worst = 0;
  for (int i = 0; i < kStates; ++i) worst = std::max(worst, std::abs(dx[i]) / (1.0 + std::abs(x[i])));
  return {worst, drive.TorqueIntoNode(x, kSpeed, 0.0, Side::kRight, [&](double) { return in; })};
}

TEST(TopDrive, SteadyStartHoldsStillAndCarriesTheSteadyTorqueForEveryDrive) {
  struct Kind {
    std::string name;
    Bench bench;
  };
  std::vector<Kind> kinds;
  kinds.push_back({"PI", Bench(Drive::kPiSpeedController)});
  kinds.push_back({"PI behind a compliant gear", Bench(Drive::kPiSpeedController, true)});
  kinds.push_back({"DC motor, PI in volts", Bench(Drive::kDcMotorSpeed)});
  kinds.push_back({"DC motor, PI commanding torque", Bench(Drive::kDcMotorSpeed)});
  kinds.back().bench.parts.dc_torque_command = true;
  kinds.push_back({"DC motor, PI in volts, compliant gear", Bench(Drive::kDcMotorSpeed, true)});
  kinds.push_back({"induction motor under a speed loop", Bench(Drive::kInductionMotorSpeed)});
  kinds.push_back({"induction motor under a speed loop, compliant gear", Bench(Drive::kInductionMotorSpeed, true)});
  for (Kind& k : kinds) {
    k.bench.parts.setpoint = &k.bench.setpoint, k.bench.parts.pi = &k.bench.pi, k.bench.parts.law = &k.bench.law;
    k.bench.parts.induction = &k.bench.induction;
    const Steady s = AtSteadyStart(k.bench);
    EXPECT_LT(s.worst_rate, 1e-9) << k.name;
    EXPECT_NEAR(s.torque, kTorque, 1e-9 * kTorque) << k.name;
  }
}

// Open loop, a DC motor holds still on the voltage R T / k + k w, and carries the torque its current gives.
TEST(TopDrive, OpenLoopDcMotorHoldsStillOnItsSteadyVoltage) {
  Bench b(Drive::kDcMotorVoltage);
  b.setpoint = model::Schedule(b.parts.dc.armature_resistance * kTorque / b.parts.dc.motor_constant +
                               b.parts.dc.motor_constant * kSpeed);
  const Steady s = AtSteadyStart(b);
  EXPECT_LT(s.worst_rate, 1e-12);
  EXPECT_NEAR(s.torque, kTorque, 1e-9 * kTorque);
  b.setpoint = model::Schedule(1.01 * (b.parts.dc.armature_resistance * kTorque / b.parts.dc.motor_constant +
                                       b.parts.dc.motor_constant * kSpeed));
  EXPECT_GT(AtSteadyStart(b).worst_rate, 1.0);  // another voltage moves the current at once
}

// A dashpot to its set-point and a scheduled torque act on a massless node through a - b v.
TEST(TopDrive, MasslessBalanceOfADashpotAndOfATorque) {
  Bench dashpot(Drive::kSpeedDashpot);
  dashpot.parts.dashpot = 300;
  dashpot.setpoint = model::Schedule({{0.0, 0.0}, {2.0, 10.0}});
  const TopDrive d(dashpot.parts, dashpot.slots, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(d.MasslessTorque(1.0, Side::kRight), 300 * 5.0);
  EXPECT_DOUBLE_EQ(d.MasslessTorqueRate(1.0, Side::kRight), 300 * 5.0);
  EXPECT_DOUBLE_EQ(d.MasslessConductance(), 300);
  std::vector<double> x(kStates, 0.0);
  EXPECT_DOUBLE_EQ(d.DriveTorque(x, 4.0, 1.0, Side::kRight, {}), 300 * (5.0 - 4.0));
  Bench torque(Drive::kTorque);
  torque.setpoint = model::Schedule(750.0);
  const TopDrive q(torque.parts, torque.slots, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(q.MasslessTorque(1.0, Side::kRight), 750);
  EXPECT_DOUBLE_EQ(q.MasslessConductance(), 0);
}

}  // namespace
}  // namespace drillwave::dynamics
