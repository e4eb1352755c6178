#pragma once
// The PI speed controller of a top drive (chapter §2.5): every kind's drive law, written once. Its output is a torque
// for a PI top drive, a voltage for a DC motor's speed loop and a torque demand for an induction motor's
// slip-frequency control; the kind clamps it and keeps the integral of the error as a state of its own layout.

namespace drillwave::model {

struct PiController {
  double kp = 0;  // proportional gain, output per (rad/s) of speed error
  double ki = 0;  // integral gain, output per rad of integrated speed error

  // kp (setpoint - speed) + ki * integral of (setpoint - speed).
  double Output(double setpoint, double speed, double integral) const {
    return Proportional(setpoint, speed) + ki * integral;
  }
  // The proportional part alone: the whole output of a controller without integral action (ki = 0).
  double Proportional(double setpoint, double speed) const { return kp * (setpoint - speed); }
  // The integral that holds the output at `output` with no speed error: where a steady start puts the state
  // (0 without integral action, which then cannot hold an output at zero error).
  double IntegralHolding(double output) const { return ki > 0 ? output / ki : 0.0; }
};

}  // namespace drillwave::model
