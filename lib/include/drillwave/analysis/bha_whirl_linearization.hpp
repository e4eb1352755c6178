#pragma once
// The BHA's lateral motion with a mass unbalance at the bit (model::JeffcottBha, the failure seed's Jeffcott rotor,
// eqs. 21-23) in a linearization about steady rotation at the bit speed w0.
//
// In the fixed frame the unbalance forces the lateral motion at the bit angle Phi: no equilibrium, a periodic orbit.
// With an isotropic stiffness the angle drops out in the frame turning with the bit: with z = x + i y and
// zeta = z e^{-i Phi} (zeta's real axis points at the unbalance),
//   (M + m) (zeta'' + 2 i Phi' zeta' + i Phi'' zeta - Phi'^2 zeta) + c (zeta' + i Phi' zeta) + k zeta
//       = m e (Phi'^2 - i Phi''),
//   (J_b + m e^2) Phi'' = T - m e Im(zeta'' + 2 i Phi' zeta' + i Phi'' zeta - Phi'^2 zeta),
// (T: the string's and the bit's other torques), autonomous in (zeta, Phi'). The synchronous whirl is its equilibrium
// zeta0 = m e w0^2 / (k - (M + m) w0^2 + i c w0), which costs the bit the steady torque c w0 |zeta0|^2
// (model::JeffcottBha::SteadyDragTorque). The perturbation eps = xi + i eta of zeta and omega of Phi' add the states
// xi, eta, xi', eta' and couple the bit's speed through a mass matrix in (xi'', eta'', omega'). The roots are those of
// the orbit's Floquet exponents (the frame turns with the orbit); |zeta| is the whirl radius of either frame.
#include "drillwave/analysis/network_linearization.hpp"
#include "drillwave/model/jeffcott_bha.hpp"

namespace drillwave::analysis {

// Adds the whirl's four states (before the derivative-only states) and its coupling to the bit. Row `bit_speed` of
// lin.system must be the bit's acceleration with every torque but the unbalance's divided by `row_inertia`;
// `own_inertia` is J_b, the bit's inertia without the unbalance.
void AddBhaWhirl(NetworkLinearization& lin, int bit_speed, double row_inertia, double own_inertia,
                 const model::JeffcottBha& bha, double w0);

}  // namespace drillwave::analysis
