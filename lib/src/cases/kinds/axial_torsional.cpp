// Model kind "axial_torsional": coupled axial and torsional waves in a pipe and optional BHA sections, a lumped bit,
// and the Richard-Germay-Detournay bit-rock law with the state-dependent cut delay t_n (DESIGN.md §1-3, chapter seed
// 2.28-2.33; the baseline model of shared/recordings/synthetic/BASELINE.md).
//
// Each channel (torsion: angular speed and torque; axial: speed, down positive, and force) is a waves::WaveChain of m
// sub-sections (the pipe's, then the BHA's) joined by massless nodes, with viscous damping, buoyant weight, side
// friction and Kelvin-Voigt damping as that chain carries them; this kind assembles the two chains with the top, the
// hoist and the bit.
// Top: a top drive of inertia J_td under a PI speed controller; a hoist of mass M_td held by the hook force H: constant,
// set for a target weight on bit, or a schedule H(t) (chapter eq. 2.23: M_top U_tt(0) = E A U_s(0) + H(t)); or, with
// hoist/rig, hanging from the two-mass hoisting rig of eq. 2.22 (model::HoistRig: rigid hook, constant pay-out).
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
// U = V t + h(Omega t) in the prehistory, BASELINE.md's start), which keep the waves free of jumps: a jump in a node
// speed would travel through every sub-section, and only inputs are tracked as breakpoints here.
// The rock's strength may vary with the drilled depth U (rock/strength_heterogeneity: eps and sigma l times 1 + g(U),
// a smooth seeded field), a disturbance inside the bit-rock law that also keeps the right-hand side a pure function.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <queue>
#include <stdexcept>

#include "drillwave/analysis/axial_torsional_linearization.hpp"
#include "drillwave/bitrock/rgd.hpp"
#include "drillwave/cases/kinds.hpp"
#include "drilling_run.hpp"
#include "drillwave/cases/statistics.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/integration/hermite_history.hpp"
#include "drillwave/integration/simulator.hpp"
#include "drillwave/model/gear.hpp"
#include "drillwave/model/hoist_rig.hpp"
#include "drillwave/model/induction_motor.hpp"
#include "drillwave/model/pi_controller.hpp"
#include "drillwave/model/schedule.hpp"
#include "drillwave/waves/wave_chain.hpp"
#include "string_components.hpp"
#include "top_components.hpp"

namespace drillwave::cases {
namespace {

using integration::Side;
using io::JsonReader;
using Range = io::Range;
constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

// One wave channel: the pipe's and the BHA's sub-sections as a chain (waves::WaveChain).
using Channel = waves::ChainSpec;

// DC motor of the top drive (the torsional_wave kind's dc_motor top): torque constant K = back-emf constant.
struct DcMotor {
  bool on = false;
  double k = 0, resistance = 0, inductance = 0;
  // Armature voltage that makes the motor follow the PI: at steady state K I = u_PI with w_top = Omega_ref.
  double Voltage(double u_pi, double omega_ref) const { return resistance / k * u_pi + k * omega_ref; }
  double CurrentRate(double voltage, double w_top, double current) const {
    return (voltage - k * w_top - resistance * current) / inductance;
  }
};

// The bit-rock law's parameters and forces are bitrock::RgdLaw's (a, zeta, eps, sigma_l, mu, gamma, blades, Stribeck).
struct Model : bitrock::RgdLaw {
  int m = 20;
  double length = 0;
  Channel torsion, axial;
  double top_inertia = 0, hoist_mass = 0, bit_inertia = 0, bit_mass = 0;
  double hoist_damping = 0;  // c_h [N s/m]: the hoist's dashpot to the block paying out at the steady V0
  model::PiController pi;
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
  // Supply frequency of the V/f drive for the PI's torque demand u at drive speed w (both on the top drive's side).
  double SupplyFrequency(double u_pi, double drive_speed) const {
    return induction.SupplyForTorque(u_pi / gear.ratio, gear.ratio * drive_speed);
  }
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

using bitrock::Axial;
using bitrock::Turn;

// Steady drilling at top speed omega with weight on bit W0: depth of cut per revolution, speeds, torques.
struct Steady {
  double omega, depth, rop, wob, tob;
};
Steady SteadyDrilling(const Model& md, double omega) {
  Steady s;
  s.omega = omega;
  s.wob = md.weight_on_bit;
  s.depth = std::max(0.0, (md.weight_on_bit - md.ContactForce()) / md.CutWeightPerDepth());
  s.rop = s.depth * omega / (2 * kPi);  // d = n V t_n with t_n = 2 pi / (n omega)
  s.tob = md.CutTorquePerDepth() * s.depth + md.FrictionArm(omega) * md.ContactForce();
  return s;
}

// State: 0 bit angle, 1 bit position, 2 top speed, 3 bit speed, 4 hoist speed, 5 bit axial speed, 6 PI integral;
// with a motor 7 its current; with an unbalance 8-11 the BHA's lateral x, y, x', y' (and 7 unused, held at 0); with
// an induction motor or a compliant gear 12-15 the motor's fluxes and 16-17 the motor's speed (referred to the top
// drive) and the gear's twist; with a hoisting rig 18-20 its derrick displacement and speed and the cable's stretch
// (the unused ones held at 0).
enum Index {
  kPhi = 0, kU, kWtop, kWbit, kVtop, kVbit, kZ, kDim, kCurrent = kDim, kX, kY, kXd, kYd, kFullDim,
  kFlux = kFullDim, kMotorSpeed = kFlux + 4, kTwist, kTopDim, kRig = kTopDim, kRigDim = kRig + 3
};

class Process {
 public:
  using State = std::vector<double>;
  explicit Process(const Model& md)
      : md_(md), steady_(SteadyDrilling(md, md.top_speed.Value(0.0))),
        cut_(md.blades, steady_.omega, steady_.rop, md.surface_passes, md.bottom_roughness) {
    InitializeWaves();
    // Throws std::domain_error when the motor cannot carry the steady torque (below its pull-out torque).
    if (md.induction_on)
      steady_supply_hz_ =
          md.induction.SteadySupplyFrequency(top_torque0_ / md.gear.ratio, md.gear.ratio * steady_.omega);
  }

  // --- Simulator interface --------------------------------------------------------------------------------
  int Dimension() const {
    if (md_.rig) return kRigDim;
    if (md_.induction_on || md_.gear.compliant()) return kTopDim;
    return md_.unbalance.has_value() ? kFullDim : md_.motor.on ? kDim + 1 : kDim;
  }
  double MaxStep() const { return std::min(md_.torsion.ShortestPiece(), md_.axial.ShortestPiece()); }
  void BeginStep(double t0) { step_start_ = t0; }

