#pragma once
// The gear between a top-drive motor and the string's top: rigid, or the compliant coupling of the rig's two-mass
// model (motor / rotary-table inertia behind the gear, top-drive inertia at the string; chapter §2.6, the torsional
// counterpart of eq. 2.22).

namespace drillwave::model {

// A gear between a motor and the node it drives: the motor turns `ratio` times faster. Rigid (stiffness 0): the
// motor's inertia adds ratio^2 J_m to the node's. Compliant: the motor is a second inertia with its own speed, and
// the gear passes k (twist) + c (twist rate) to the node, the twist being the motor angle / ratio - node angle.
// Quantities on the motor's side are referred to the node's side: speed / ratio, torque * ratio, inertia * ratio^2.
struct Gear {
  double ratio = 1;          // motor turns per node turn, > 0
  double stiffness = 0;      // [N·m/rad] on the node's side; 0: rigid
  double damping = 0;        // [N·m·s/rad] on the node's side
  double motor_inertia = 0;  // J_m [kg·m^2] on the motor's shaft

  bool compliant() const { return stiffness > 0; }
  double ReferredMotorInertia() const { return ratio * ratio * motor_inertia; }
  // What the motor adds to the inertia of the node it drives: all of it through a rigid gear, none through a
  // compliant one (there the motor is an inertia of its own).
  double InertiaAddedToNode() const { return compliant() ? 0.0 : ReferredMotorInertia(); }
  double Torque(double twist, double motor_speed_referred, double node_speed) const {
    return stiffness * twist + damping * (motor_speed_referred - node_speed);
  }
};

}  // namespace drillwave::model
