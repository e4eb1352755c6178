// The run of the kind "axial_torsional": the Simulator's process (the two wave chains, the top, the hoist and the bit,
// the regimes and the cut profile) and the sampled trajectory with its statistics.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>

#include "axial_torsional_model.hpp"
#include "drilling_run.hpp"
#include "drillwave/cases/statistics.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/dynamics/top_drive.hpp"
#include "drillwave/integration/hermite_history.hpp"
#include "drillwave/integration/simulator.hpp"

namespace drillwave::cases::axial_torsional {
namespace {

using integration::Side;
using bitrock::Axial;
using bitrock::Turn;
constexpr double kInf = std::numeric_limits<double>::infinity();

// State: 0 bit angle, 1 bit position, 2 top speed, 3 bit speed, 4 hoist speed, 5 bit axial speed, 6 PI integral;
// with a motor 7 its current; with an unbalance 8-11 the BHA's lateral x, y, x', y' (and 7 unused, held at 0); with
// an induction motor or a compliant gear 12-15 the motor's fluxes and 16-17 the motor's speed (referred to the top
// drive) and the gear's twist; with a hoisting rig 18-20 its derrick displacement and speed and the cable's stretch,
// and with its drawworks 21 the drum's speed and 22-25 its motor's fluxes (the unused ones held at 0). With torque
// feedback the top drive's low-passed string torque follows them all.
enum Index {
  kPhi = 0, kU, kWtop, kWbit, kVtop, kVbit, kZ, kDim, kCurrent = kDim, kX, kY, kXd, kYd, kFullDim,
  kFlux = kFullDim, kMotorSpeed = kFlux + 4, kTwist, kTopDim, kRig = kTopDim, kRigDim = kRig + 3,
  kDrum = kRigDim, kDrumFlux, kDrawworksDim = kDrumFlux + 4
};

// The model's top drive: its PI speed loop alone, or commanding the torque of a DC motor (its constant referred to
// the top drive already) or the torque demand of an induction motor.
dynamics::TopDriveParts TopDriveOf(const Model& md) {
  dynamics::TopDriveParts parts;
  parts.drive = md.motor.on       ? model::Drive::kDcMotorSpeed
                : md.induction_on ? model::Drive::kInductionMotorSpeed
                                  : model::Drive::kPiSpeedController;
  parts.setpoint = &md.top_speed;
  parts.pi = &md.pi, parts.law = &md.law;
  parts.dc = {md.motor.k, md.motor.resistance, md.motor.inductance, 0.0};
  parts.dc_torque_command = true;
  parts.induction = &md.induction;
  parts.gear = md.gear;
  parts.inertia = md.TopInertia();
  return parts;
}

class Process {
 public:
  using State = std::vector<double>;
  explicit Process(const Model& md)
      : md_(md), steady_(SteadyDrilling(md, md.top_speed.Value(0.0))),
        cut_(md.blades, steady_.omega, steady_.rop, md.surface_passes, md.bottom_roughness) {
    InitializeWaves();
    const dynamics::TopDriveParts parts = TopDriveOf(md);
    dynamics::TopDrive::Slots slots;
    slots.integral = kZ;
    if (md.motor.on) slots.current = kCurrent;
    if (md.induction_on) slots.flux = kFlux;
    if (md.gear.compliant()) slots.motor_speed = kMotorSpeed;
    if (dynamics::TopDrive::HasFilter(parts)) slots.filter = filter_index_ = LayoutDimension();
    // Throws std::domain_error when the motor cannot carry the steady torque (below its pull-out torque).
    top_drive_.emplace(parts, slots, steady_.omega, top_torque0_);
    // The drawworks' supply that pays out at the steady rate of penetration under the steady hook force.
    if (Drawworks()) drawworks_supply_hz_ = Drawworks()->SteadySupply(steady_.rop, md.hook_force.Value(0.0));
  }
  const model::Drawworks* Drawworks() const { return md_.rig && md_.rig->drawworks ? &*md_.rig->drawworks : nullptr; }
  double DrawworksSupplyHz() const { return drawworks_supply_hz_; }

  // --- Simulator interface --------------------------------------------------------------------------------
  int Dimension() const { return filter_index_ >= 0 ? filter_index_ + 1 : LayoutDimension(); }
  double MaxStep() const {
    return top_drive_->MaxStep(std::min(md_.torsion.ShortestPiece(), md_.axial.ShortestPiece()));
  }
  void BeginStep(double t0) { step_start_ = t0; }