  State InitialState() const {
    State x(Dimension(), 0.0);
    x[kWtop] = steady_.omega;
    x[kWbit] = steady_.omega;
    x[kVtop] = x[kVbit] = steady_.rop;
    // The PI holds the steady top torque with its integral part, the motor with its steady current (DC) or fluxes
    // (induction: at the supply frequency that gives the steady torque), the gear with its twist.
    x[kZ] = md_.pi.IntegralHolding(top_torque0_);
    if (md_.motor.on) x[kCurrent] = top_torque0_ / md_.motor.k;
    if (md_.induction_on) {
      const auto psi = md_.induction.SteadyFluxes(steady_supply_hz_, md_.gear.ratio * steady_.omega);
      std::copy(psi.begin(), psi.end(), x.begin() + kFlux);
      const double n = md_.gear.ratio, u = n * md_.induction.TorqueDemandFor(steady_supply_hz_, n * steady_.omega);
      x[kZ] = md_.pi.IntegralHolding(u);
    }
    if (md_.gear.compliant()) {
      x[kMotorSpeed] = steady_.omega;
      x[kTwist] = top_torque0_ / md_.gear.stiffness;
    }
    return x;
  }

  void Derivatives(const State& x, State& dx, double t) const {
    const Side side = t <= step_start_ ? Side::kRight : Side::kLeft;
    const double omega_ref = md_.top_speed.Evaluate(t, t > step_start_).first;
    const Ends ends = StringEnds(x, t, side);
    const BitForces f = Forces(x, t, side, ends);
    dx[kPhi] = rg_.turn == Turn::kStuck ? 0.0 : x[kWbit];
    dx[kU] = rg_.axial == Axial::kHeld && rg_.contact ? 0.0 : x[kVbit];
    // Top drive (with its motor and gear) and hoist. States a component does not use stay at 0.
    if (Dimension() >= kTopDim) std::fill(dx.begin() + kDim, dx.end(), 0.0);
    const double vd = DriveSpeed(x), u = TopTorque(x, omega_ref);
    if (md_.motor.on)
      dx[kCurrent] = md_.motor.CurrentRate(md_.motor.Voltage(PiOutput(x, omega_ref), omega_ref), vd, x[kCurrent]);
    if (md_.induction_on) {
      const auto rates = md_.induction.FluxRates(Fluxes(x), md_.SupplyFrequency(PiOutput(x, omega_ref), vd),
                                                 md_.gear.ratio * vd);
      std::copy(rates.begin(), rates.end(), dx.begin() + kFlux);
    }
    double into_top = u;
    if (md_.gear.compliant()) {
      into_top = GearTorque(x);
      dx[kMotorSpeed] = (u - into_top) / md_.gear.ReferredMotorInertia();
      dx[kTwist] = vd - x[kWtop];
    }
    dx[kWtop] = (ends.top[0] + into_top) / md_.TopInertia();
    if (md_.rig) {  // the top drive hangs from the rig's travelling block
      const model::HoistRig::State rig = RigState(x);
      dx[kVtop] = md_.rig->TopAcceleration(rig, ends.top[1], x[kVtop], steady_.rop, md_.hook_force.Value(0.0),
                                           md_.hoist_mass);
      const auto rates = md_.rig->Rates(rig, x[kVtop], steady_.rop, t, t > step_start_);
      std::copy(rates.begin(), rates.end(), dx.begin() + kRig);
    } else {
      dx[kVtop] = (ends.top[1] - md_.hook_force.Evaluate(t, t > step_start_).first - HoistDashpot(x)) / md_.hoist_mass;
    }
    dx[kZ] = omega_ref - vd;
    // Bit.
    dx[kWbit] = rg_.turn == Turn::kStuck ? 0.0 : (f.drive_torque - f.torque) / md_.EffectiveBitInertia();
    dx[kVbit] = rg_.axial == Axial::kHeld && rg_.contact ? 0.0 : (f.drive_force - f.weight) / md_.bit_mass;
    if (!md_.axial_coupling) {  // no axial dynamics: the bit drills the steady depth per revolution
      dx[kU] = steady_.depth / (2 * kPi) * std::max(BitSpeed(x), 0.0);
      dx[kVtop] = dx[kVbit] = 0;
    }
    if (md_.unbalance.has_value()) LateralRates(x, dx[kWbit], dx);
  }

  // The waves leaving every node over the piece, checked and prepared by each channel's chain
  // (waves::WaveChain::Prepare); the end speeds from the piece's states, in the regime that holds over it.
  double PrepareCommit(const integration::Piece& p, double abs_tol, double rel_tol) {
    const double h = p.t1 - p.t0, tq = p.t0 + 0.25 * h;
    state_quarter_.resize(p.x0.size());
    integration::InterpolatePiece(p, tq, state_quarter_);
    double worst = 0;
    for (int c = 0; c < 2; ++c) {
      const waves::WaveChain::StepEnds step{p.t0, p.t1, EndSpeeds(c, p.x0), EndRates(c, p.f0),
                                            EndSpeeds(c, state_quarter_), EndSpeeds(c, p.x_mid),
                                            EndSpeeds(c, p.x1), EndRates(c, p.f1)};
      worst = std::max(worst, chains_[c].Prepare(step, abs_tol, rel_tol));
    }
    return worst;
  }

  void Commit(const integration::Piece& p) {
    // A node's waves are read one piece's travel time later, never earlier: keeping two of the longest makes the
    // histories a few dozen pieces each, which stay in cache.
    const double read_back = 2 * std::max(md_.torsion.LongestPiece(), md_.axial.LongestPiece());
    // The kinks just stored next to the top and the bit reach them one piece later: the steps stop there, as at a
    // breakpoint (the state's own dense output is then smooth within each step, and the end waves too).
    while (!end_kinks_.empty() && end_kinks_.top() < p.t1) end_kinks_.pop();
    arriving_kinks_.clear();
    for (waves::WaveChain& chain : chains_) chain.Commit(p.t0, p.t1, read_back, arriving_kinks_);
    for (double t : arriving_kinks_) end_kinks_.push(t);
    const double keep = 2 * std::max(md_.torsion.travel_time(), md_.axial.travel_time()) + 1.0;
    cut_.Commit(p, kPhi, kU, rg_.contact, rg_.last_contact_change, keep);
  }

  // Witnesses: bitrock::RgdRegimes's (0, 1 rotation; 2, 3 axial; 4 contact).
  int NumWitnesses() const { return bitrock::RgdRegimes::kWitnesses; }
  double Witness(int k, double t, const State& x) const {
    const Side side = Side::kLeft;
    if (k >= 2 && !md_.axial_coupling) return 1.0;  // always on bottom and advancing
    return rg_.Witness(
        k, x[kWbit], x[kVbit], md_.ContactForceAt(x[kU]), [&] { return Forces(x, t, side); },
        [&] { return DepthOfCut(x, t, side); });
  }

  bool OnEvent(int k, double t, State& x) {
    const Side side = Side::kLeft;
    for (waves::WaveChain& chain : chains_) chain.ForgetStart();  // the regime (and the bit's waves) may change here
    const Turn turn_before = rg_.turn;
    const bool changed =
        rg_.OnEvent(k, t, x[kWbit], x[kVbit], md_.ContactForceAt(x[kU]), [&] { return Forces(x, t, side); });
    if (k <= 1) {
      if (rg_.turn == Turn::kStuck) ++stick_onsets_, stuck_.push_back({t, kInf});
      if (turn_before == Turn::kStuck && !stuck_.empty()) stuck_.back().end_s = t;
    }
    return changed;
  }

