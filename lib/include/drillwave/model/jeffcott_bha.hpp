#pragma once
// The BHA's lateral motion as a Jeffcott rotor at the bit (failure seed eqs. 21-23): a lateral mass M on a stiffness
// k with damping c, and an unbalance m at radius e turning with the bit angle Phi. With the lateral state
// s = (x, y, x', y'):
//   (M + m) x'' + c x' + k x = m e (Phi'^2 cos Phi + Phi'' sin Phi)
//   (M + m) y'' + c y' + k y = m e (Phi'^2 sin Phi - Phi'' cos Phi)
// and the unbalance acts on the bit's torsion with m e (x'' sin Phi - y'' cos Phi) besides its own m e^2 Phi''
// (seed eq. 23). Shared by every kind with a lumped bit; the kind integrates s beside the bit's angle and speed.
#include <array>
#include <cmath>

namespace drillwave::model {

struct JeffcottBha {
  using Lateral = std::array<double, 4>;  // x, y [m], x', y' [m/s]

  double mass = 0;            // M [kg]
  double stiffness = 0;       // k [N/m]
  double damping = 0;         // c [N·s/m]
  double unbalance_mass = 0;  // m [kg]
  double eccentricity = 0;    // e [m]

  double TotalMass() const { return mass + unbalance_mass; }       // M + m
  double Moment() const { return unbalance_mass * eccentricity; }  // m e
  double NaturalFrequency() const { return std::sqrt(stiffness / TotalMass()); }
  // Steady whirl radius at a constant bit speed w: m e w^2 / sqrt((k - (M + m) w^2)^2 + (c w)^2).
  double WhirlAmplitude(double w) const {
    return Moment() * w * w / std::hypot(stiffness - TotalMass() * w * w, damping * w);
  }
  // Torque the steady whirl at bit speed w takes from the bit: the lateral damper's power c w^2 r^2 over w.
  double SteadyDragTorque(double w) const {
    const double r = WhirlAmplitude(w);
    return damping * w * r * r;
  }
  // What the bit's inertia gains against its angular acceleration when x'' and y'' are eliminated from eq. 23:
  // m e^2 - (m e)^2 / (M + m).
  double AddedInertia() const { return Moment() * eccentricity - Moment() * Moment() / TotalMass(); }

  // Forces on the lateral motion other than its inertia and the unbalance's angular-acceleration term (eqs. 21-22
  // with Phi'' = 0): m e w^2 (cos Phi, sin Phi) - c (x', y') - k (x, y).
  std::array<double, 2> Forces(double phi, double w, const Lateral& s) const {
    const double centrifugal = Moment() * w * w;
    return {centrifugal * std::cos(phi) - damping * s[2] - stiffness * s[0],
            centrifugal * std::sin(phi) - damping * s[3] - stiffness * s[1]};
  }
  // Torque of the lateral motion on the bit at zero angular acceleration, m e (x'' sin Phi - y'' cos Phi) of eq. 23;
  // the part that goes with Phi'' is AddedInertia. (The centrifugal force is radial: no torque.)
  double Reaction(double phi, double w, const Lateral& s) const {
    const std::array<double, 2> f = Forces(phi, w, s);
    return Moment() / TotalMass() * (f[0] * std::sin(phi) - f[1] * std::cos(phi));
  }
  // (x', y', x'', y'') given the bit's angular acceleration phi_dd.
  Lateral Rates(double phi, double w, double phi_dd, const Lateral& s) const {
    const std::array<double, 2> f = Forces(phi, w, s);
    const double me = Moment(), total = TotalMass();
    return {s[2], s[3], (f[0] + me * std::sin(phi) * phi_dd) / total, (f[1] - me * std::cos(phi) * phi_dd) / total};
  }
};

}  // namespace drillwave::model
