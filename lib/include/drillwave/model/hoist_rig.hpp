#pragma once
// The hoisting rig above the top drive as two coupled masses (chapter eq. 2.22): M1, every rig element but the string,
// the cables, the drawworks and the blocks (derrick and crown), on the ground stiffness k01 with damping gamma1; M2,
// the cables and the crown and travelling blocks, hanging from M1 by the cable stiffness k12, with damping gamma2; the
// drawworks' cable tension u_F pulls on M1.
//
// How it is coupled (a reading of the seed, which leaves both points open):
// - The top drive hangs from the travelling block on a rigid hook, so it moves with M2: the hook force H of eq. 2.23
//   becomes internal, and M2 + M_td carry the string's pull S. (A hook spring would add a third, much higher mode.)
// - Eq. 2.22 alone has no steady drilling: the block descends at the rate of penetration V0 and the cable would
//   stretch by V0 t. The drawworks pays out line at the steady V0 of the start (constant pay-out), and the equations
//   hold for the displacements from that steady descent. The steady tension u_F0 and the weights only set the static
//   positions; the input is the change u_F(t) - u_F0.
// Displacements down positive: y1 the derrick's, delta the cable's stretch beyond its steady value, v the top drive's
// speed:
//   M1 y1''        = -gamma1 y1' - k01 y1 + k12 delta - (u_F(t) - u_F0)
//   (M2 + M_td) v' = S(t) - H0 - gamma2 (v - V0) - k12 delta           (H0: the hook force of steady drilling)
//   delta'         = v - V0 - y1'
// With a constant pay-out the rate of penetration returns to V0, and with it the weight on bit to its steady value:
// a change of u_F moves the rig and the string for a while, not the steady state.
#include <array>
#include <cmath>
#include <optional>

#include "drillwave/model/drawworks.hpp"
#include "drillwave/model/schedule.hpp"

namespace drillwave::model {

struct HoistRig {
  double derrick_mass = 0;      // M_rg1 [kg]
  double block_mass = 0;        // M_rg2 [kg]
  double derrick_damping = 0;   // gamma_rg1 [N·s/m]
  double block_damping = 0;     // gamma_rg2 [N·s/m]
  double ground_stiffness = 0;  // k_rg01 [N/m]
  double cable_stiffness = 0;   // k_rg12 [N/m]
  Schedule tension_change;      // u_F(t) - u_F0 [N], up on the derrick
  // The drawworks paying out the line at its own speed (absent: a constant pay-out at the steady rate of penetration);
  // Rates then takes its pay-out for steady_rop.
  std::optional<Drawworks> drawworks;

  // State: y1 [m], y1' [m/s], delta [m].
  using State = std::array<double, 3>;

  // Undamped natural frequencies [rad/s] with the top drive's mass on the block and no string (S = H0): the roots of
  // M1 (M2 + M_td) w^4 - (M1 k12 + (M2 + M_td)(k01 + k12)) w^2 + k01 k12 = 0, lower first.
  std::array<double, 2> NaturalFrequencies(double top_drive_mass) const {
    const double m2 = block_mass + top_drive_mass;
    const double a = derrick_mass * m2, b = derrick_mass * cable_stiffness + m2 * (ground_stiffness + cable_stiffness);
    const double c = ground_stiffness * cable_stiffness;
    const double root = std::sqrt(b * b - 4 * a * c);
    return {std::sqrt(2 * c / (b + root)), std::sqrt((b + root) / (2 * a))};  // (b - root) / 2a written stably
  }

  // The cable's pull on the block and top drive, up: the steady hook force, the block's damper and the stretch.
  double CablePull(const State& s, double v, double steady_rop, double steady_hook_force) const {
    return steady_hook_force + block_damping * (v - steady_rop) + cable_stiffness * s[2];
  }
  // (y1', y1'', delta') at top drive speed v with the line paid out at `pay_out` (the steady rate of penetration, or
  // the drawworks').
  State Rates(const State& s, double v, double pay_out, double t, bool left) const {
    const double du = tension_change.Evaluate(t, left).first;
    return {s[1], (-derrick_damping * s[1] - ground_stiffness * s[0] + cable_stiffness * s[2] - du) / derrick_mass,
            v - pay_out - s[1]};
  }
  // The top drive's acceleration under the string's pull S (down) and the cable.
  double TopAcceleration(const State& s, double string_pull, double v, double steady_rop, double steady_hook_force,
                         double top_drive_mass) const {
    return (string_pull - CablePull(s, v, steady_rop, steady_hook_force)) / (block_mass + top_drive_mass);
  }
};

}  // namespace drillwave::model