  double NextBreakpoint() const {
    const double rig = md_.rig ? md_.rig->tension_change.NextKnotAfter(passed_) : kInf;
    const double input = std::min({md_.top_speed.NextKnotAfter(passed_), md_.hook_force.NextKnotAfter(passed_), rig});
    return end_kinks_.empty() ? input : std::min(input, end_kinks_.top());
  }
  void OnBreakpoint(double t) {
    passed_ = t;
    for (waves::WaveChain& chain : chains_) chain.ForgetStart();  // an input may jump here, or a kink arrive at an end
    while (!end_kinks_.empty() && end_kinks_.top() <= t + 1e-12 * std::max(1.0, std::abs(t))) end_kinks_.pop();
  }

  // --- Outputs --------------------------------------------------------------------------------------------
  struct Sample {
    double top_speed, bit_speed, top_torque, bit_torque, wob, hookload, depth, bit_axial_speed, tn, stuck, off_bottom;
    double top_current, lateral_displacement, motor_speed, gear_torque;
  };
  Sample Sampled(double t, const State& x, const State& dx) const {
    const Side side = Side::kLeft;
    const BitForces f = Forces(x, t, side);
    const auto omega_ref = md_.top_speed.Value(t);
    Sample s;
    s.top_speed = x[kWtop];
    s.bit_speed = rg_.turn == Turn::kStuck ? 0.0 : x[kWbit];
    s.top_torque = TopTorque(x, omega_ref);
    s.bit_torque = rg_.turn == Turn::kStuck ? f.drive_torque : f.torque;
    s.wob = f.weight;
    s.hookload = md_.hook_force.Value(t) + HoistDashpot(x) + md_.hoist_mass * dx[kVtop];
    // With the rig the string's pull on the top drive, as without it: the cable's pull plus (M2 + M_td) v'.
    if (md_.rig)
      s.hookload = md_.rig->CablePull(RigState(x), x[kVtop], steady_.rop, md_.hook_force.Value(0.0)) +
                   (md_.rig->block_mass + md_.hoist_mass) * dx[kVtop];
    s.depth = rg_.contact ? f.depth : std::min(f.depth, 0.0);
    s.bit_axial_speed = !md_.axial_coupling ? dx[kU] : rg_.axial == Axial::kHeld && rg_.contact ? 0.0 : x[kVbit];
    s.tn = f.tn;
    s.stuck = rg_.turn == Turn::kStuck ? 1.0 : 0.0;
    s.off_bottom = rg_.contact ? 0.0 : 1.0;
    s.top_current = md_.motor.on ? x[kCurrent] : md_.induction_on ? md_.induction.StatorCurrentRms(Fluxes(x)) : 0.0;
    s.motor_speed = md_.gear.compliant() ? md_.gear.ratio * x[kMotorSpeed] : 0.0;
    s.gear_torque = md_.gear.compliant() ? GearTorque(x) : 0.0;
    s.lateral_displacement = md_.unbalance.has_value() ? std::hypot(x[kX], x[kY]) : 0.0;
    return s;
  }
  const std::vector<StuckInterval>& stuck_intervals() const { return stuck_; }
  const Steady& steady() const { return steady_; }
  double steady_supply_hz() const { return steady_supply_hz_; }

 private:
  using BitForces = bitrock::RgdForces;

  // Force of the string on the top node and on the bit node of each channel (0 torsion, 1 axial) at the state's end
  // speeds, with the end nodes' own share of damping and weight.
  struct Ends {
    double top[2], bit[2];
  };

  double EndSpeed(int c, bool bit, const State& x) const {
    if (!bit) return c == 0 ? x[kWtop] : x[kVtop];
    if (c == 0) return rg_.turn == Turn::kStuck ? 0.0 : x[kWbit];
    return rg_.axial == Axial::kHeld && rg_.contact ? 0.0 : x[kVbit];
  }

  Ends StringEnds(const State& x, double t, Side side) const {
    Ends e;
    for (int c = 0; c < 2; ++c) {
      const waves::ChainEnds f = chains_[c].EndForces(t, side, EndSpeeds(c, x));
      e.top[c] = f.top, e.bit[c] = f.bit;
    }
    return e;
  }
  waves::ChainEnds EndSpeeds(int c, const State& x) const { return {EndSpeed(c, false, x), EndSpeed(c, true, x)}; }
  // The end nodes' accelerations (dx of the state).
  static waves::ChainEnds EndRates(int c, const State& dx) {
    return c == 0 ? waves::ChainEnds{dx[kWtop], dx[kWbit]} : waves::ChainEnds{dx[kVtop], dx[kVbit]};
  }

  // The depth of cut against the rock surface under the blades, and the cut delay t_n through tn (bitrock::CutProfile).
  double DepthOfCut(const State& x, double t, Side side, double* tn = nullptr) const {
    return cut_.DepthOfCut(x[kPhi], x[kU], t, side, rg_.contact, rg_.last_contact_change, tn);
  }

  BitForces Forces(const State& x, double t, Side side) const { return Forces(x, t, side, StringEnds(x, t, side)); }
  BitForces Forces(const State& x, double t, Side side, const Ends& ends) const {
    BitForces f;
    const double w = rg_.turn == Turn::kStuck ? 0.0 : x[kWbit];
    f.drive_torque = ends.bit[0];
    f.drive_force = ends.bit[1];
    if (md_.unbalance.has_value()) f.drive_torque += LateralReaction(x);
    f.depth = DepthOfCut(x, t, side, &f.tn);
    if (!md_.axial_coupling) f.depth = steady_.depth;
    if (!rg_.contact) return f;
    // Cutting only into new rock: not while turning backwards, nor before the bit is back past its furthest angle.
    const bool cutting = rg_.turn != Turn::kBackward && x[kPhi] >= cut_.Furthest(t);
    md_.OnBottom(rg_.turn, rg_.axial, w, cutting, x[kU], f);
    if (!md_.axial_coupling) f.weight = md_.weight_on_bit;
    return f;
  }

  // --- Top drive and BHA components ---------------------------------------------------------------------------
  double PiOutput(const State& x, double omega_ref) const {
    return md_.pi.Output(omega_ref, DriveSpeed(x), x[kZ]);
  }
  // Torque of the drive (on the top drive's side): the PI's output, or the motor's K I when a DC motor sits between
  // them, or n T_e of an induction motor. It turns the top drive, or the motor behind a compliant gear.
  double TopTorque(const State& x, double omega_ref) const {
    if (md_.motor.on) return md_.motor.k * x[kCurrent];
    if (md_.induction_on) return md_.gear.ratio * md_.induction.Torque(Fluxes(x));
    return PiOutput(x, omega_ref);
  }
  // The speed the PI and the motor see (on the top drive's side): the top drive's, or the motor's behind a compliant
  // gear.
  double DriveSpeed(const State& x) const { return md_.gear.compliant() ? x[kMotorSpeed] : x[kWtop]; }
  double GearTorque(const State& x) const { return md_.gear.Torque(x[kTwist], x[kMotorSpeed], x[kWtop]); }
  static model::InductionMotor::Fluxes Fluxes(const State& x) {
    return {x[kFlux], x[kFlux + 1], x[kFlux + 2], x[kFlux + 3]};
  }
  double BitSpeed(const State& x) const { return rg_.turn == Turn::kStuck ? 0.0 : x[kWbit]; }
  // The hoist's dashpot force (up) against the block paying out at the steady rate of penetration.
  double HoistDashpot(const State& x) const { return md_.hoist_damping * (x[kVtop] - steady_.rop); }
  static model::HoistRig::State RigState(const State& x) { return {x[kRig], x[kRig + 1], x[kRig + 2]}; }