  State InitialState() const {
    State x(Dimension(), 0.0);
    x[kWtop] = steady_.omega;
    x[kWbit] = steady_.omega;
    x[kVtop] = x[kVbit] = steady_.rop;
    top_drive_->SteadyStart(SteadyStringTorque(), x);
    if (const model::Drawworks* d = Drawworks()) {
      x[kDrum] = steady_.rop / d->line_radius;
      const auto psi = d->motor.SteadyFluxes(drawworks_supply_hz_, d->gear_ratio * x[kDrum]);
      std::copy(psi.begin(), psi.end(), x.begin() + kDrumFlux);
    }
    return x;
  }

  void Derivatives(const State& x, State& dx, double t) const {
    const Side side = t <= step_start_ ? Side::kRight : Side::kLeft;
    const Ends ends = StringEnds(x, t, side);
    const BitForces f = Forces(x, t, side, ends);
    dx[kPhi] = rg_.turn == Turn::kStuck ? 0.0 : x[kWbit];
    dx[kU] = rg_.axial == Axial::kHeld && rg_.contact ? 0.0 : x[kVbit];
    // Top drive (with its motor and gear) and hoist. States a component does not use stay at 0.
    if (Dimension() >= kTopDim) std::fill(dx.begin() + kDim, dx.end(), 0.0);
    const Reading in = ReadController(x, t, side);
    top_drive_->Rates(x, x[kWtop], t, side, in, dx);
    const double into_top = top_drive_->TorqueIntoNode(x, x[kWtop], t, side, [&](double) { return in; });
    dx[kWtop] = (ends.top[0] + into_top) / md_.TopInertia();
    if (md_.rig) {  // the top drive hangs from the rig's travelling block
      const model::HoistRig::State rig = RigState(x);
      dx[kVtop] = md_.rig->TopAcceleration(rig, ends.top[1], x[kVtop], steady_.rop, md_.hook_force.Value(0.0),
                                           md_.hoist_mass);
      const model::Drawworks* d = Drawworks();
      const auto rates = md_.rig->Rates(rig, x[kVtop], d ? d->PayOut(x[kDrum]) : steady_.rop, t, t > step_start_);
      std::copy(rates.begin(), rates.end(), dx.begin() + kRig);
      if (d) {
        const auto psi = DrumFluxes(x);
        dx[kDrum] = d->DrumAcceleration(md_.rig->CablePull(rig, x[kVtop], steady_.rop, md_.hook_force.Value(0.0)), psi);
        const double supply = drawworks_supply_hz_ + d->supply_change_hz.Evaluate(t, t > step_start_).first;
        const auto flux_rates = d->motor.FluxRates(psi, supply, d->gear_ratio * x[kDrum]);
        std::copy(flux_rates.begin(), flux_rates.end(), dx.begin() + kDrumFlux);
      }
    } else {
      dx[kVtop] = (ends.top[1] - md_.hook_force.Evaluate(t, t > step_start_).first - HoistDashpot(x)) / md_.hoist_mass;
    }
    // Bit.
    dx[kWbit] = rg_.turn == Turn::kStuck ? 0.0 : (f.drive_torque - f.torque) / md_.EffectiveBitInertia();
    dx[kVbit] = rg_.axial == Axial::kHeld && rg_.contact ? 0.0 : (f.drive_force - f.weight) / md_.bit_mass;
    if (!md_.axial_coupling) {  // no axial dynamics: the bit drills the depth per revolution its held weight cuts
      dx[kU] = f.depth / (2 * kPi) * std::max(BitSpeed(x), 0.0);
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
    // A delayed controller reads the top's arriving wave one delay later still.
    const double read_back = 2 * std::max(md_.torsion.LongestPiece(), md_.axial.LongestPiece()) + top_drive_->delay();
    // The kinks just stored next to the top and the bit reach them one piece later: the steps stop there, as at a
    // breakpoint (the state's own dense output is then smooth within each step, and the end waves too).
    while (!end_kinks_.empty() && end_kinks_.top() < p.t1) end_kinks_.pop();
    arriving_kinks_.clear();
    for (waves::WaveChain& chain : chains_) chain.Commit(p.t0, p.t1, read_back, arriving_kinks_);
    for (double t : arriving_kinks_) end_kinks_.push(t);
    const double keep = 2 * std::max(md_.torsion.travel_time(), md_.axial.travel_time()) + 1.0;
    cut_.Commit(p, kPhi, kU, rg_.contact, rg_.last_contact_change, keep);
    held_phi_ = p.x1[kPhi], held_u_ = p.x1[kU];
    top_drive_->Commit(p, kWtop, read_back);
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
    top_drive_->MarkRestart();
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
    const double rig = md_.rig ? std::min(md_.rig->tension_change.NextKnotAfter(passed_),
                                          Drawworks() ? Drawworks()->supply_change_hz.NextKnotAfter(passed_) : kInf)
                               : kInf;
    const double input = std::min({md_.top_speed.NextKnotAfter(passed_), md_.hook_force.NextKnotAfter(passed_), rig,
                                   top_drive_->NextBreakpoint(passed_)});
    return end_kinks_.empty() ? input : std::min(input, end_kinks_.top());
  }
  void OnBreakpoint(double t, State& x) {
    passed_ = t;
    top_drive_->OnBreakpoint(t, x);
    for (waves::WaveChain& chain : chains_) chain.ForgetStart();  // an input may jump here, or a kink arrive at an end
    while (!end_kinks_.empty() && waves::PassedWith(end_kinks_.top(), t)) end_kinks_.pop();
  }

  // --- Outputs --------------------------------------------------------------------------------------------
  // A sample of the last committed piece, read from its quartic, with the coordinates its regime holds still (a
  // stuck bit's angle, a held bit's position) put back to the exact values the dynamics held them at. The quartic
  // returns a constant only to rounding, and an angle an ulp below the furthest one reached reads as "not cutting":
  // such a sample dropped the cutting force, and a held bit's weight on bit fell to a sigma l (issue 39). The same
  // holds just after a break-away, where the piece starts on the furthest angle: an angle within rounding of it
  // (a few ulps) is put back on it.
  void RestoreHeld(double t, State& x) const {
    if (rg_.turn == Turn::kStuck) x[kPhi] = held_phi_;
    if (rg_.AxiallyHeld()) x[kU] = held_u_;
    const double furthest = cut_.Furthest(t);
    if (rg_.turn == Turn::kForward && x[kPhi] < furthest && furthest - x[kPhi] <= 1e-13 * (1 + std::abs(furthest)))
      x[kPhi] = furthest;
  }
  struct Sample {
    double top_speed, bit_speed, top_torque, bit_torque, wob, hookload, depth, bit_axial_speed, tn, stuck, off_bottom;
    double top_current, lateral_displacement, motor_speed, gear_torque;
  };
  Sample Sampled(double t, const State& x, const State& dx) const {
    const Side side = Side::kLeft;
    const BitForces f = Forces(x, t, side);
    Sample s;
    s.top_speed = x[kWtop];
    s.bit_speed = rg_.turn == Turn::kStuck ? 0.0 : x[kWbit];
    // The controller as the derivatives at the sample read it (the right limits of a step starting there).
    s.top_torque = top_drive_->DriveTorque(x, DriveSpeed(x), t, Side::kRight, ReadController(x, t, Side::kRight));
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
    s.top_current = top_drive_->Current(x);
    s.motor_speed = top_drive_->has_motor_speed() ? top_drive_->MotorShaftSpeed(x) : 0.0;
    s.gear_torque = top_drive_->has_motor_speed() ? top_drive_->GearTorque(x, x[kWtop]) : 0.0;
    s.lateral_displacement = md_.unbalance.has_value() ? std::hypot(x[kX], x[kY]) : 0.0;
    return s;
  }
  const std::vector<StuckInterval>& stuck_intervals() const { return stuck_; }
  const Steady& steady() const { return steady_; }
  double steady_supply_hz() const { return top_drive_->steady_supply_hz(); }

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
    // Without axial dynamics the weight on bit is held at W0 and the depth of cut follows the rock's strength (the
    // steady depth in homogeneous rock): a stronger patch is cut less deep under the same weight, and the cutting
    // torque moves only by the share of W0 the wear flats' contact takes (a constant depth would move it by the whole
    // strength deviation: 2-3 times the first torsional mode's response, dev rec06).
    if (!md_.axial_coupling) f.depth = md_.HeldWeightDepth(md_.weight_on_bit, x[kU]);
    if (!rg_.contact) return f;
    // Cutting only into new rock: not while turning backwards, nor before the bit is back past its furthest angle.
    const bool cutting = rg_.turn != Turn::kBackward && x[kPhi] >= cut_.Furthest(t);
    md_.OnBottom(rg_.turn, rg_.axial, w, cutting, x[kU], f);
    if (!md_.axial_coupling) f.weight = md_.weight_on_bit;
    return f;
  }

