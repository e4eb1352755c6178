#pragma once
// The seed's Routh-Hurwitz condition (setup seed eq. 12) for the two-disc set-up's steady rotation at lower-disc speed
// w, in closed form from a case document: the characteristic polynomial of DESIGN.md §4,
//   J_u J_l s^3 + (J_u d_l + J_l d_u) s^2 + (k (J_u + J_l) + d_u d_l) s + k (d_u + d_l),  d = dT/dw at w.
#include <nlohmann/json.hpp>

#include "drillwave/cases/friction_json.hpp"
#include "drillwave/bitrock/friction.hpp"

namespace drillwave::testing {

class TwoDiscRouthHurwitz {
 public:
  explicit TwoDiscRouthHurwitz(const nlohmann::json& model)
      : ju_(model["upper_disc"]["inertia_kgm2"]),
        km_(model["upper_disc"]["motor_constant_Nm_per_V"]),
        k_(model["string"]["stiffness_Nm_per_rad"]),
        jl_(model["lower_disc"]["inertia_kgm2"]),
        upper_(cases::ReadFrictionLaw(model["upper_disc"]["friction"], "/upper")),
        lower_(cases::ReadFrictionLaw(model["lower_disc"]["friction"], "/lower")) {}

  bool Stable(double w) const {
    const double d = lower_.SlipTorqueDerivative(w), du = upper_.SlipTorqueDerivative(w);
    const double a3 = ju_ * jl_, a2 = ju_ * d + jl_ * du, a1 = k_ * (ju_ + jl_) + du * d, a0 = k_ * (du + d);
    return a2 > 0 && a1 > 0 && a0 > 0 && a2 * a1 > a3 * a0;
  }
  // The steady speed in [lo, hi] where the verdict changes (bisection; one change inside assumed).
  double Boundary(double lo, double hi) const {
    const bool s_lo = Stable(lo);
    for (int i = 0; i < 100; ++i) (Stable(0.5 * (lo + hi)) == s_lo ? lo : hi) = 0.5 * (lo + hi);
    return lo;
  }
  // The input voltage that holds the steady rotation at w.
  double Voltage(double w) const { return (upper_.SlipTorque(w) + lower_.SlipTorque(w)) / km_; }
  const bitrock::FrictionLaw& lower() const { return lower_; }

 private:
  double ju_, km_, k_, jl_;
  bitrock::FrictionLaw upper_, lower_;
};

}  // namespace drillwave::testing