  // The Jeffcott rotor's torque on the bit at zero angular acceleration (the rest is in EffectiveBitInertia), and
  // its rates given the bit's angular acceleration phi_dd (model::JeffcottBha).
  static model::JeffcottBha::Lateral Lateral(const State& x) { return {x[kX], x[kY], x[kXd], x[kYd]}; }
  double LateralReaction(const State& x) const { return md_.unbalance->Reaction(x[kPhi], BitSpeed(x), Lateral(x)); }
  void LateralRates(const State& x, double phi_dd, State& dx) const {
    const auto rates = md_.unbalance->Rates(x[kPhi], BitSpeed(x), phi_dd, Lateral(x));
    std::copy(rates.begin(), rates.end(), dx.begin() + kX);
  }

  // Steady drilling: every node of a channel at the same speed, the bit's reaction carried up the chain; the top
  // drive balances the top section.
  void InitializeWaves() {
    chains_.reserve(2);
    chains_.emplace_back(md_.torsion, steady_.omega, steady_.tob);
    chains_.emplace_back(md_.axial, steady_.rop, steady_.wob);
    top_torque0_ = chains_[0].steady_top_force();
  }

  const Model& md_;
  Steady steady_;
  std::vector<waves::WaveChain> chains_;  // torsion, axial
  bitrock::CutProfile cut_;
  double top_torque0_ = 0;
  double steady_supply_hz_ = 0;  // induction motor: the supply frequency of steady drilling
  bitrock::RgdRegimes rg_;
  double step_start_ = 0, passed_ = 0;
  int stick_onsets_ = 0;
  std::vector<StuckInterval> stuck_;
  State state_quarter_;
  // Times at which kinks reach the top or the bit (breakpoints), earliest first.
  std::priority_queue<double, std::vector<double>, std::greater<double>> end_kinks_;
  std::vector<double> arriving_kinks_;  // Commit's scratch
};

// hoist/rig: the two-mass hoisting rig (model::HoistRig).
model::HoistRig ReadHoistRig(const JsonReader& r) {
  model::HoistRig rig;
  rig.derrick_mass = r.Number("derrick_mass_kg", Range::Positive());
  rig.block_mass = r.Number("block_mass_kg", Range::Positive());
  rig.derrick_damping = r.Number("derrick_damping_Ns_per_m", Range::NonNegative());
  rig.block_damping = r.Number("block_damping_Ns_per_m", Range::NonNegative());
  rig.ground_stiffness = r.Number("ground_stiffness_N_per_m", Range::Positive());
  rig.cable_stiffness = r.Number("cable_stiffness_N_per_m", Range::Positive());
  if (r.Has("cable_tension_change_N"))
    rig.tension_change = model::Schedule::FromJson(r.Raw("cable_tension_change_N"), r.PathOf("cable_tension_change_N"));
  r.Finish();
  return rig;
}

// The induction motor and the gear of the top drive block (the DC motor is read beside them).
void ReadTopMotorAndGear(const JsonReader& top, Model& md) {
  if (top.Has("induction_motor")) {
    if (md.motor.on)
      throw InputError(top.PathOf("induction_motor"),
                       "expected either a DC motor (motor) or an induction motor, not both");
    md.induction_on = true;
    md.induction = ReadInductionMotor(top.Object("induction_motor"));
  }
  md.gear = ReadGear(top);
  md.motor.k *= md.gear.ratio;  // a DC motor's constant referred to the top drive: torque n K I, back-emf n K w
}

class AxialTorsionalModel : public PreparedModel {
 public:
  explicit AxialTorsionalModel(Model md) : md_(std::move(md)) {}
  // Steady drilling at the inputs' final values and its linearization (analysis/axial_torsional_linearization.hpp).
  std::vector<LinearizedOperatingPoint> Linearize() const override;

  RunResult Run(const RunSettings& settings) const override {
    Process process(md_);
    std::vector<double> x = process.InitialState();
    DrillingSamples d;
    std::vector<double> hook, current, lateral, motor_rpm, gear_torque;
    std::vector<double> dx(x.size());
    auto sample = [&](double t, const std::vector<double>& s) {
      process.BeginStep(t);  // look-ups at t from the committed history (left limits inside the last piece)
      process.Derivatives(s, dx, t);
      const Process::Sample v = process.Sampled(t, s, dx);
      d.time.push_back(t), d.top.push_back(v.top_speed), d.bit.push_back(v.bit_speed);
      d.top_torque.push_back(v.top_torque), d.bit_torque.push_back(v.bit_torque), d.wob.push_back(v.wob);
      hook.push_back(v.hookload), d.depth.push_back(v.depth), d.vbit.push_back(v.bit_axial_speed);
      d.tn.push_back(v.tn), d.stuck.push_back(v.stuck), d.off.push_back(v.off_bottom), d.angle.push_back(s[kPhi]);
      if (md_.motor.on || md_.induction_on) current.push_back(v.top_current);
      if (md_.gear.compliant()) motor_rpm.push_back(v.motor_speed * 30 / kPi), gear_torque.push_back(v.gear_torque);
      if (md_.unbalance.has_value()) lateral.push_back(v.lateral_displacement);
    };
    sample(0.0, x);
    const auto observer = integration::SampleEvery(settings.output_interval_s, sample);
    // (No floor on the history's step: the kinks that events send through the sub-sections are followed, see
    // PrepareCommit; before they were, 0.1 ms steps were accepted across them.)
    const integration::IntegratorOptions& integrator = settings.integrator;
    integration::Simulator<Process> sim(process, integrator);
    sim.Integrate(0.0, x, settings.duration_s, observer);

    double lateral_sum = 0, lateral_max = 0;
    int n = 0;
    if (md_.unbalance.has_value())
      for (std::size_t i = 0; i < d.time.size(); ++i)
        if (d.time[i] >= settings.window_begin_s && d.time[i] <= settings.window_end_s)
          lateral_sum += lateral[i], lateral_max = std::max(lateral_max, lateral[i]), ++n;
    RunResult result;
    const Steady& s = process.steady();
    SummarizeDrillingRun(d, std::move(hook), process.stuck_intervals(), settings, {s.depth, s.rop, s.tob},
                         sim.stats(), result);
    result.summary["hook_force_N"] = md_.hook_force.Value(0.0);
    if (md_.rig) {  // the rig's undamped modes with the top drive on the block, string removed (model::HoistRig)
      const auto w = md_.rig->NaturalFrequencies(md_.hoist_mass);
      result.summary["rig_natural_frequencies_rad_s"] = {w[0], w[1]};
    }
    if (md_.unbalance.has_value()) {  // whirl radius over the window, and the closed form at the steady bit speed
      result.summary["whirl_amplitude_mean_m"] = n ? lateral_sum / n : 0.0;
      result.summary["whirl_amplitude_max_m"] = lateral_max;
      result.summary["steady_whirl_amplitude_m"] = md_.unbalance->WhirlAmplitude(s.omega);
      result.summary["lateral_natural_frequency_rad_s"] = md_.unbalance->NaturalFrequency();
    }
    if (md_.motor.on || md_.induction_on) {  // DC: armature current; induction: stator rms
      result.channels.push_back({"top_current_A", std::move(current)});
      result.plot_panels.push_back({"top_current_A"});
    }
    if (md_.induction_on) result.summary["steady_supply_frequency_Hz"] = process.steady_supply_hz();
    if (md_.gear.compliant()) {
      result.channels.push_back({"motor_rpm", std::move(motor_rpm)});
      result.channels.push_back({"gear_torque_Nm", std::move(gear_torque)});
      result.plot_panels.push_back({"gear_torque_Nm", "top_torque_Nm"});
    }
    if (md_.unbalance.has_value()) {
      result.channels.push_back({"lateral_displacement_m", std::move(lateral)});
      result.plot_panels.push_back({"lateral_displacement_m"});
    }
    return result;
  }

