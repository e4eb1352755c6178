#pragma once
// The model of the kind "axial_torsional" (reader, linearization and schema in axial_torsional.cpp; the run in
// axial_torsional_run.cpp): coupled axial and torsional waves in a pipe and optional BHA sections, a lumped bit,
// and the Richard-Germay-Detournay bit-rock law with the state-dependent cut delay t_n (DESIGN.md §1-3, chapter seed
// 2.28-2.33; the baseline model of shared/recordings/synthetic/BASELINE.md).
//
// Each channel (torsion: angular speed and torque; axial: speed, down positive, and force) is a waves::WaveChain of m
// sub-sections (the pipe's, then the BHA's) joined by massless nodes, with viscous damping, buoyant weight, side
// friction and Kelvin-Voigt damping as that chain carries them; this kind assembles the two chains with the top, the
// hoist and the bit.
// Top: a top drive of inertia J_td under a PI speed controller, with a law against stick-slip (model::TopDriveLaw:
// torque limit, SoftTorque / Z-Torque feedback of the string torque at the top or wave cancellation, actuator delay,
// handover), run by dynamics::PiTopDrive as the torsional_wave kind's top is; a hoist of mass M_td held by the hook
// force H: constant, set for a target weight on bit, or a schedule H(t) (chapter eq. 2.23: M_top U_tt(0) = E A U_s(0)
// + H(t)); or, with hoist/rig, hanging from the two-mass hoisting rig of eq. 2.22 (model::HoistRig: rigid hook,
// constant pay-out).
// Under the hook force the hoist may also have a dashpot c_h to the travelling block, which pays out line at the
// steady rate of penetration V0: -c_h (v_top - V0), nothing in steady drilling. It gives the axial top the partial
// reflection of Aarsnes & van de Wouw's distributed model (eta_a = (c_h - Z_a) / (c_h + Z_a) for a light hoist).
// Bit (node m): inertia J_b, mass M_b (buoyant weight included) and the bit-rock forces:
//   t_n: Phi(t) - Phi(t - t_n) = 2 pi / n,  d = n (U(t) - U(t - t_n))   (from the stored bit angle and position;
//        after a bounce, against the deepest of the last four blade passes at that angle)
//   cutting (d > 0, not turning backwards): W_c = a zeta eps d, T_c = a^2 eps d / 2
//   wear-flat contact (d > 0): W_f = a sigma l advancing, in [0, a sigma l] held axially, 0 lifting
//   friction: T_f = a gamma mu W_f / 2 sign(w), set-valued at w = 0 (stuck while the torque stays within T_c + T_f)
//   off bottom (d <= 0): no contact at all.
// Optional components, each switched on by its JSON object (absent: the baseline above):
//   rock/stribeck: mu(w) = mu + (mu_s - mu) exp(-|w| / w_s) while turning; a stuck bit holds with mu_s.
//   rock/contact: the chapter's friction function F(|w|) in place of sign(w) (eqs. 2.29-2.30), and optionally the
//        cutting torque times F^2 (eq. 2.33); bitrock/contact_law.hpp.
//   axial_coupling false: no axial dynamics; the weight on bit is held at W0 and the depth of cut at its steady value.
//   top/motor: a DC motor between the PI and the top: V = R/K u_PI + K Omega_ref, La I' = V - K w_top - R I,
//        torque K I on the top drive.
//   top/induction_motor: an induction motor (chapter eqs. 2.18-2.19) on a V/f supply with slip compensation
//        between the PI and the top: slip-frequency control, f = (p n w_m + u_PI / (n G)) / 2 pi at the measured speed
//        w_m, G the small-slip torque gain, the slip held below pull-out.
//   top/gear: the motor turns n times faster than the top drive; with a stiffness the motor is a second inertia
//        behind a compliant gear (the rig's two-mass model), and the PI acts on the motor's speed.
//   bit/unbalance: the BHA's lateral motion (x, y) as the Jeffcott rotor of the failure seed (eqs. 21-23), with the
//        unbalance m at radius e turning with the bit angle Phi and reacting on the bit's torsion.
// Three discrete regimes (rotation: forward / stuck / backward; axial: advancing / held / lifting; contact: on /
// off) switch at located events. The run starts in steady drilling at the set-points (prehistory Phi = Omega t,
// U = V t). Disturb it through the inputs (a set-point schedule) or the rock left before t = 0 (rock/bottom_roughness:
// U = V t + h(Omega t) in the prehistory, BASELINE.md's start). The inputs' knots are breakpoints, and so are the
// kinks and jumps that reach the top or the bit through the chains (the start's own among them: a set-point ramp from
// t = 0 kinks the top's waves against their steady prehistory).
// The rock's strength may vary with the drilled depth U (rock/strength_heterogeneity: eps and sigma l times 1 + g(U),
// a smooth seeded field), a disturbance inside the bit-rock law that also keeps the right-hand side a pure function.
#include <array>
#include <optional>

