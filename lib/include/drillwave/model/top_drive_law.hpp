#pragma once
// The law of a PI top drive against stick-slip (issue 35), one set of parameters for every kind with such a top: its
// torque limit, the torque feedback of the soft-torque family (SoftTorque, SoftSpeed, Z-Torque) or the wave
// cancellation on the d'Alembert form, the actuator delay and the hand-over from the stiff PI it replaces. The PI's
// own gains stay in model::PiController beside it (motors' speed loops share them); dynamics::PiTopDrive runs the law
// inside a process.
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

// Wave cancellation on the d'Alembert form (DESIGN.md §1: v = D + U, T = Z (D - U) at the top): the drive reads the
// up-going wave w arriving at the top and turns the top at v = w + d, so that the wave it sends down is d whatever w:
// w is absorbed, not reflected (the top is an infinite pipe for it; the chapter's top boundary, eq. 2.10 family, with
// beta = Z, whose reflection (beta - Z) / (beta + Z) and so the neutral term of its DDE vanish), and d is the wave
// the drive chooses to inject,
//   d = setpoint / 2 + k I,   I' = setpoint - v   (the slow speed loop, k = ki / 2 Z [1/s]),
// which the string feels as the torque Z (setpoint - v) + ki I: its integral holds the mean speed at the set-point.
// Below k the loop reflects what arrives (reflection -k / (s + k)). The drive's torque (dynamics::PiTopDrive)
//   u = T_load + J (w' + d') + kp (w + d - v),
// T_load what the string and the top's own dampers take from it, J the inertia its speed carries: the feed-forward
// keeps v = w + d exactly, kp pulls the top back onto it after a jump, the clamp or an actuator delay. The wave and
// its rate are read from the wave arriving at the top (a drive estimates w = (v - T / Z) / 2 from its torque sub).
// Only on a top without a compliant gear, friction or Kelvin-Voigt dashpots next to it.
// Filtered (filter_time_constant_s = tf > 0): the law reads a low-passed wave a, tf a' = w - a, instead of w and its
// rate, and u = T_load + J (a' + d') + kp (a + d - v). Late by an actuator delay, the exact law feeds the top the rate
// of a wave one delay old, and its high-frequency content, which a real sub's noise and the string's fast echoes
// carry, comes back as a reflection; the filter gives up absorbing above 1 / tf to keep the loop's gain there small.
struct WaveCancellation {
  double impedance = 0;  // Z of the top section [N·m·s/rad], which turns the integral torque into a wave; 0: off
  double filter_time_constant_s = 0;  // tf of the arriving wave's low-pass [s]; 0: the wave read as it arrives

  bool active() const { return impedance > 0; }
  bool filtered() const { return active() && filter_time_constant_s > 0; }
  // The low-passed wave's rate.
  double FilterRate(double arriving, double low_passed) const {
    return (arriving - low_passed) / filter_time_constant_s;
  }
  // The wave a steady top turning at `speed` reads when the string takes `string_torque` from it: w = (v - T / Z) / 2.
  double SteadyArrivingWave(double speed, double string_torque) const {
    return 0.5 * (speed - string_torque / impedance);
  }
  // The down-going wave for the set-point and the integral torque ki I; linear, so also its rate for their rates.
  double DownWave(double setpoint, double integral_torque) const {
    return 0.5 * (setpoint + integral_torque / impedance);
  }
  // The slow speed loop's corner k = ki / 2 Z [1/s] for the integral gain ki.
  double Corner(double ki) const { return 0.5 * ki / impedance; }
};

// A sliding-mode speed loop (the boundary-layer control of Slotine & Li, Applied Nonlinear Control, ch. 7; the
// sliding-mode drill-string controllers of Navarro-Lopez & Cortes 2007 on a surface of speed errors): the surface
// s = e + lambda I, e = command - v, I' = e, and the drive's torque
//   u = J lambda e + J eta sat(s / phi),
// J the inertia the top's speed carries. For a constant command J v' = u - T (T what the string and dampers take)
// gives s' = T / J - eta sat(s / phi): outside the layer |s| > phi the top reaches it while J eta dominates the
// load, whatever the load is; inside, the law is the PI of InLayer (what a linearization sees). The command is
// Z-Torque's (the set-point less the high-passed string torque over Z): the surface holds the top on the
// impedance-matched speed. phi -> 0 is the discontinuous law, whose gain inside the layer grows as 1 / phi.
struct SlidingMode {
  double surface_corner = 0;  // lambda [1/s]
  double reaching_rate = 0;   // eta [rad/s^2]; 0: none
  double boundary_layer = 0;  // phi [rad/s], > 0 with a reaching rate

  bool active() const { return reaching_rate > 0; }
  // The law inside its layer: kp = J (lambda + eta / phi), ki = J eta lambda / phi.
  PiController InLayer(double inertia) const {
    const double gain = inertia * reaching_rate / boundary_layer;
    return {inertia * surface_corner + gain, gain * surface_corner};
  }
  double Torque(double inertia, double error, double integral) const {
    const double s = error + surface_corner * integral;
    return inertia * (surface_corner * error + reaching_rate * std::clamp(s / boundary_layer, -1.0, 1.0));
  }
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
  WaveCancellation wave_cancellation;  // instead of the PI's output (its gains: kp the pull onto w + d, ki = 2 Z k)
  SlidingMode sliding_mode;  // instead of the PI's output (its gains: the law's inside its layer, SlidingMode::InLayer)
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