 private:
  Model md_;
};

// A section of the string (the pipe, then the BHA): geometry, viscous damping per metre, sub-sections.
struct Section {
  double length, outer, inner, c_t, c_a;
  int pieces;
  double Area() const { return kPi / 4 * (outer * outer - inner * inner); }
  double Polar() const { return kPi / 32 * (std::pow(outer, 4) - std::pow(inner, 4)); }
};
struct StringSpec {
  double length = 0;              // top drive to bit
  std::vector<Section> sections;  // top to bottom
  double e_mod = 0, g_mod = 0, rho = 0, rho_mud = 0;
  double eta_t = 0, eta_a = 0;    // Kelvin-Voigt retardation times [s]
  double side_torque_per_m = 0, side_from = 0, side_to = 0;
};

// One section below the pipe (the BHA, or a part of it: heavy-weight pipe, collars, ...).
Section ReadBha(const JsonReader& c, const Section& pipe, double string_length) {
  Section bha;
  bha.length = c.Number("length_m", Range::Positive());
  if (bha.length >= string_length)
    throw InputError(c.PathOf("length_m"), "expected less than the string's length_m = " +
                                               ReadableNumber(string_length) + " m (the BHA is its lowest part)");
  bha.outer = c.Number("outer_diameter_m", Range::Positive());
  bha.inner = c.Number("inner_diameter_m", Range::NonNegative());
  if (bha.inner >= bha.outer) throw InputError(c.PathOf("inner_diameter_m"), "expected a value below outer_diameter_m");
  bha.c_t = c.Number("torsional_damping_Nms_per_rad_m", Range::NonNegative(), pipe.c_t);
  bha.c_a = c.Number("axial_damping_Ns_per_m2", Range::NonNegative(), pipe.c_a);
  // By default pieces about as long as the pipe's, so that the travel times are near each other (the step is capped
  // at the shortest).
  const double pipe_piece = pipe.length / pipe.pieces;
  const int pieces = std::clamp(static_cast<int>(std::lround(bha.length / pipe_piece)), 1, 400);
  bha.pieces = c.Integer("subsections", 1, 400, pieces);
  c.Finish();
  return bha;
}

StringSpec ReadString(const JsonReader& s) {
  StringSpec sp;
  Section pipe;
  sp.length = s.Number("length_m", Range::Positive());
  pipe.outer = s.Number("outer_diameter_m", Range::Positive());
  pipe.inner = s.Number("inner_diameter_m", Range::NonNegative());
  if (pipe.inner >= pipe.outer)
    throw InputError(s.PathOf("inner_diameter_m"), "expected a value below outer_diameter_m");
  sp.e_mod = s.Number("youngs_modulus_Pa", Range::Positive());
  sp.g_mod = s.Number("shear_modulus_Pa", Range::Positive());
  sp.rho = s.Number("density_kg_m3", Range::Positive());
  sp.rho_mud = s.Number("mud_density_kg_m3", Range::NonNegative(), 0.0);
  if (sp.rho_mud >= sp.rho) throw InputError(s.PathOf("mud_density_kg_m3"), "expected a value below density_kg_m3");
  pipe.c_t = s.Number("torsional_damping_Nms_per_rad_m", Range::NonNegative());
  pipe.c_a = s.Number("axial_damping_Ns_per_m2", Range::NonNegative());
  sp.eta_t = ReadKelvinVoigt(s);
  sp.eta_a = ReadKelvinVoigt(s, "axial_kelvin_voigt_s");
  if (s.Has("side_friction")) {
    const JsonReader f = s.Object("side_friction");
    sp.side_torque_per_m = f.Number("torque_per_m_Nm", Range::NonNegative());
    sp.side_from = f.Number("from_m", Range::NonNegative(), 0.0);
    sp.side_to = f.Number("to_m", Range::NonNegative(), 1e300);
    if (sp.side_to <= sp.side_from) throw InputError(f.PathOf("to_m"), "expected a depth below from_m");
    f.Finish();
  }
  pipe.pieces = s.Integer("subsections", 2, 400, 20);
  pipe.length = sp.length;
  sp.sections = {pipe};
  if (s.Has("bha")) {  // one section, or several top to bottom (heavy-weight pipe, collars, ...)
    const bool several = s.Raw("bha").is_array();
    const std::vector<JsonReader> parts = several ? s.ObjectArray("bha") : std::vector<JsonReader>{s.Object("bha")};
    if (parts.empty()) throw InputError(s.PathOf("bha"), "expected at least one section");
    double below_pipe = 0;
    for (const JsonReader& part : parts) below_pipe += part.Number("length_m", Range::Positive());
    if (below_pipe >= sp.length && several)
      throw InputError(s.PathOf("bha"), "expected sections shorter together (" + ReadableNumber(below_pipe) +
                                            " m) than the string's length_m = " + ReadableNumber(sp.length) + " m");
    sp.sections[0].length = std::max(sp.length - below_pipe, 0.0);  // (a single section too long: ReadBha says so)
    for (const JsonReader& part : parts) sp.sections.push_back(ReadBha(part, sp.sections[0], sp.length));
  }
  s.Finish();
  return sp;
}

// Channels of sub-sections, pipe then BHA: damping and buoyant weight of each piece lumped at its two nodes (half at
// each), which keeps the d'Alembert reduction exact inside every piece.
void BuildChannels(const StringSpec& sp, double g, Model& md) {
  md.m = 0;
  for (const Section& section : sp.sections) md.m += section.pieces;
  for (Channel* ch : {&md.torsion, &md.axial}) {
    ch->z.assign(md.m, 0.0), ch->tau.assign(md.m, 0.0);
    ch->damping.assign(md.m + 1, 0.0), ch->load.assign(md.m + 1, 0.0), ch->coulomb.assign(md.m + 1, 0.0);
  }
  if (sp.eta_t > 0) md.torsion.kv.assign(md.m, 0.0);
  if (sp.eta_a > 0) md.axial.kv.assign(md.m, 0.0);
  int k = 0;
  double depth = 0;  // of the top of piece k
  for (const Section& section : sp.sections) {
    const double piece = section.length / section.pieces, weight_per_m = (sp.rho - sp.rho_mud) * section.Area() * g;
    for (int i = 0; i < section.pieces; ++i, ++k, depth += piece) {
      md.torsion.z[k] = section.Polar() * std::sqrt(sp.g_mod * sp.rho);
      md.torsion.tau[k] = piece / std::sqrt(sp.g_mod / sp.rho);
      md.axial.z[k] = section.Area() * std::sqrt(sp.e_mod * sp.rho);
      md.axial.tau[k] = piece / std::sqrt(sp.e_mod / sp.rho);
      if (md.torsion.kelvin_voigt()) md.torsion.kv[k] = sp.eta_t * sp.g_mod * section.Polar() / piece;
      if (md.axial.kelvin_voigt()) md.axial.kv[k] = sp.eta_a * sp.e_mod * section.Area() / piece;
      for (int end = 0; end < 2; ++end) {
        const int j = k + end;
        md.torsion.damping[j] += 0.5 * section.c_t * piece;
        md.axial.damping[j] += 0.5 * section.c_a * piece;
        md.axial.load[j] += 0.5 * weight_per_m * piece;
        // Side friction between from_m and to_m on the internal (massless) nodes, over the half piece each stands for.
        if (j == 0 || j == md.m) continue;
        const double lo = std::max(depth + 0.5 * end * piece, sp.side_from);
        const double hi = std::min(depth + 0.5 * (end + 1) * piece, sp.side_to);
        md.torsion.coulomb[j] += sp.side_torque_per_m * std::max(0.0, hi - lo);
      }
    }
  }
}

// The axial balance of steady drilling (chapter eq. 2.23 at rest in the moving frame): H = W_b - W0 - C V0, with the
// buoyant weight W_b of string and bit, the viscous drag C = sum c_a L per unit rate of penetration, and
// V0 = d0 Omega / 2 pi, d0 = (W0 - a sigma l) / (a zeta eps) (SteadyDrilling). Solved for H or, linear in W0, for W0.
struct HoistBalance {
  double buoyant_weight = 0, drag_per_speed = 0;
  double RopPerWob(double omega, const Model& md) const { return omega / (2 * kPi) / md.CutWeightPerDepth(); }
  double HookForce(const Model& md, double omega, double wob) const {
    return buoyant_weight - wob - drag_per_speed * RopPerWob(omega, md) * std::max(wob - md.ContactForce(), 0.0);
  }
  double WeightOnBit(const Model& md, double omega, double hook) const {
    const double kappa = drag_per_speed * RopPerWob(omega, md);
    return (buoyant_weight - hook + kappa * md.ContactForce()) / (1 + kappa);
  }
};
HoistBalance Balance(const Model& md, const StringSpec& string) {
  HoistBalance b;
  for (double l : md.axial.load) b.buoyant_weight += l;
  for (const Section& section : string.sections) b.drag_per_speed += section.c_a * section.length;
  return b;
}

// A dashpot at the top (the hoist's, to a block moving at the steady speed) adds to the top node's damping: the
// linearization sees speed perturbations only.
analysis::WaveChannel LinearChannel(const Channel& ch, double top_inertia, double bit_inertia,
                                    double top_dashpot = 0) {
  analysis::WaveChannel linear{ch.z, ch.tau, ch.damping, top_inertia, bit_inertia, ch.kv};
  linear.node_damping.front() += top_dashpot;
  return linear;
}

// The top drive's motor and gear as the linearization's network top. The DC motor's voltage R/K u_PI + K Omega_ref is
// a PI in volts (gains R/K kp, R/K ki) plus a constant; its constant, referred here (n K), goes back to the motor's
// own K, which the network refers again.
void DescribeTopDrive(const Model& md, analysis::AxialTorsionalString& string) {
  string.gear = md.gear;
  if (md.motor.on) {
    string.top_drive = waves::Drive::kDcMotorSpeed;
    string.dc_motor = {md.motor.k / md.gear.ratio, md.motor.resistance, md.motor.inductance, 0};
    string.pi.kp = md.motor.resistance / md.motor.k * md.pi.kp;
    string.pi.ki = md.motor.resistance / md.motor.k * md.pi.ki;
  } else if (md.induction_on) {
    string.top_drive = waves::Drive::kInductionMotorSpeed;
    string.induction_motor = md.induction;
  }
}

// What the top drive supplies in steady drilling at omega: the bit's torque and every node's damping and Coulomb
// friction (as InitializeWaves balances the top section).
double SteadyTopTorque(const Channel& torsion, double bit_torque, double omega) {
  double torque = bit_torque;
  for (std::size_t j = 0; j < torsion.damping.size(); ++j)
    torque += torsion.damping[j] * omega - torsion.load[j] + (j > 0 ? torsion.coulomb[j] : 0.0);
  return torque;
}

std::vector<LinearizedOperatingPoint> AxialTorsionalModel::Linearize() const {
  // Steady drilling at the final set-points: the hook force leaves W0 on the bit by the axial balance.
  const double omega = md_.top_speed.knots().back().second;
  HoistBalance balance;
  for (double l : md_.axial.load) balance.buoyant_weight += l;
  for (double c : md_.axial.damping) balance.drag_per_speed += c;  // sum of c_a times piece length
  // The hoist's dashpot pulls against the block paying out at the start's rate V0: at other set-points it carries
  // c_h (V - V0), a drag like the string's with an offset.
  if (md_.hoist_damping > 0) {
    balance.buoyant_weight += md_.hoist_damping * SteadyDrilling(md_, md_.top_speed.Value(0.0)).rop;
    balance.drag_per_speed += md_.hoist_damping;
  }
  Model at = md_;
  if (md_.rig) {
    // The drawworks pays out at the rate of penetration of the start: steady drilling at omega keeps that rate, and
    // the weight on bit cuts its depth per revolution.
    const double rop = SteadyDrilling(md_, md_.top_speed.Value(0.0)).rop;
    at.weight_on_bit = md_.ContactForce() + md_.CutWeightPerDepth() * 2 * kPi * rop / omega;
  } else if (md_.axial_coupling) {
    at.weight_on_bit = balance.WeightOnBit(md_, omega, md_.hook_force.knots().back().second);
  }
  if (!(omega > 0) || !(at.weight_on_bit > md_.ContactForce())) return {};  // no steady drilling
  const Steady s = SteadyDrilling(at, omega);
  analysis::AxialTorsionalString string{LinearChannel(md_.torsion, md_.top_inertia, md_.bit_inertia),
                                        LinearChannel(md_.axial, md_.hoist_mass, md_.bit_mass, md_.hoist_damping),
                                        md_.pi, md_.CutWeightPerDepth(), md_.CutTorquePerDepth(),
                                        md_.blades, md_.axial_coupling};
  DescribeTopDrive(md_, string);
  string.rig = md_.rig;
  string.unbalance = md_.unbalance;
  // The steady whirl of an unbalanced BHA costs the bit a torque too.
  const double whirl_drag = md_.unbalance ? md_.unbalance->SteadyDragTorque(omega) : 0.0;
  const double top_torque = SteadyTopTorque(md_.torsion, s.tob + whirl_drag, omega);
  // Stribeck: d mu / dw = -(mu_s - mu) / w_s e^{-w / w_s} while turning forward.
  const double mu_slope = md_.stribeck_speed > 0 ? -(md_.static_mu - md_.mu) / md_.stribeck_speed *
                                                       std::exp(-omega / md_.stribeck_speed)
                                                 : 0.0;
  const double friction_slope = 0.5 * md_.a * md_.gamma * mu_slope * md_.ContactForce();
  analysis::NetworkLinearization lin;
  try {
    lin = analysis::LinearizeAxialTorsional(string, {omega, s.rop, friction_slope, top_torque});
  } catch (const std::domain_error&) {  // the induction motor cannot carry the steady torque (beyond pull-out)
    return {};
  } catch (const std::invalid_argument& e) {  // parameters out of the linearization's range (e.g. mutated to 1e-300)
    throw InputError("/model", std::string("no linearization for this model: ") + e.what());
  }
  nlohmann::json point = {{"bit_speed_rad_s", omega},
                          {"weight_on_bit_N", s.wob},
                          {"hook_force_N", md_.hook_force.knots().back().second},
                          {"depth_of_cut_m", s.depth},
                          {"rop_m_h", 3600 * s.rop},
                          {"bit_torque_Nm", s.tob},
                          {"top_torque_Nm", top_torque},
                          {"bit_torque_slope_Nms_per_rad", friction_slope},
                          {"cut_delay_s", 2 * kPi / (md_.blades * omega)},
                          {"axial_coupling", md_.axial_coupling}};
  if (md_.unbalance) {
    point["steady_whirl_radius_m"] = md_.unbalance->WhirlAmplitude(omega);
    point["whirl_drag_torque_Nm"] = whirl_drag;
  }
  if (md_.strength_heterogeneity.on()) point["rock_strength_heterogeneity"] = md_.LinearizedRock();
  return {{std::move(point), std::move(lin.state_names), std::move(lin.system)}};
}

class AxialTorsionalKind : public ModelKind {
 public:
  std::string name() const override { return "axial_torsional"; }
  std::string description() const override {
    return "coupled axial-torsional waves in a pipe with a lumped bit and the Richard-Germay-Detournay bit-rock law "
           "(state-dependent cut delay t_n, set-valued wear-flat contact and friction, lift-off); PI top drive, hoist "
           "under constant hook force; optional BHA section, Kelvin-Voigt damping, Stribeck bit friction, DC motor, "
           "BHA mass unbalance (Jeffcott rotor at the bit), two-mass hoisting rig, axial coupling off";
  }
  nlohmann::json FieldSchema() const override {
    nlohmann::json fields = {{"string/length_m", "> 0, top drive to bit"},
            {"string/outer_diameter_m", "> 0"},
            {"string/inner_diameter_m", ">= 0, < outer"},
            {"string/youngs_modulus_Pa", "> 0"},
            {"string/shear_modulus_Pa", "> 0"},
            {"string/density_kg_m3", "> 0, steel"},
            {"string/mud_density_kg_m3", ">= 0, < steel, default 0 (buoyancy only)"},
            {"string/torsional_damping_Nms_per_rad_m", "c_t >= 0, viscous, per metre"},
            {"string/axial_damping_Ns_per_m2", "c_a >= 0, viscous, per metre"},
            {"string/subsections", "integer in [2, 400], default 20: the pipe's pieces (damping and weight lumped at "
                                   "their nodes)"},
            {"string/axial_kelvin_voigt_s", "eta_a in [0, 10] s, default 0: axial N += eta_a E A dv/ds"},
            {"string/bha/length_m", "> 0, < string/length_m: drill collars of the same steel between the pipe and "
                                    "the bit (string/length_m stays top drive to bit). string/bha may also be an "
                                    "array of such sections, top to bottom (heavy-weight pipe, collars, ...)"},
            {"string/bha/outer_diameter_m", "> 0"},
            {"string/bha/inner_diameter_m", ">= 0, < outer"},
            {"string/bha/subsections", "integer in [1, 400], default: pieces about as long as the pipe's"},
            {"string/bha/torsional_damping_Nms_per_rad_m", ">= 0, default the pipe's"},
            {"string/bha/axial_damping_Ns_per_m2", ">= 0, default the pipe's"},
            {"string/side_friction/torque_per_m_Nm", ">= 0: Coulomb friction of the pipe against the borehole "
                                                     "(set-valued: a stopped piece of pipe is held)"},
            {"string/side_friction/from_m", ">= 0, default 0 (measured depth where it starts)"},
            {"string/side_friction/to_m", "> from_m, default: the bit"},
            {"bit/inertia_kgm2", "J_b > 0 (bit, and the BHA unless string/bha distributes it)"},
            {"bit/mass_kg", "M_b > 0"},
            {"axial_coupling", "boolean, default true; false: no axial dynamics, weight on bit held at W0 and depth "
                               "of cut at its steady value"},
            {"top/type", "top_drive (a PI speed controller, the only top of this kind; optional)"},
            {"top/inertia_kgm2", "J_td > 0"},
            {"top/kp_Nms_per_rad", ">= 0"},
            {"top/ki_Nm_per_rad", ">= 0; the run starts, and `stability` linearizes, in steady drilling at the "
                                  "set-point, which only integral action holds: with 0 (a proportional drive) the "
                                  "start is out of balance and the drive settles below its set-point"},
            {"top/speed_rad_s", "set-point schedule [rad/s]"},
            {"top/motor/motor_constant_Nm_per_A", "K > 0: optional DC motor (absent: the PI output is the torque); "
                                                        "V = R/K u_PI + K Omega_ref, La I' = V - K w_top - R I, torque K I"},
            {"top/motor/resistance_ohm", "R > 0"},
            {"top/motor/inductance_H", "La > 0"},
            {"hoist/mass_kg", "M_td > 0"},
            {"hoist/damping_Ns_per_m", "c_h >= 0, default 0: a dashpot from the hoist to the travelling block, which "
                                       "pays out line at the steady rate of penetration V0 (-c_h (v_top - V0); the "
                                       "top's reflection of Aarsnes & van de Wouw 2019); not with hoist/rig"},
            {"hoist/hook_force_N", "H(t) [N], a number or {\"knots\": [[t, v], ...]}, instead of weight_on_bit_N: the run "
                                   "starts in steady drilling under H(0), with W0 = (W_b - H(0) + kappa a sigma l) / "
                                   "(1 + kappa), kappa = c_a L Omega0 / (2 pi a zeta eps), which must exceed a sigma l"},
            {"hoist/weight_on_bit_N", "W0 > a sigma l: the hook force is set so that steady drilling has this weight "
                                      "on bit (H = buoyant weight of pipe, BHA and bit - W0 - c_a L V0)"},
            {"hoist/rig/derrick_mass_kg", "M_rg1 > 0: optional two-mass hoisting rig (chapter eq. 2.22), absent: the "
                                          "hook force; the top drive hangs from the travelling block on a rigid hook, "
                                          "the drawworks pays out line at the steady rate of penetration; needs "
                                          "weight_on_bit_N, not with axial_coupling false"},
            {"hoist/rig/block_mass_kg", "M_rg2 > 0: cables, crown and travelling blocks"},
            {"hoist/rig/derrick_damping_Ns_per_m", "gamma_rg1 >= 0"},
            {"hoist/rig/block_damping_Ns_per_m", "gamma_rg2 >= 0"},
            {"hoist/rig/ground_stiffness_N_per_m", "k_rg01 > 0: derrick to ground"},
            {"hoist/rig/cable_stiffness_N_per_m", "k_rg12 > 0: derrick to travelling block"},
            {"hoist/rig/cable_tension_change_N", "u_F(t) - u_F0 [N], up on the derrick: a number or {\"knots\": "
                                                 "[[t, v], ...]}, default 0 (u_F0: the tension of steady drilling)"},
            {"gravity_m_s2", "> 0, default 9.81"}};
    fields.update(TopComponentFields("top"));
    fields.update(StringComponentFields("string", "bit"));
    fields["string/kelvin_voigt_s"] = fields["string/kelvin_voigt_s"].get<std::string>() +
                                      "; with side_friction the nodes tied by the dashpots are held by it where it "
                                      "suffices (a convex problem solved exactly)";
    fields.update(bitrock::RgdFieldSchema());
    fields["top/induction_motor/pole_pairs"] =
        "p, integer in [1, 64]: optional induction motor (absent: the PI output is the torque) on a V/f supply with "
        "slip-frequency control, f = (p n w_m + u_PI / (n G)) / 2 pi at the measured speed w_m, G = p (V/f)^2 / "
        "(4 pi^2 R_r), slip held below R_r / (L_ls + L_lr); not with motor";
    return fields;
  }