  // --- Top drive and BHA components ---------------------------------------------------------------------------
  // The layout's dimension without the torque feedback's filter.
  int LayoutDimension() const {
    if (md_.rig) return Drawworks() ? kDrawworksDim : kRigDim;
    if (md_.induction_on || md_.gear.compliant()) return kTopDim;
    return md_.unbalance.has_value() ? kFullDim : md_.motor.on ? kDim + 1 : kDim;
  }
  // What the top drive's controller reads at t (dynamics::PiTopDrive::Read), and its output.
  using Reading = dynamics::PiTopDrive::Reading;
  Reading ReadController(const State& x, double t, Side side) const {
    return top_drive_->Read(
        x, DriveSpeed(x), t, side, [&](double when, double speed) { return TopStringTorque(x, when, side, speed); },
        [&](double when, double speed) { return TopWave(x, when, side, speed); });
  }
  // The torque the top feeds into the top piece at time t turning at `speed` (what a torque sub there measures): minus
  // the chain's force on the top node without that node's own share of the pipe's damping, as the network's
  // linearization reads it.
  double TopStringTorque(const State& x, double t, Side side, double speed) const {
    waves::ChainEnds v = EndSpeeds(0, x);
    v.top = speed;
    return -(chains_[0].TopForce(t, side, v) + md_.torsion.damping[0] * speed);
  }
  // What the string takes from the top in steady drilling (the top node's share of the pipe's damping aside).
  double SteadyStringTorque() const { return top_torque0_ - md_.torsion.damping[0] * steady_.omega; }
  // What a wave-cancelling top drive reads at time t turning at `speed`: the torque the string and the top node's
  // damping take from it, and the wave arriving there (the reader refuses Kelvin-Voigt dashpots with the law).
  dynamics::PiTopDrive::TopWave TopWave(const State& x, double t, Side side, double speed) const {
    const waves::WaveChain::Wave arriving = chains_[0].TopArrival(t, side);
    return {TopStringTorque(x, t, side, speed) + md_.torsion.damping[0] * speed, arriving.value, arriving.rate};
  }
  // The speed the PI and the motor see (on the top drive's side): the top drive's, or the motor's behind a compliant
  // gear.
  double DriveSpeed(const State& x) const { return top_drive_->DriveSpeed(x, x[kWtop]); }
  double BitSpeed(const State& x) const { return rg_.turn == Turn::kStuck ? 0.0 : x[kWbit]; }
  // The hoist's dashpot force (up) against the block paying out at the steady rate of penetration.
  double HoistDashpot(const State& x) const { return md_.hoist_damping * (x[kVtop] - steady_.rop); }
  static model::HoistRig::State RigState(const State& x) { return {x[kRig], x[kRig + 1], x[kRig + 2]}; }
  static model::InductionMotor::Fluxes DrumFluxes(const State& x) {
    return {x[kDrumFlux], x[kDrumFlux + 1], x[kDrumFlux + 2], x[kDrumFlux + 3]};
  }

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
  std::optional<dynamics::TopDrive> top_drive_;  // built on the steady torque the waves give the top
  int filter_index_ = -1;                        // the drive's filter (TopDrive::HasFilter)
  double top_torque0_ = 0;
  double drawworks_supply_hz_ = 0;  // the drawworks motor's steady supply
  bitrock::RgdRegimes rg_;
  double step_start_ = 0, passed_ = 0;
  double held_phi_ = 0, held_u_ = 0;  // bit angle and position at the end of the last committed piece
  int stick_onsets_ = 0;
  std::vector<StuckInterval> stuck_;
  State state_quarter_;
  // Times at which kinks reach the top or the bit (breakpoints), earliest first.
  std::priority_queue<double, std::vector<double>, std::greater<double>> end_kinks_;
  std::vector<double> arriving_kinks_;  // Commit's scratch
};

// The top drive and the hoist move throughout a run (unlike the bit, which may stick or be held), and the dashpot
// the pipe's damping puts on them, with the wave impedance, decays their speed at the rate (c + Z) / J. The explicit
// Dormand-Prince steps are stable only while h times that rate stays below about 3.3 (its stability interval on the
// negative real axis), so a damping too large for the run's step budget is refused here, naming it and the most it
// may be, rather than integrated in steps of nanoseconds whose histories fill the memory (issue 38: 1e9 N m s/rad per
// m ended in bad_alloc).
void CheckTopDamping(const Model& md, const RunSettings& settings) {
  constexpr double kStableStepTimesRate = 3.3;
  const double steps_allowed = settings.integrator.max_planned_steps;
  if (!std::isfinite(steps_allowed)) return;
  const double fastest = kStableStepTimesRate * steps_allowed / settings.duration_s;  // the largest rate allowed
  struct Top {
    const Channel& channel;
    double inertia;
    const char *field, *unit, *node, *inertia_unit;
  };
  const double hoist_mass = md.hoist_mass + (md.rig ? md.rig->block_mass : 0.0);  // on the rig's rigid hook
  const Top tops[2] = {
      {md.torsion, md.TopInertia(), "torsional_damping_Nms_per_rad_m", "N m s/rad", "top drive", "kg m2"},
      {md.axial, hoist_mass, "axial_damping_Ns_per_m2", "N s/m", "hoist", "kg"}};
  for (int c = 0; c < (md.axial_coupling ? 2 : 1); ++c) {
    const Top& top = tops[c];
    const double dashpot = top.channel.damping[0], impedance = top.channel.z[0];
    // Only where the damping, not the impedance alone, makes the top too fast for the budget.
    if (!(dashpot > 0) || impedance / top.inertia > fastest || (dashpot + impedance) / top.inertia <= fastest) continue;
    const double per_m = md.pipe_damping_per_m[c];
    double most = per_m * (fastest * top.inertia - impedance) / dashpot;  // dashpot is proportional to per_m
    if (most > 0) {  // four digits, rounded down so that the bound shown is allowed
      const double unit = std::pow(10.0, std::floor(std::log10(most)) - 3);
      most = std::floor(most / unit) * unit;
    }
    const double rate = (dashpot + impedance) / top.inertia;
    throw InputError(std::string("/model/string/") + top.field,
                     Significant(per_m, 4) + " " + top.unit + " per m puts " + Significant(dashpot, 4) + " " + top.unit + " on the " +
                         top.node + " (" + Significant(top.inertia, 4) + " " + top.inertia_unit +
                         "), which explicit steps follow only below " + Significant(kStableStepTimesRate / rate, 4) +
                         " s: the " + Significant(settings.duration_s, 4) + " s run needs at least " +
                         Significant(settings.duration_s * rate / kStableStepTimesRate, 4) + " steps, above the limit of " +
                         Significant(steps_allowed, 4) + " (max_samples); expected a number in [0, " + Significant(most, 4) +
                         "] for this run",
                     {"max_samples"});
  }
}

}  // namespace

RunResult Simulate(const Model& md_, const RunSettings& settings) {
  CheckTopDamping(md_, settings);
  Process process(md_);
  std::vector<double> x = process.InitialState();
  DrillingSamples d;
  std::vector<double> hook, current, lateral, motor_rpm, gear_torque, pay_out;
  std::vector<double> dx(x.size()), exact(x.size());
  const double runaway = RunawaySpeed(md_.top_speed);
  auto sample = [&](double t, const std::vector<double>& interpolated) {
    exact = interpolated;
    process.RestoreHeld(t, exact);
    const std::vector<double>& s = exact;
    process.BeginStep(t);  // look-ups at t from the committed history (left limits inside the last piece)
    process.Derivatives(s, dx, t);
    const Process::Sample v = process.Sampled(t, s, dx);
    ThrowIfRunaway(t, v.bit_speed, runaway, s);
    d.time.push_back(t), d.top.push_back(v.top_speed), d.bit.push_back(v.bit_speed);
    d.top_torque.push_back(v.top_torque), d.bit_torque.push_back(v.bit_torque), d.wob.push_back(v.wob);
    hook.push_back(v.hookload), d.depth.push_back(v.depth), d.vbit.push_back(v.bit_axial_speed);
    d.tn.push_back(v.tn), d.stuck.push_back(v.stuck), d.off.push_back(v.off_bottom), d.angle.push_back(s[kPhi]);
    if (md_.motor.on || md_.induction_on) current.push_back(v.top_current);
    if (md_.gear.compliant()) motor_rpm.push_back(v.motor_speed * 30 / kPi), gear_torque.push_back(v.gear_torque);
    if (md_.unbalance.has_value()) lateral.push_back(v.lateral_displacement);
    if (const model::Drawworks* w = process.Drawworks()) pay_out.push_back(3600 * w->PayOut(s[kDrum]));
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
  if (process.Drawworks()) {  // the line paid out, and the drawworks motor's supply of steady drilling
    result.channels.push_back({"pay_out_m_h", std::move(pay_out)});
    result.plot_panels.push_back({"pay_out_m_h"});
    result.summary["drawworks_steady_supply_frequency_Hz"] = process.DrawworksSupplyHz();
  }
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

void CheckSteadyStart(const Model& md) { Process steady_start(md); }

}  // namespace drillwave::cases::axial_torsional
