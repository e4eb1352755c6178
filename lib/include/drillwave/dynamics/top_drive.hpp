#pragma once
// The drive at a string's end as one component of a process (issue 36): an imposed speed, a dashpot to a set-point,
// a scheduled torque, or a PI speed loop (dynamics::PiTopDrive, with its laws against stick-slip) alone or through a
// DC or induction motor, behind a rigid or compliant gear. It keeps the formulas of its states — the PI's integral
// and filter, the motor's current or fluxes, the gear's motor speed and twist — their steady start, the torque it
// puts into its node and what it gives the outputs. The process owns the state vector (it tells the component where
// its slots sit), the node's own speed and what the string does; the wave network's ends and the coupled kind's top
// both run their drives through it, so that a drive written here works in every kind with a top.
#include <optional>
#include <vector>

#include "drillwave/dynamics/pi_top_drive.hpp"
#include "drillwave/integration/options.hpp"
#include "drillwave/model/dc_motor.hpp"
#include "drillwave/model/drive.hpp"
#include "drillwave/model/gear.hpp"
#include "drillwave/model/induction_motor.hpp"
#include "drillwave/model/pi_controller.hpp"
#include "drillwave/model/schedule.hpp"
#include "drillwave/model/top_drive_law.hpp"

namespace drillwave::dynamics {

// What a drive is made of. The pointed-to parts are kept by the caller and must outlive the drive; pi and law are
// read only with a speed loop, induction only with an induction motor.
struct TopDriveParts {
  model::Drive drive = model::Drive::kNone;
  const model::Schedule* setpoint = nullptr;  // speed [rad/s], torque [N·m], voltage [V] or supply [Hz], by drive
  double dashpot = 0;                         // kSpeedDashpot's beta [N·m·s/rad]
  const model::PiController* pi = nullptr;
  const model::TopDriveLaw* law = nullptr;
  // kDcMotorVoltage and kDcMotorSpeed. Its constant is referred to the node (n k through the gear).
  model::DcMotor dc;
  // kDcMotorSpeed: the PI commands a torque u and the drive applies V = R/k u + k setpoint (the back-emf of the
  // set-point fed forward, so that at steady state k I = u), instead of a PI in volts.
  bool dc_torque_command = false;
  const model::InductionMotor* induction = nullptr;
  model::Gear gear;
  double inertia = 0;  // what the drive's node carries (the laws' feed-forward)
};

class TopDrive {
 public:
  using Side = integration::Side;
  using State = std::vector<double>;
  using Reading = PiTopDrive::Reading;
  // Where the drive's states sit in the process's state; -1: the drive has no such state. The gear's twist follows
  // the motor's speed, an induction motor's four fluxes start at flux.
  struct Slots {
    int integral = -1, filter = -1, current = -1, flux = -1, motor_speed = -1;
  };

  // Which states a drive of these parts has.
  static bool HasSpeedLoop(model::Drive d) {
    return d == model::Drive::kPiSpeedController || d == model::Drive::kDcMotorSpeed ||
           d == model::Drive::kInductionMotorSpeed;
  }
  static bool HasDcMotor(model::Drive d) {
    return d == model::Drive::kDcMotorVoltage || d == model::Drive::kDcMotorSpeed;
  }
  static bool HasInductionMotor(model::Drive d) {
    return d == model::Drive::kInductionMotor || d == model::Drive::kInductionMotorSpeed;
  }
  // A PI drive's filter: the torque feedback's low-passed string torque or the filtered wave cancellation's wave.
  static bool HasFilter(const TopDriveParts& parts) {
    return parts.drive == model::Drive::kPiSpeedController &&
           (parts.law->torque_feedback.active() || parts.law->wave_cancellation.filtered());
  }

  // A drive turning steadily at initial_speed and putting steady_torque into its node before the start. Throws
  // std::domain_error where an induction motor under a speed loop cannot carry that torque (above its pull-out).
  TopDrive(const TopDriveParts& parts, Slots slots, double initial_speed, double steady_torque);
  TopDrive(const TopDrive&) = delete;  // the controller keeps references into the parts
  TopDrive& operator=(const TopDrive&) = delete;

  double delay() const { return controller_ ? controller_->delay() : 0.0; }
  bool has_motor_current() const { return slots_.current >= 0 || slots_.flux >= 0; }  // a DC or induction motor
  bool has_motor_speed() const { return slots_.motor_speed >= 0; }
  // An induction motor's steady supply [Hz]: the one that carries the steady torque under a speed loop.
  double steady_supply_hz() const { return steady_supply_hz_; }

