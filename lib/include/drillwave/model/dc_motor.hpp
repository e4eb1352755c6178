#pragma once
// A DC motor (chapter eq. 2.15): torque k I with L dI/dt = V - k v - R I, its torque constant equal to its back-emf
// constant.

namespace drillwave::model {

struct DcMotor {
  double motor_constant = 0;       // k [N·m/A = V·s/rad]
  double armature_resistance = 0;  // R [ohm]
  double armature_inductance = 0;  // L [H]
  double voltage_limit = 0;        // [V], 0: unlimited

  // dI/dt at armature voltage V with the motor turning at `speed` and carrying `current`, for a motor whose constant
  // is k (the motor's own, or referred through a gear: n k against the speed on the gear's far side).
  double CurrentRate(double voltage, double k, double speed, double current) const {
    return (voltage - k * speed - armature_resistance * current) / armature_inductance;
  }
};

}  // namespace drillwave::model