  std::unique_ptr<PreparedModel> Prepare(const JsonReader& r) const override {
    Model md;
    const StringSpec string = ReadString(r.Object("string"));
    md.length = string.length;
    const JsonReader b = r.Object("bit");
    md.bit_inertia = b.Number("inertia_kgm2", Range::Positive());
    md.bit_mass = b.Number("mass_kg", Range::Positive());
    bitrock::ReadRgdBit(b, md);
    md.unbalance = ReadUnbalance(b);
    b.Finish();
    bitrock::ReadRgdRock(r.Object("rock"), md);
    r.RefuseRenamed("top_drive", "/model/top");
    const JsonReader td = r.Object("top");
    td.String("type", {"top_drive"}, "top_drive");
    md.top_inertia = td.Number("inertia_kgm2", Range::Positive());
    md.pi = ReadPiController(td);
    md.top_speed = model::Schedule::FromJson(td.Raw("speed_rad_s"), td.PathOf("speed_rad_s"));
    if (td.Has("motor")) {
      const JsonReader mo = td.Object("motor");
      md.motor.on = true;
      md.motor.k = mo.Number("motor_constant_Nm_per_A", Range::Positive());
      md.motor.resistance = mo.Number("resistance_ohm", Range::Positive());
      md.motor.inductance = mo.Number("inductance_H", Range::Positive());
      mo.Finish();
    }
    ReadTopMotorAndGear(td, md);
    td.Finish();
    if (!(md.top_speed.Value(0.0) > 0))
      throw InputError(td.PathOf("speed_rad_s"), "the run starts in steady drilling: the set-point at t = 0 must be > 0");
    const JsonReader h = r.Object("hoist");
    md.hoist_mass = h.Number("mass_kg", Range::Positive());
    md.hoist_damping = h.Number("damping_Ns_per_m", Range::NonNegative(), 0.0);
    const bool hook_given = h.Has("hook_force_N");
    if (hook_given == h.Has("weight_on_bit_N"))
      throw InputError(h.path(), "expected either weight_on_bit_N (the hook force is set for it) or hook_force_N (a "
                                 "schedule), " + std::string(hook_given ? "not both" : "got neither"));
    if (hook_given) md.hook_force = model::Schedule::FromJson(h.Raw("hook_force_N"), h.PathOf("hook_force_N"));
    else md.weight_on_bit = h.Number("weight_on_bit_N", Range::Positive());
    if (h.Has("rig")) {
      if (hook_given)
        throw InputError(h.PathOf("rig"), "the rig carries the top drive itself: expected weight_on_bit_N (the steady "
                                          "state it keeps) instead of hook_force_N");
      md.rig = ReadHoistRig(h.Object("rig"));
      if (md.hoist_damping > 0)
        throw InputError(h.PathOf("damping_Ns_per_m"), "expected 0 with hoist/rig (the rig's own dampers hold the "
                                                       "block); the dashpot is for the hook-force hoist");
    }
    h.Finish();
    const double g = r.Number("gravity_m_s2", Range::Positive(), 9.81);
    md.axial_coupling = r.Boolean("axial_coupling", true);
    r.Finish();
    if (md.rig && !md.axial_coupling)
      throw InputError(h.PathOf("rig"), "expected no rig with axial_coupling false (no axial dynamics to hang it on)");
    if (!hook_given && !(md.weight_on_bit > md.ContactForce()))
      throw InputError(h.PathOf("weight_on_bit_N"), "expected more than the wear-flat contact force a sigma l = " +
                                                        ReadableNumber(md.ContactForce()) + " N (no cutting otherwise; "
                                                        "a = /model/bit/radius_m, sigma l = /model/rock/sigma_l_N_per_m)");
    if (hook_given && !md.axial_coupling && !md.hook_force.IsConstant())
      throw InputError(h.PathOf("hook_force_N"), "expected a constant with axial_coupling false (no axial dynamics: "
                                                 "the weight on bit stays at H(0)'s steady value)");

    BuildChannels(string, g, md);
    md.axial.load[md.m] += md.bit_mass * g * (1 - string.rho_mud / string.rho);
    const HoistBalance balance = Balance(md, string);
    const double omega0 = md.top_speed.Value(0.0);
    if (!hook_given) {
      md.hook_force = model::Schedule(balance.HookForce(md, omega0, md.weight_on_bit));
    } else {
      md.weight_on_bit = balance.WeightOnBit(md, omega0, md.hook_force.Value(0.0));
      if (!(md.weight_on_bit > md.ContactForce()))
        throw InputError(h.PathOf("hook_force_N"),
                         "the hook force at t = 0, " + ReadableNumber(md.hook_force.Value(0.0)) + " N, leaves " +
                             ReadableNumber(md.weight_on_bit) + " N on the bit in steady drilling (buoyant weight " +
                             ReadableNumber(balance.buoyant_weight) + " N); expected more than the wear-flat contact "
                             "force a sigma l = " + ReadableNumber(md.ContactForce()) + " N");
    }
    if (md.induction_on) {
      try {
        Process steady_start(md);
      } catch (const std::domain_error& e) {
        throw InputError(td.PathOf("induction_motor"), std::string("no steady drilling at the set-point: ") + e.what());
      }
    }
    return std::make_unique<AxialTorsionalModel>(std::move(md));
  }
};

}  // namespace

std::unique_ptr<ModelKind> MakeAxialTorsionalKind() { return std::make_unique<AxialTorsionalKind>(); }

}  // namespace drillwave::cases