  // The set-point (the imposed speed of kPrescribedSpeed) and its slope at t, on `side` of a knot.
  double Setpoint(double t, Side side) const {
    return side == Side::kLeft ? parts_.setpoint->ValueBefore(t) : parts_.setpoint->Value(t);
  }
  double SetpointRate(double t, Side side) const {
    return side == Side::kLeft ? parts_.setpoint->SlopeBefore(t) : parts_.setpoint->Slope(t);
  }

  // The speed the drive turns at, referred to the node's side: its motor's behind a compliant gear, else the node's.
  double DriveSpeed(const State& x, double node_speed) const {
    return slots_.motor_speed >= 0 ? x[slots_.motor_speed] : node_speed;
  }
  // What its speed loop reads at t with the drive turning at drive_speed (PiTopDrive::Read); without one, the drive's
  // own speed. string_torque and top_wave as PiTopDrive::Read asks them.
  template <class StringTorque, class ReadTopWave>
  Reading Read(const State& x, double drive_speed, double t, Side side, const StringTorque& string_torque,
               const ReadTopWave& top_wave) const {
    if (!controller_) return Reading{0.0, drive_speed, 0.0};
    const double low_passed = slots_.filter >= 0 ? x[slots_.filter] : 0.0;
    return controller_->Read(t, side, drive_speed, low_passed, string_torque, top_wave);
  }

  // The drive's torque on its own side of the gear, turning at drive_speed with its loop reading `in`.
  double DriveTorque(const State& x, double drive_speed, double t, Side side, const Reading& in) const;
  // The torque into the node turning at node_speed: the drive's through a rigid gear, the gear's through a compliant
  // one. read(drive_speed) gives the loop's reading, asked only where the drive's torque is.
  template <class Read>
  double TorqueIntoNode(const State& x, double node_speed, double t, Side side, const Read& read) const {
    if (slots_.motor_speed >= 0) return GearTorque(x, node_speed);
    return DriveTorque(x, node_speed, t, side, read(node_speed));
  }
  // The rates of the drive's states into dx, the node turning at node_speed and the loop reading `in` at the drive's
  // speed.
  void Rates(const State& x, double node_speed, double t, Side side, const Reading& in, State& dx) const;
  // Its states in steady rotation (the constructor's), the string taking string_torque from the node.
  void SteadyStart(double string_torque, State& x) const;

  // A massless node's own balance a - b v: a (a dashpot's beta times its set-point, a scheduled torque), a's rate and
  // b, the dashpot's beta.
  double MasslessTorque(double t, Side side) const;
  double MasslessTorqueRate(double t, Side side) const;
  double MasslessConductance() const { return parts_.drive == model::Drive::kSpeedDashpot ? parts_.dashpot : 0.0; }

  // Outputs: the motor's current (a DC motor's armature current, an induction motor's stator rms; 0 without), its
  // speed on its own shaft, the gear's torque, the kinetic and elastic energy of a motor behind a compliant gear.
  double Current(const State& x) const;
  double MotorShaftSpeed(const State& x) const { return parts_.gear.ratio * x[slots_.motor_speed]; }
  double GearTorque(const State& x, double node_speed) const {
    return parts_.gear.Torque(x[slots_.motor_speed + 1], x[slots_.motor_speed], node_speed);
  }
  double StoredEnergy(const State& x) const;

  // The speed loop's own events (PiTopDrive); no-ops without one.
  double MaxStep(double process_max_step) const {
    return controller_ ? controller_->MaxStep(process_max_step) : process_max_step;
  }
  double NextBreakpoint(double passed) const;
  void OnBreakpoint(double t, State& x) {
    if (controller_) controller_->OnBreakpoint(t, x[slots_.integral]);
  }
  void MarkRestart() {
    if (controller_) controller_->MarkRestart();
  }
  void Commit(const integration::Piece& piece, int node_speed_index, double read_back) {
    if (controller_) controller_->Commit(piece, node_speed_index, read_back);
  }

 private:
  // The speed loop's output: a torque (or an induction motor's torque demand), a DC motor's voltage in volts.
  double LoopOutput(const State& x, double t, Side side, const Reading& in) const {
    return controller_->Output(t, side, in, x[slots_.integral]);
  }
  double ArmatureVoltage(const State& x, double t, Side side, const Reading& in) const;
  double SupplyFrequency(const State& x, double drive_speed, double t, Side side, const Reading& in) const;
  model::InductionMotor::Fluxes Fluxes(const State& x) const;

  TopDriveParts parts_;
  Slots slots_;
  double initial_speed_, steady_torque_;
  double steady_supply_hz_ = 0;
  std::optional<PiTopDrive> controller_;
};

}  // namespace drillwave::dynamics
