#include "drillwave/dynamics/top_drive.hpp"

#include <algorithm>
#include <limits>

namespace drillwave::dynamics {

using model::Drive;

TopDrive::TopDrive(const TopDriveParts& parts, Slots slots, double initial_speed, double steady_torque)
    : parts_(parts), slots_(slots), initial_speed_(initial_speed), steady_torque_(steady_torque) {
  if (HasSpeedLoop(parts.drive))
    controller_.emplace(*parts.pi, *parts.law, *parts.setpoint, initial_speed, parts.inertia);
  if (HasInductionMotor(parts.drive)) {
    const double n = parts.gear.ratio;
    steady_supply_hz_ = parts.drive == Drive::kInductionMotor
                            ? parts.setpoint->Value(0.0)
                            : parts.induction->SteadySupplyFrequency(steady_torque / n, n * initial_speed);
  }
}

double TopDrive::DriveTorque(const State& x, double drive_speed, double t, Side side, const Reading& in) const {
  switch (parts_.drive) {
    case Drive::kNone:
    case Drive::kPrescribedSpeed:
      return 0;
    case Drive::kSpeedDashpot:
      return parts_.dashpot * (Setpoint(t, side) - drive_speed);
    case Drive::kTorque:
      return Setpoint(t, side);
    case Drive::kPiSpeedController:
      return controller_->Torque(t, side, in, x[slots_.integral]);
    case Drive::kDcMotorVoltage:
    case Drive::kDcMotorSpeed:
      return parts_.dc.motor_constant * x[slots_.current];
    case Drive::kInductionMotor:
    case Drive::kInductionMotorSpeed:
      return parts_.gear.ratio * parts_.induction->Torque(Fluxes(x));
  }
  return 0;
}

void TopDrive::Rates(const State& x, double node_speed, double t, Side side, const Reading& in, State& dx) const {
  const double vd = DriveSpeed(x, node_speed);
  if (controller_) {
    dx[slots_.integral] = PiTopDrive::IntegralRate(in);
    if (slots_.filter >= 0) dx[slots_.filter] = controller_->FilterRate(in, x[slots_.filter]);
  }
  if (slots_.current >= 0)
    dx[slots_.current] =
        parts_.dc.CurrentRate(ArmatureVoltage(x, t, side, in), parts_.dc.motor_constant, vd, x[slots_.current]);
  if (slots_.flux >= 0) {
    const auto rates =
        parts_.induction->FluxRates(Fluxes(x), SupplyFrequency(x, vd, t, side, in), parts_.gear.ratio * vd);
    std::copy(rates.begin(), rates.end(), dx.begin() + slots_.flux);
  }
  if (slots_.motor_speed >= 0) {
    dx[slots_.motor_speed] =
        (DriveTorque(x, vd, t, side, in) - GearTorque(x, node_speed)) / parts_.gear.ReferredMotorInertia();
    dx[slots_.motor_speed + 1] = vd - node_speed;
  }
}

// In steady rotation the speed loop holds its output with its integral part: a torque, a DC motor's steady voltage
// (R I + k v in volts) or an induction motor's torque demand for the steady supply; a DC motor carries the current of
// the steady torque, an induction motor the fluxes steady at its supply (open loop: the scheduled one, whatever
// torque that gives), a compliant gear the twist of the steady torque; a filter has settled.
void TopDrive::SteadyStart(double string_torque, State& x) const {
  const double v0 = initial_speed_;
  double held = steady_torque_;
  if (slots_.current >= 0) {
    const double k = parts_.dc.motor_constant;
    x[slots_.current] = steady_torque_ / k;
    if (!parts_.dc_torque_command) held = parts_.dc.armature_resistance * x[slots_.current] + k * v0;
  }
  if (slots_.flux >= 0) {
    const double n = parts_.gear.ratio;
    const auto psi = parts_.induction->SteadyFluxes(steady_supply_hz_, n * v0);
    std::copy(psi.begin(), psi.end(), x.begin() + slots_.flux);
    if (parts_.drive == Drive::kInductionMotorSpeed)  // the demand that asks for this supply
      held = n * parts_.induction->TorqueDemandFor(steady_supply_hz_, n * v0);
  }
  if (controller_) x[slots_.integral] = controller_->InitialIntegral(held, string_torque);
  if (slots_.filter >= 0) x[slots_.filter] = controller_->InitialLowPassed(v0, string_torque);
  if (slots_.motor_speed >= 0) {
    x[slots_.motor_speed] = v0;
    x[slots_.motor_speed + 1] = steady_torque_ / parts_.gear.stiffness;
  }
}

double TopDrive::MasslessTorque(double t, Side side) const {
  if (parts_.drive == Drive::kSpeedDashpot) return parts_.dashpot * Setpoint(t, side);
  if (parts_.drive == Drive::kTorque) return Setpoint(t, side);
  return 0;
}
double TopDrive::MasslessTorqueRate(double t, Side side) const {
  if (parts_.drive == Drive::kSpeedDashpot) return parts_.dashpot * SetpointRate(t, side);
  if (parts_.drive == Drive::kTorque) return SetpointRate(t, side);
  return 0;
}

double TopDrive::Current(const State& x) const {
  if (slots_.current >= 0) return x[slots_.current];
  if (slots_.flux >= 0) return parts_.induction->StatorCurrentRms(Fluxes(x));
  return 0;
}

double TopDrive::StoredEnergy(const State& x) const {
  if (slots_.motor_speed < 0) return 0;
  const double vm = x[slots_.motor_speed], twist = x[slots_.motor_speed + 1];
  return 0.5 * parts_.gear.ReferredMotorInertia() * vm * vm + 0.5 * parts_.gear.stiffness * twist * twist;
}

double TopDrive::NextBreakpoint(double passed) const {
  const double knot =
      parts_.setpoint ? parts_.setpoint->NextKnotAfter(passed) : std::numeric_limits<double>::infinity();
  return controller_ ? std::min(knot, controller_->NextBreakpoint(passed)) : knot;
}

// A DC motor's armature voltage: the set-point (open loop) or the speed loop's, clamped to its limit.
double TopDrive::ArmatureVoltage(const State& x, double t, Side side, const Reading& in) const {
  const model::DcMotor& m = parts_.dc;
  double u;
  if (parts_.drive == Drive::kDcMotorVoltage)
    u = Setpoint(t, side);
  else if (!parts_.dc_torque_command)
    u = LoopOutput(x, t, side, in);
  else
    u = m.armature_resistance / m.motor_constant * LoopOutput(x, t, side, in) + m.motor_constant * Setpoint(t, side);
  return m.voltage_limit > 0 ? std::clamp(u, -m.voltage_limit, m.voltage_limit) : u;
}

// An induction motor's supply: the set-point (open loop), or the supply for the speed loop's torque demand at the
// drive's speed (slip-frequency control).
double TopDrive::SupplyFrequency(const State& x, double drive_speed, double t, Side side, const Reading& in) const {
  if (parts_.drive == Drive::kInductionMotor) return Setpoint(t, side);
  const double n = parts_.gear.ratio;
  return parts_.induction->SupplyForTorque(LoopOutput(x, t, side, in) / n, n * drive_speed);
}

model::InductionMotor::Fluxes TopDrive::Fluxes(const State& x) const {
  model::InductionMotor::Fluxes psi;
  std::copy(x.begin() + slots_.flux, x.begin() + slots_.flux + 4, psi.begin());
  return psi;
}

}  // namespace drillwave::dynamics
