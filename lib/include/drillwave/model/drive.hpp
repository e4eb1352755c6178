#pragma once
// How a string's end is driven from outside: the seeds' top boundary conditions, each a kind of dynamics::TopDrive.

namespace drillwave::model {

enum class Drive {
  kNone,
  kPrescribedSpeed,    // v = setpoint(t): the imposed-speed top (Neumann-free, reflection -1)
  kSpeedDashpot,       // torque beta (setpoint(t) - v): the dissipative top of the chapter's eq. 2.10 family
  kPiSpeedController,  // torque kp (setpoint - v) + ki * integral(setpoint - v), clamped to +/- torque_limit
  kTorque,             // torque = setpoint(t)
  // DC motor (chapter eq. 2.15): torque k I with L dI/dt = V - R I - k v (k_T = k_e = k). V is the setpoint in volts
  // (open loop) or comes from a PI speed controller, kp (setpoint - v) + ki * integral, in volts; both clamped to
  // +/- voltage_limit.
  kDcMotorVoltage,
  kDcMotorSpeed,
  // Induction motor on a V/f supply (chapter eqs. 2.18-2.19): the setpoint is the supply frequency [Hz] (open loop),
  // or the speed [rad/s] of a PI controller whose torque demand kp (setpoint - v) + ki * integral [N·m] the drive
  // turns into the supply frequency by slip-frequency control (model::InductionMotor::SupplyForTorque).
  kInductionMotor,
  kInductionMotorSpeed,
};

}  // namespace drillwave::model
