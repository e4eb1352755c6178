#pragma once
// A PI speed controller with its law against stick-slip (model::TopDriveLaw) as a component of a process: what the
// controller reads (an actuator delay late), the speed it tracks, its torque and the rates of its two states (the
// integral of the speed error and a filter: with torque feedback the low-passed string torque, under a filtered wave
// cancellation the low-passed arriving wave); under wave cancellation the torque that absorbs the arriving wave
// instead of the PI's output. The first component of the
// dynamics layer issue 36 asks for: the wave network's process (torsional_wave, every PI speed loop of its ends) and
// the coupled kind's (axial_torsional) both run their top's controller through it, so a law written here works in
// both. It depends on model and integration only; the process keeps the state slots and tells it the string torque.
#include <optional>

#include "drillwave/integration/hermite_history.hpp"
#include "drillwave/integration/options.hpp"
#include "drillwave/model/pi_controller.hpp"
#include "drillwave/model/schedule.hpp"
#include "drillwave/model/top_drive_law.hpp"

namespace drillwave::dynamics {

class PiTopDrive {
 public:
  using Side = integration::Side;
  // What a wave-cancelling drive reads besides (model::WaveCancellation): the torque the string and the top's own
  // dampers take from it, and the up-going wave arriving at the top and its rate.
  struct TopWave {
    double load = 0, arriving = 0, arriving_rate = 0;
  };
  // What the controller reads at one instant: the speed it tracks (the set-point less the torque feedback), the
  // drive's speed and the string torque at the top (0 without feedback), all one actuator delay late; under wave
  // cancellation also the set-point's slope and the top's wave.
  struct Reading {
    double command, speed, torque;
    double command_rate = 0;
    TopWave wave{};
    double low_passed = 0;  // the filter's state: the low-passed string torque or arriving wave
  };

  // The controller of a drive turning steadily at initial_speed before the start (what a delayed controller reads
  // then), whose speed carries `inertia` (wave cancellation's feed-forward, the sliding mode's gains). The references
  // must outlive it.
  PiTopDrive(const model::PiController& pi, const model::TopDriveLaw& law, const model::Schedule& setpoint,
             double initial_speed, double inertia);

  // A filter state: the torque feedback's low-passed string torque or the filtered wave cancellation's wave.
  bool has_filter() const { return law_.torque_feedback.active() || law_.wave_cancellation.filtered(); }
  double delay() const { return law_.actuator_delay_s; }

  // The reading at time t for a drive now turning at drive_speed, the filter's state low_passed (ignored without
  // feedback); string_torque(when, speed) is the torque the top feeds into the string at `when` turning at `speed`
  // (asked only with feedback), top_wave(when, speed) the TopWave there (asked only under wave cancellation).
  template <class StringTorque, class ReadTopWave>
  Reading Read(double t, Side side, double drive_speed, double low_passed, const StringTorque& string_torque,
               const ReadTopWave& top_wave) const {
    Reading in{0.0, drive_speed, 0.0};
    in.low_passed = low_passed;
    double when = t;
    if (speed_history_) when = t - delay(), in.speed = speed_history_->Value(when, 0, side);
    in.command = Setpoint(when, side);
    if (law_.torque_feedback.active()) {
      in.torque = string_torque(when, in.speed);
      if (Engaged(t, side)) in.command = law_.Command(in.command, in.torque, low_passed);
    }
    // A filtered wave is followed before a handover too, so that the law takes over with it settled.
    if (CancelsWaves(t, side) || law_.wave_cancellation.filtered())
      in.command_rate = SetpointRate(when, side), in.wave = top_wave(when, in.speed);
    return in;
  }
  // The PI's output for the reading (a torque, or a motor's voltage or torque demand), with the gains in force at t;
  // under wave cancellation the torque that absorbs the arriving wave; under a sliding mode its torque.
  double Output(double t, Side side, const Reading& in, double integral) const {
    if (CancelsWaves(t, side)) return WaveCancellingTorque(in, integral);
    if (law_.sliding_mode.active() && Engaged(t, side))
      return law_.sliding_mode.Torque(inertia_, in.command - in.speed, integral);
    return PiAt(t, side).Output(in.command, in.speed, integral);
  }
  // The output as the drive's torque: clamped to the torque limit.
  double Torque(double t, Side side, const Reading& in, double integral) const {
    return law_.Clamp(Output(t, side, in, integral));
  }
  static double IntegralRate(const Reading& in) { return in.command - in.speed; }
  double FilterRate(const Reading& in, double low_passed) const {
    return law_.torque_feedback.active() ? law_.FilterRate(in.torque, low_passed)
                                         : law_.wave_cancellation.FilterRate(in.wave.arriving, low_passed);
  }
  // The filter's steady state for a drive turning at `speed` with the string taking `string_torque` from it.
  double InitialLowPassed(double speed, double string_torque) const {
    return law_.torque_feedback.active() ? string_torque
                                         : law_.wave_cancellation.SteadyArrivingWave(speed, string_torque);
  }
  // Steady start: the integral that holds `held`, the drive's output, with no speed error (the gains in force at 0);
  // under wave cancellation the one whose torque ki I is string_torque, what the string takes from the top (the law's
  // torque carries the top's dampers itself).
  double InitialIntegral(double held, double string_torque) const;

  // The process's step cap, lowered to the delay (delayed look-ups come from committed history).
  double MaxStep(double process_max_step) const;
  // Breakpoints of its own after `passed`: the set-point's knots one delay late, the handover.
  double NextBreakpoint(double passed) const;
  // At every breakpoint the process passes: at the handover the integral of the speed error is rescaled so that the
  // integral torque carries over.
  void OnBreakpoint(double t, double& integral);
  // A restart of the process's steps (an event, a breakpoint): the drive's speed may kink there.
  void MarkRestart() { restarted_ = true; }
  // The drive's speed (component speed_index of the piece) into the delayed controller's history, kept read_back.
  void Commit(const integration::Piece& piece, int speed_index, double read_back);

 private:
  bool Engaged(double t, Side side) const;
  bool CancelsWaves(double t, Side side) const { return law_.wave_cancellation.active() && Engaged(t, side); }
  const model::PiController& PiAt(double t, Side side) const { return Engaged(t, side) ? pi_ : law_.handover.before; }
  double Setpoint(double t, Side side) const {
    return side == Side::kLeft ? setpoint_.ValueBefore(t) : setpoint_.Value(t);
  }
  double SetpointRate(double t, Side side) const {
    return side == Side::kLeft ? setpoint_.SlopeBefore(t) : setpoint_.Slope(t);
  }
  double WaveCancellingTorque(const Reading& in, double integral) const;

  const model::PiController& pi_;
  const model::TopDriveLaw& law_;
  const model::Schedule& setpoint_;
  double inertia_;
  std::optional<integration::HermiteHistory> speed_history_;  // with a delay
  bool restarted_ = true;    // the next committed piece starts after an event or a breakpoint
  bool handed_over_ = false;
};

}  // namespace drillwave::dynamics
