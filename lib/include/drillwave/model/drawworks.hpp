#pragma once
// The drawworks that pays out the hoisting line (chapter eq. 2.37): an induction motor through a gear on the drum.
// The line's pull on the block, P (up), unwinds the drum; the motor holds it back, generating (its speed a little
// above the synchronous speed of its supply):
//   J w_d' = r P + n T_em(psi),   psi' = F(psi, f(t), n w_d)   (model::InductionMotor, eqs. 2.37a-d)
// w_d the drum's speed (paying out positive), r the line radius (the drum's radius over the reeving's lines: the block
// descends r w_d), n the gear ratio (motor speed / drum speed), J the drum's and motor's inertia referred to the drum.
// The supply is the steady one f0 that pays out at the steady rate of penetration under the steady pull, plus a
// schedule of changes: the driller's lever. A faster pay-out than the bit drills loads the bit until it drills as fast.
#include "drillwave/model/induction_motor.hpp"
#include "drillwave/model/schedule.hpp"

namespace drillwave::model {

struct Drawworks {
  double line_radius = 0;      // r [m]
  double inertia = 0;          // J [kg m^2], referred to the drum
  double gear_ratio = 1;       // n
  InductionMotor motor;
  Schedule supply_change_hz;   // f(t) - f0 [Hz]

  // The drum's acceleration under the line's pull and the motor's fluxes.
  double DrumAcceleration(double line_pull, const InductionMotor::Fluxes& psi) const {
    return (line_radius * line_pull + gear_ratio * motor.Torque(psi)) / inertia;
  }
  double PayOut(double drum_speed) const { return line_radius * drum_speed; }
  // The supply that holds the drum at the speed paying out `rate` under the steady `pull`; throws std::domain_error
  // beyond the motor's pull-out torque.
  double SteadySupply(double rate, double pull) const {
    return motor.SteadySupplyFrequency(-line_radius * pull / gear_ratio, gear_ratio * rate / line_radius);
  }
};

}  // namespace drillwave::model
