#pragma once
// Steady drilling of the coupled axial-torsional model (cases kind "axial_torsional") and the linear delay system of
// small perturbations about it: the stability of the Richard-Germay-Detournay model with distributed strings
// (DESIGN.md §3-4).
//
// Each channel is a chain of wave pieces between massless nodes (network_linearization.hpp builds its equations, with
// the Kelvin-Voigt dashpots across the pieces): the torsional one between a top drive under a PI speed controller (its
// output the torque, with its law against stick-slip, or a DC motor's voltage or an induction motor's torque demand,
// through a rigid or compliant gear)
// and the bit's inertia, the axial one between the hoist's mass (under a constant hook force: no linear term; or
// hanging from the hoisting rig) and the bit's mass. The bit-rock law couples them
// through the depth of cut d = n (U(t) - U(t - t_n)), t_n solving Phi(t) - Phi(t - t_n) = 2 pi / n. About steady
// drilling (Phi = Omega0 t, U = V0 t, t_n0 = 2 pi / (n Omega0)) the cut delay moves by
//   delta t_n = -(phi(t) - phi(t - t_n0)) / Omega0     (the bit ahead of its steady angle reaches the last cut sooner)
// and the depth of cut by
//   delta d = n (u(t) - u(t - t_n0)) + n V0 delta t_n = n (u - u(t - t_n0)) - (n V0 / Omega0) (phi - phi(t - t_n0)),
// which the cutting forces W_c = a zeta eps d and T_c = a^2 eps d / 2 feed back into the bit's two equations; the
// wear-flat contact W_f = a sigma l is constant while the bit advances, its friction torque moves only with the slope
// of a Stribeck law or of a contact law's F (bitrock/contact_law.hpp; eq. 2.33's cutting torque adds its slope and
// its gain F^2). The bit angle phi and position u enter only through these differences: they are derivative-only
// states of the LinearDelaySystem (its characteristic function is divided by s for each), so a shift of the bit's
// angle or depth, which changes nothing, is no root.
#include <optional>
#include <vector>

#include "drillwave/analysis/network_linearization.hpp"
#include "drillwave/model/hoist_rig.hpp"
#include "drillwave/model/jeffcott_bha.hpp"
#include "drillwave/model/pi_controller.hpp"
#include "drillwave/model/top_drive_law.hpp"

namespace drillwave::analysis {

// One channel: pieces top to bottom, the ground (viscous) damping lumped at each node, the end inertias.
struct WaveChannel {
  std::vector<double> impedance, travel_time_s;  // per piece, > 0
  std::vector<double> node_damping;              // per node (pieces + 1), >= 0
  double top_inertia = 0;                        // J_td [kg m^2] or the hoist's mass [kg], > 0
  double bit_inertia = 0;                        // J_b or M_b, > 0
  std::vector<double> dashpot;                   // per piece: Kelvin-Voigt eta K / length across it (empty: none)
};

struct AxialTorsionalString {
  WaveChannel torsion, axial;       // torsion's top_inertia: the top drive's own (the gear adds a rigid motor's)
  model::PiController pi;           // the top drive's PI speed controller, in its drive's units (see top_drive)
  double cut_weight_per_depth = 0;  // a zeta eps [N/m]
  double cut_torque_per_depth = 0;  // a^2 eps / 2 [N m/m] (times F(Omega0)^2 with eq. 2.33)
  int blades = 1;                   // n
  bool axial_coupling = true;       // false: the depth of cut is held (no axial channel, no cut delay)
  // What the PI drives, as a waves::Node top (constants referred as it refers them): kPiSpeedController, its output is
  // the torque; kDcMotorSpeed, its output is dc_motor's armature voltage (kp [V s/rad], ki [V/rad]);
  // kInductionMotorSpeed, its output is the torque demand of induction_motor's slip-frequency drive. The gear sits
  // between the motor and the top drive.
  waves::Drive top_drive = waves::Drive::kPiSpeedController;
  waves::DcMotor dc_motor{};
  model::InductionMotor induction_motor{};
  model::Gear gear{};
  // The PI top drive's law (kPiSpeedController only): its torque feedback's filter joins the states, an actuator delay
  // makes the controller's terms retarded (network_linearization.hpp).
  model::TopDriveLaw top_law{};
  // The two-mass hoisting rig above the hoist (model::HoistRig, chapter eq. 2.22; absent: a constant hook force). The
  // hoist's mass then carries the block's too, the block's damper acts on the hoist's speed, and the derrick's
  // displacement and speed and the cable's stretch join the states: about steady drilling (constant pay-out)
  //   y1' = y1d,  M1 y1d' = -gamma1 y1d - k01 y1 + k12 delta,  delta' = v_hoist - y1d,
  //   (M2 + M_td) v_hoist' = (the string's pull) - gamma2 v_hoist - k12 delta.
  //   With the rig's drawworks (model::Drawworks) the line is paid out at r w_d instead of the constant rate: the
  //   drum's speed and its induction motor's four fluxes join the states, at the steady supply drawworks_supply_hz,
  //   delta' = v_hoist - y1d - r w_d,  J w_d' = r P + n T(psi),  psi' = F(psi, f0, n w_d),
  //   P = gamma2 (v_hoist - V0) + k12 delta + H0 the line's pull (model::HoistRig::CablePull).
  std::optional<model::HoistRig> rig{};
  double drawworks_supply_hz = 0;
  // The BHA's lateral motion with a mass unbalance at the bit (bha_whirl_linearization.hpp); absent: none.
  std::optional<model::JeffcottBha> unbalance{};
};

struct SteadyDrilling {
  double speed_rad_s = 0;              // Omega0 of top and bit
  double rop_m_s = 0;                  // V0 > 0
  double friction_slope_Nms_per_rad = 0;  // d T_bit / d w at Omega0, the depth of cut held (0 for Coulomb friction)
  double top_torque_Nm = 0;            // what the top drive supplies (sets an induction motor's steady supply)
};

// States: the top drive's speed, the bit's speed, the PI's integral, the motor's current, fluxes or speed and gear
// twist (network_linearization.hpp), the hoist's speed, the bit's axial speed, with a rig its three states, with an
// unbalance the whirl's four, then
// the derivative-only states: bit angle, bit position, the torsional waves, the axial waves (without axial coupling:
// the torsional network alone). Throws std::invalid_argument for inconsistent sizes or non-positive inertias.
NetworkLinearization LinearizeAxialTorsional(const AxialTorsionalString& string, const SteadyDrilling& point);

}  // namespace drillwave::analysis