#include "drillwave/bitrock/rgd.hpp"
#include "drillwave/cases/model_kind.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/model/gear.hpp"
#include "drillwave/model/hoist_rig.hpp"
#include "drillwave/model/induction_motor.hpp"
#include "drillwave/model/jeffcott_bha.hpp"
#include "drillwave/model/pi_controller.hpp"
#include "drillwave/model/schedule.hpp"
#include "drillwave/model/top_drive_law.hpp"
#include "drillwave/waves/wave_chain.hpp"

namespace drillwave::cases::axial_torsional {


// One wave channel: the pipe's and the BHA's sub-sections as a chain (waves::WaveChain).
using Channel = waves::ChainSpec;

// DC motor of the top drive (the torsional_wave kind's dc_motor top): torque constant K = back-emf constant. Its PI
// commands a torque u and the drive applies V = R/K u + K Omega_ref (dynamics::TopDriveParts::dc_torque_command), so
// that at steady state K I = u with w_top = Omega_ref.
struct DcMotor {
  bool on = false;
  double k = 0, resistance = 0, inductance = 0;
};

// The bit-rock law's parameters and forces are bitrock::RgdLaw's (a, zeta, eps, sigma_l, mu, gamma, blades, Stribeck).
struct Model : bitrock::RgdLaw {
  int m = 20;
  double length = 0;
  Channel torsion, axial;
  // The pipe's viscous dampings c_t and c_a per metre as read: the run checks what they put on the top against its
  // step budget (CheckTopDamping in axial_torsional_run.cpp).
  std::array<double, 2> pipe_damping_per_m{};
  double top_inertia = 0, hoist_mass = 0, bit_inertia = 0, bit_mass = 0;
  double hoist_damping = 0;  // c_h [N s/m]: the hoist's dashpot to the block paying out at the steady V0
  model::PiController pi;
  model::TopDriveLaw law;     // with a DC or induction motor: the plain PI (the reader refuses the rest)
  model::Schedule top_speed;  // rad/s
  model::Schedule hook_force;  // H(t) [N], up
  double weight_on_bit = 0;    // W0 of steady drilling at t = 0 [N] (the target the hook force is set for, or H(0)'s)
  bool axial_coupling = true;
  DcMotor motor;          // between the PI and the top drive when motor.on (k referred to the top drive: n K)
  bool induction_on = false;
  model::InductionMotor induction;  // between the PI and the top drive when induction_on
  model::Gear gear;                 // between the motor and the top drive
  // The top drive's own speed carries its inertia, and with a rigid gear the motor's.
  double TopInertia() const { return top_inertia + gear.InertiaAddedToNode(); }
  std::optional<model::JeffcottBha> unbalance;  // the BHA's lateral motion at the bit (absent: none)
  std::optional<model::HoistRig> rig;           // the hoisting rig above the top drive (absent: the hook force H)

  // The bit's inertia against its angular acceleration when the BHA moves laterally with it: eliminating x'' and
  // y'' from seed eq. 23 leaves J_b + m e^2 - (m e)^2 / (M + m) (J_b itself without an unbalance).
  double EffectiveBitInertia() const {
    if (!unbalance) return bit_inertia;
    const double me = unbalance->Moment();
    return bit_inertia + me * unbalance->eccentricity - me * me / unbalance->TotalMass();
  }
};

// Steady drilling at top speed omega with weight on bit W0: depth of cut per revolution, speeds, torques.
struct Steady {
  double omega, depth, rop, wob, tob;
};
inline Steady SteadyDrilling(const Model& md, double omega) {
  Steady s;
  s.omega = omega;
  s.wob = md.weight_on_bit;
  s.depth = std::max(0.0, (md.weight_on_bit - md.ContactForce()) / md.CutWeightPerDepth());
  s.rop = s.depth * omega / (2 * kPi);  // d = n V t_n with t_n = 2 pi / (n omega)
  s.tob = md.SteadyTorque(md.weight_on_bit, omega);
  return s;
}

// Runs the model from steady drilling at its set-points: the trajectory's channels and the run's statistics.
RunResult Simulate(const Model& md, const RunSettings& settings);

// Throws std::domain_error where the top's induction motor cannot carry the steady torque at the set-point.
void CheckSteadyStart(const Model& md);

}  // namespace drillwave::cases::axial_torsional
