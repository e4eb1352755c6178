#pragma once
// A contact through a friction law — a lumped inertia on its brake or bit, an end of the wave network — written once
// for every kind (issue 36): the friction it opposes slipping with, and what holds it at rest. Its regime and the
// switching between regimes: bitrock/stick_slip.hpp. (The coupled kind's bit meets the rock through
// bitrock::RgdLaw, whose static range depends on the cut.)
#include "drillwave/bitrock/friction.hpp"
#include "drillwave/bitrock/stick_slip.hpp"

namespace drillwave::dynamics {

class Contact {
 public:
  // law: kept by the caller. smoothing_rad_s > 0 replaces the static range by law(v) tanh(|v| / smoothing): the
  // contact never sticks then.
  explicit Contact(const bitrock::FrictionLaw& law, double smoothing_rad_s = 0.0)
      : law_(&law), smoothing_rad_s_(smoothing_rad_s) {}

  // Whether the contact can be held at rest: a set-valued law, not smoothed.
  bool CanStick() const { return law_->IsSetValued() && smoothing_rad_s_ == 0; }

  // The friction torque of the contact turning at v, slipping in `turn`'s direction, its law scaled by `scale` (a
  // normal load or a schedule): a set-valued law is read on the side of the slip direction, so that at v = 0 it is
  // the slip torque that way, never a value inside the static range.
  double SlipTorque(bitrock::Turn turn, double v, double scale = 1.0) const;

  // The contact held at rest under the driving torque `drive`: its law's static range, scaled.
  bitrock::AtRest HeldAtRest(double drive, double scale = 1.0) const {
    return {drive, {scale * law_->StaticPositive(), scale * law_->StaticNegative()}};
  }

 private:
  const bitrock::FrictionLaw* law_;
  double smoothing_rad_s_;
};

}  // namespace drillwave::dynamics
