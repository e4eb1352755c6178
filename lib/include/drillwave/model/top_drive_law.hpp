#pragma once
// The law of a PI top drive against stick-slip (issue 35), one set of parameters for every kind with such a top: its
// torque limit, the torque feedback of the soft-torque family (SoftTorque, SoftSpeed, Z-Torque), the actuator delay
// and the hand-over from the stiff PI it replaces. The PI's own gains stay in model::PiController beside it (motors'
// speed loops share them); dynamics::PiTopDrive runs the law inside a process.
#include <algorithm>

#include "drillwave/model/pi_controller.hpp"

namespace drillwave::model {

// Torque feedback into a PI top drive's speed loop (the soft-torque family of stick-slip mitigation): the speed the PI
// tracks is the set-point corrected by the string torque the top measures, high-pass filtered by a first-order filter,
//   r = setpoint - gain * T_hp,   T_hp = T - T_lp,   T_lp' = (T - T_lp) / time_constant_s,
// T the torque the top feeds into the string. In steady rotation T_hp = 0: the set-point speed is held. Over the band
// where the PI is stiff and T_hp ~ T, the top takes T ~ (setpoint - v) / gain: gain = 1 / Z matches the pipe's
// impedance (Z-Torque). Only on a top without a compliant gear.
struct TorqueFeedback {
  double gain = 0;             // [rad/s per N·m]; 0: none
  double time_constant_s = 0;  // of the high-pass filter, > 0 with a gain

  bool active() const { return gain != 0; }
};

// The law takes over at time_s from a plain PI with the gains `before` and no torque feedback: a drive switched to
// SoftTorque while the string sticks and slips. The integral torque carries over (the integral of the speed error is
// rescaled by before.ki / pi.ki), so only the proportional part and the feedback change the torque at time_s.
struct Handover {
  double time_s = 0;  // 0: the law acts from the start
  PiController before;

  bool active() const { return time_s > 0; }
};

struct TopDriveLaw {
  double torque_limit = 0;          // [N·m], 0: unlimited
  TorqueFeedback torque_feedback;   // SoftTorque / Z-Torque set-point correction
  // The drive's torque acts this pure delay [s] after the controller computes it (0: none). Simulated as the same
  // delay on the controller's inputs (set-point, speed, string torque), which gives the same torque for a linear
  // controller; the clamp commutes with the delay.
  double actuator_delay_s = 0;
  Handover handover;

  // The speed the PI tracks: the set-point less the feedback gain times the high-passed string torque.
  double Command(double setpoint, double string_torque, double low_passed) const {
    return setpoint - torque_feedback.gain * (string_torque - low_passed);
  }
  double FilterRate(double string_torque, double low_passed) const {
    return (string_torque - low_passed) / torque_feedback.time_constant_s;
  }
  double Clamp(double torque) const {
    return torque_limit > 0 ? std::clamp(torque, -torque_limit, torque_limit) : torque;
  }
};

}  // namespace drillwave::model
