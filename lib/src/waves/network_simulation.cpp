#include "drillwave/waves/network_simulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <queue>
#include <stdexcept>

#include <boost/math/tools/roots.hpp>

#include "drillwave/core/validity.hpp"
#include "drillwave/dynamics/contact.hpp"
#include "drillwave/dynamics/top_drive.hpp"
#include "drillwave/integration/simulator.hpp"
#include "drillwave/waves/wave_chain.hpp"

namespace drillwave::waves {
namespace {

using bitrock::Turn;
using integration::Side;
using State = std::vector<double>;

constexpr int kNone = -1;
constexpr int kBitAngle = 0;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The chain of the network's sections (WaveChain): the inner nodes' dampers; the ends' own dampers, drives and
// friction stay with the process.
ChainSpec ChainOf(const Network& net) {
  ChainSpec spec;
  for (const Section& s : net.sections) {
    spec.z.push_back(s.impedance), spec.tau.push_back(s.travel_time_s), spec.kv.push_back(s.dashpot);
  }
  if (!net.HasKelvinVoigt()) spec.kv.clear();
  for (std::size_t i = 0; i < net.nodes.size(); ++i) {
    const bool end = i == 0 || i + 1 == net.nodes.size();
    spec.damping.push_back(end ? 0.0 : net.nodes[i].ground_damping);
  }
  spec.load.assign(net.nodes.size(), 0.0), spec.coulomb.assign(net.nodes.size(), 0.0);
  return spec;
}

// The mutable side of a run: the string's waves (a WaveChain: the inner nodes are massless, their waves stored split
// at the kinks and jumps that arrive there), the ends' friction regimes, the breakpoints pending at the ends.
// State layout: the bit angle (for statistics and, later, the cut-depth delay), then the speeds of the ends with
// inertia, then the ends' drives' states (dynamics::TopDrive, which runs them) grouped by kind: PI integrals, a PI
// top's filter (the low-passed string torque or arriving wave), DC motor currents, induction motor fluxes (4 each),
// for an end behind a compliant gear its motor's speed (referred to the node) and the gear's twist; then the bit's
// lateral BHA (x, y, x', y'), and with
// Kelvin-Voigt damping and record_energy the energy the dashpots have dissipated. The top's angle is not integrated:
// nothing reads it.
class NetworkProcess {
 public:
  NetworkProcess(const Network& net, const NetworkRunOptions& options)
      : net_(net),
        options_(options),
        num_nodes_(static_cast<int>(net.nodes.size())),
        bit_(num_nodes_ - 1),
        chain_(ChainOf(net), net.initial.speed_rad_s, net.bit().SteadyLoad(net.initial.speed_rad_s)),
        slopes_(chain_.end_slopes()) {
    int next = 1;  // index 0: bit angle
    speed_index_.assign(num_nodes_, kNone);
    regime_.assign(num_nodes_, Turn::kForward);
    const std::array<int, 2> ends{0, bit_};
    for (int i : ends)
      if (!net.nodes[i].massless()) speed_index_[i] = next++;
    std::array<dynamics::TopDrive::Slots, 2> slots;  // the top's and the bit's drive
    for (int e : {0, 1})
      if (net.nodes[ends[e]].has_speed_integral()) slots[e].integral = next++;
    for (int e : {0, 1})
      if (net.nodes[ends[e]].has_drive_filter()) slots[e].filter = next++;
    for (int e : {0, 1})
      if (net.nodes[ends[e]].has_dc_motor()) slots[e].current = next++;
    for (int e : {0, 1})
      if (net.nodes[ends[e]].has_induction_motor()) slots[e].flux = next, next += 4;
    for (int e : {0, 1})
      if (net.nodes[ends[e]].has_compliant_gear()) slots[e].motor_speed = next, next += 2;  // motor speed, then twist
    if (net.bit().lateral) lateral_index_ = next, next += 4;  // x, y, x', y'
    kelvin_voigt_ = net.HasKelvinVoigt();
    if (kelvin_voigt_ && options.record_energy) dissipated_index_ = next++;
    dimension_ = next;
    for (int i : ends)
      if (net.nodes[i].has_set_valued_friction()) frictional_nodes_.push_back(i);
    steady_torque_ = net_.SteadyTopTorque();
    // Throws std::domain_error where an induction motor cannot carry the steady torque (above its pull-out torque).
    for (int e : {0, 1})
      drives_[e].emplace(DriveParts(net.nodes[ends[e]]), slots[e], net.initial.speed_rad_s, steady_torque_);
    // What the delays can still reach, output look-ups.
    read_back_ = 2.0 * net.LargestTravelTime() + 1.0 + net.top().law.actuator_delay_s;
    if (!kelvin_voigt_) {
      if (!KnownSpeed(0)) top_end_.emplace(*this, 0, -slopes_.top_top);
      if (!KnownSpeed(bit_)) bit_end_.emplace(*this, bit_, -slopes_.bit_bit);
      chain_.CloseEnds(top_end_ ? &*top_end_ : nullptr, bit_end_ ? &*bit_end_ : nullptr);
    }
  }
  NetworkProcess(const NetworkProcess&) = delete;  // the chain keeps pointers to the ends' closures
  NetworkProcess& operator=(const NetworkProcess&) = delete;

  int Dimension() const { return dimension_; }
  double MaxStep() const { return DriveAt(0).MaxStep(net_.SmallestTravelTime()); }
  void BeginStep(double t0) { step_start_ = t0; }

  State InitialState() const {
    State x(dimension_, 0.0);
    for (int i = 0; i < num_nodes_; ++i)
      if (speed_index_[i] != kNone) x[speed_index_[i]] = net_.initial.speed_rad_s;
    // Each drive in steady rotation (dynamics::TopDrive::SteadyStart), the string taking what the node's own dampers
    // and friction leave of the steady torque.
    for (int i : {0, bit_})
      DriveAt(i).SteadyStart(steady_torque_ - net_.nodes[i].SteadyLoad(net_.initial.speed_rad_s), x);
    return x;
  }

  // Decides the initial regimes: a bit at rest is stuck if the driving torque is within its static range.
  void InitializeRegimes(double t0, State& x) {
    step_start_ = t0;
    for (int i : frictional_nodes_) {
      const double v = net_.initial.speed_rad_s;
      if (v > 0) regime_[i] = Turn::kForward;
      else if (v < 0) regime_[i] = Turn::kBackward;
      else {
        regime_[i] = Turn::kStuck;
        regime_[i] = bitrock::TurnAtRest(AtRest(i, t0, x));
        if (regime_[i] == Turn::kStuck) x[speed_index_[i]] = 0;
      }
    }
  }

  void Derivatives(const State& x, State& dxdt, double t) const {
    const Side side = SideAt(t);
    const ChainEnds v = EndSpeeds(x, t, side, dissipated_index_ != kNone ? Massless::kBoth : Massless::kBit);
    // Without dashpots each end's force reads only the wave arriving there; with them one solve gives both.
    const ChainEnds force = kelvin_voigt_ ? chain_.EndForces(t, side, v) : ChainEnds{0.0, 0.0};
    if (dissipated_index_ != kNone) {
      chain_.NodeSpeedsAt(t, side, v, speeds_);
      dxdt[dissipated_index_] = DashpotPower(speeds_);
    }
    dxdt[kBitAngle] = v.bit;
    for (int i : {0, bit_}) {
      const Node& node = net_.nodes[i];
      if (speed_index_[i] == kNone) continue;  // drives, motors and gears sit on ends with inertia (Validate)
      const dynamics::TopDrive& drive = DriveAt(i);
      const double vi = i == 0 ? v.top : v.bit;
      const Reading in = ReadController(i, x, drive.DriveSpeed(x, vi), t, side);
      drive.Rates(x, vi, t, side, in, dxdt);
      double& a = dxdt[speed_index_[i]];
      if (regime_[i] == Turn::kStuck) {
        a = 0;
        continue;
      }
      const double string = kelvin_voigt_ ? (i == 0 ? force.top : force.bit)
                                          : (i == 0 ? chain_.TopForce(t, side, v) : chain_.BitForce(t, side, v));
      double torque =
          string - node.ground_damping * vi + drive.TorqueIntoNode(x, vi, t, side, [&](double) { return in; });
      if (node.lateral) torque += node.lateral->Reaction(x[kBitAngle], vi, Lateral(x));
      if (node.friction) torque -= SlipFriction(i, vi);
      a = torque / node.LumpedInertia();
    }
    if (lateral_index_ != kNone) {  // the bit's lateral BHA, driven by the bit's angular acceleration
      const auto rates = net_.bit().lateral->Rates(x[kBitAngle], v.bit, dxdt[speed_index_[bit_]], Lateral(x));
      std::copy(rates.begin(), rates.end(), dxdt.begin() + lateral_index_);
    }
  }

  // The waves leaving every node over the piece, checked and prepared by the chain (WaveChain::Prepare) from the
  // ends' speeds: a wave buffer is history too, and its interpolation error is invisible to the stepper.
  double PrepareCommit(const integration::Piece& p, double abs_tol, double rel_tol) {
    const double h = p.t1 - p.t0, tq = p.t0 + 0.25 * h, tm = p.t0 + 0.5 * h;
    state_quarter_.resize(p.x0.size());
    integration::InterpolatePiece(p, tq, state_quarter_);
    WaveChain::StepEnds step{};
    step.t0 = p.t0, step.t1 = p.t1;
    const Massless asked = kelvin_voigt_ ? Massless::kBoth : Massless::kNeither;  // else the chain closes them
    if (chain_.ReadsStart(p.t0)) {  // else the chain reuses the last step's end
      step.speed0 = EndSpeeds(p.x0, p.t0, Side::kRight, asked);
      step.rate0 = EndSpeedRates(p.f0, p.t0, Side::kRight, step.speed0);
    }
    step.speed_quarter = EndSpeeds(state_quarter_, tq, Side::kLeft, asked);
    step.speed_mid = EndSpeeds(p.x_mid, tm, Side::kLeft, asked);
    step.speed1 = EndSpeeds(p.x1, p.t1, Side::kLeft, asked);
    step.rate1 = EndSpeedRates(p.f1, p.t1, Side::kLeft, step.speed1);
    return chain_.Prepare(step, abs_tol, rel_tol);
  }

  void Commit(const integration::Piece& p) {
    while (!end_breaks_.empty() && end_breaks_.top() < p.t1) end_breaks_.pop();
    arriving_.clear();
    chain_.Commit(p.t0, p.t1, read_back_, arriving_);
    for (double t : arriving_)
      if (t < t_end_) end_breaks_.push(t);
    drives_[0]->Commit(p, speed_index_[0], read_back_);
    drives_[1]->Commit(p, speed_index_[bit_], read_back_);
  }

  int NumWitnesses() const { return 2 * static_cast<int>(frictional_nodes_.size()); }

  // Two witnesses per frictional node (bitrock/stick_slip.hpp).
  double Witness(int k, double t, const State& x) const {
    const int i = frictional_nodes_[k / 2];
    return bitrock::TurnWitness(regime_[i], k % 2, x[speed_index_[i]], [&] { return AtRest(i, t, x); });
  }

  bool OnEvent(int k, double t, State& x) {
    const int i = frictional_nodes_[k / 2];
    const Turn before = regime_[i];
    const Turn after = bitrock::TurnAfterEvent(before, k % 2, [&] {
      regime_[i] = Turn::kStuck;
      return AtRest(i, t, x);
    });
    regime_[i] = after;
    if (after == Turn::kStuck || before == Turn::kStuck) x[speed_index_[i]] = 0;
    changes_.push_back({t, i, before, after});
    chain_.ForgetStart();  // the end's waves kink here
    for (auto& drive : drives_) drive->MarkRestart();
    return after != before;
  }

  // Breakpoints: the knots of the ends' input schedules (a repeated knot is a jump; behind an actuator delay also one
  // delay later), a controller's handover, and the kinks and jumps that the chain reports on their way to an end. Not
  // the kinks a delayed controller reads one delay after they arrived: the loop smooths them (a slope jump of the
  // torque read is a jump of the top's curvature), which the step control resolves. The start needs none: the chain
  // finds where the first waves leave the steady prehistory (a string at rest under a top speed that starts at 20
  // rad/s).
  double NextBreakpoint() const {
    double next = end_breaks_.empty() ? kInf : end_breaks_.top();
    for (const auto& drive : drives_) next = std::min(next, drive->NextBreakpoint(passed_));
    return next;
  }
  void OnBreakpoint(double t, State& x) {
    passed_ = t;
    for (auto& drive : drives_) drive->OnBreakpoint(t, x);
    chain_.ForgetStart();
    while (!end_breaks_.empty() && PassedWith(end_breaks_.top(), t)) end_breaks_.pop();
  }

  // Outputs at time t for a state x (interpolated by the caller).
  void Sample(double t, const State& x, NetworkTrajectory& out) const {
    const Side side = Side::kLeft;
    const int top = 0;
    const ChainEnds v = EndSpeeds(x, t, side);
    out.time_s.push_back(t);
    out.top_speed_rad_s.push_back(v.top);
    out.bit_speed_rad_s.push_back(v.bit);
    out.top_torque_nm.push_back(-chain_.TopForce(t, side, v));
    out.bit_torque_nm.push_back(BitTorque(x, t, v.bit));
    out.bit_angle_rad.push_back(x[kBitAngle]);
    out.bit_stuck.push_back(regime_[bit_] == Turn::kStuck && net_.bit().has_set_valued_friction() ? 1.0 : 0.0);
    if (DriveAt(top).has_motor_current()) out.top_current_a.push_back(DriveAt(top).Current(x));
    if (DriveAt(top).has_motor_speed()) {
      out.motor_speed_rad_s.push_back(DriveAt(top).MotorShaftSpeed(x));
      out.gear_torque_nm.push_back(DriveAt(top).GearTorque(x, v.top));
    }
    if (options_.record_energy) out.energy_j.push_back(StoredEnergy(t, x, v));
    if (dissipated_index_ != kNone) out.dissipated_j.push_back(x[dissipated_index_]);
    if (lateral_index_ != kNone) out.lateral_displacement_m.push_back(std::hypot(x[lateral_index_], x[lateral_index_ + 1]));
  }

  const std::vector<RegimeChange>& changes() const { return changes_; }
  void set_t_end(double t_end) { t_end_ = t_end; }

 private:
  Side SideAt(double t) const { return t <= step_start_ ? Side::kRight : Side::kLeft; }

  // Kinetic energy of the ends (with their motors, gears and lateral BHA) plus the energy of the waves in flight.
  double StoredEnergy(double t, const State& x, ChainEnds v) const {
    double e = 0;
    for (int i : {0, bit_})
      if (speed_index_[i] != kNone) {
        const double w = i == 0 ? v.top : v.bit;
        e += 0.5 * net_.nodes[i].LumpedInertia() * w * w;
      }
    if (lateral_index_ != kNone) {  // the bit's lateral BHA: the kinetic energy of eqs. 21-23 beyond J_eff w^2 / 2
      const model::JeffcottBha& b = *net_.bit().lateral;
      const auto s = Lateral(x);
      const double w = v.bit, phi = x[kBitAngle];
      const double me_w = b.Moment() * w, along = -s[2] * std::sin(phi) + s[3] * std::cos(phi);
      // 1/2 (M + m) |r' + (m e w / (M + m)) (-sin, cos)|^2 = 1/2 (M + m)|r'|^2 + m e w along + (m e w)^2 / 2 (M + m)
      e += 0.5 * b.TotalMass() * (s[2] * s[2] + s[3] * s[3]) + me_w * along + 0.5 * me_w * me_w / b.TotalMass() +
           0.5 * b.stiffness * (s[0] * s[0] + s[1] * s[1]);
    }
    for (const auto& drive : drives_) e += drive->StoredEnergy(x);
    return e + chain_.WaveEnergy(t);
  }

  // What node i's speed controller reads at time t with the drive turning at vd (dynamics::PiTopDrive::Read): with an
  // actuator delay the top's speed from the controller's history, the string torque from the wave that arrived then.
  using Reading = dynamics::PiTopDrive::Reading;
  Reading ReadController(int i, const State& x, double vd, double t, Side side) const {
    return DriveAt(i).Read(
        x, vd, t, side, [&](double when, double speed) { return TopStringTorque(x, when, side, speed); },
        [&](double when, double speed) { return TopWave(x, when, side, speed); });
  }
  // What a wave-cancelling top reads at time t turning at v: the torque the string and its own dampers take from it,
  // and the wave arriving there (the law refuses Kelvin-Voigt dashpots, whose pull would be part of the string's say).
  dynamics::PiTopDrive::TopWave TopWave(const State& x, double t, Side side, double v) const {
    const WaveChain::Wave arriving = chain_.TopArrival(t, side);
    return {TopStringTorque(x, t, side, v) + net_.top().ground_damping * v, arriving.value, arriving.rate};
  }
  // The torque the top feeds into the string at time t turning at v (what a torque sub there measures): minus the
  // string's force on it. Without dashpots that force reads only the wave arriving at the top; with them both ends'
  // speeds at the state's own time (Network::Validate refuses a delay there).
  double TopStringTorque(const State& x, double t, Side side, double v) const {
    if (!kelvin_voigt_) return -chain_.TopForce(t, side, {v, 0.0});
    return -chain_.EndForces(t, side, EndSpeeds(x, t, side, Massless::kBit)).top;
  }

  const dynamics::TopDrive& DriveAt(int i) const { return *drives_[i == 0 ? 0 : 1]; }

  dynamics::Contact Contact(int i) const { return dynamics::Contact(*net_.nodes[i].friction); }
  double SlipFriction(int i, double v) const { return Contact(i).SlipTorque(regime_[i], v); }

  // Everything but friction acting on end i held at rest: what the friction must balance to keep it stuck.
  // (The callers set the end's regime to stuck first, so that EndSpeeds gives it 0.)
  double DrivingTorqueAtRest(int i, double t, const State& x) const {
    const Side side = SideAt(t);
    const ChainEnds v = EndSpeeds(x, t, side, i == 0 ? Massless::kBoth : Massless::kBit);
    const dynamics::TopDrive& drive = DriveAt(i);
    const double into_node = drive.TorqueIntoNode(
        x, 0.0, t, side, [&](double drive_speed) { return ReadController(i, x, drive_speed, t, side); });
    double torque = (i == 0 ? chain_.TopForce(t, side, v) : chain_.BitForce(t, side, v)) + into_node;
    if (net_.nodes[i].lateral) torque += net_.nodes[i].lateral->Reaction(x[kBitAngle], 0.0, Lateral(x));
    return torque;
  }

  // The driving torque on end i held at rest and the static range of its friction.
  bitrock::AtRest AtRest(int i, double t, const State& x) const {
    return Contact(i).HeldAtRest(DrivingTorqueAtRest(i, t, x));
  }

  // --- The ends' speeds ------------------------------------------------------------------------------------------
  // An end with inertia has its speed in the state (0 while stuck), an imposed speed is its set-point; a massless end
  // balances the string's force on it against its own: a - b v with a drive's a (a dissipative top's beta times its
  // set-point, a torque top's torque) and its dampers' b, and at a massless bit its smooth friction T(v). Without
  // Kelvin-Voigt dashpots each end feels only the wave arriving there (MasslessEnd, which the chain also uses to
  // close its ends); with them the string's force is affine in both end speeds, F = F0 + S v (WaveChain::EndSlopes),
  // and with both ends massless the top's linear balance is folded into the bit's.
  bool KnownSpeed(int i) const {
    return speed_index_[i] != kNone || net_.nodes[i].drive == model::Drive::kPrescribedSpeed;
  }
  double KnownSpeedOf(int i, const State& x, double t, Side side) const {
    if (speed_index_[i] != kNone) return regime_[i] == Turn::kStuck ? 0.0 : x[speed_index_[i]];
    return DriveAt(i).Setpoint(t, side);
  }
  double KnownRateOf(int i, const State& f, double t, Side side) const {
    if (speed_index_[i] != kNone) return regime_[i] == Turn::kStuck ? 0.0 : f[speed_index_[i]];
    return DriveAt(i).SetpointRate(t, side);
  }
  // The constant a of a massless end's own balance a - b v (friction aside), its rate, and b: its drive's and its
  // dampers'.
  double OwnDrive(int i, double t, Side side) const { return DriveAt(i).MasslessTorque(t, side); }
  double OwnDriveRate(int i, double t, Side side) const { return DriveAt(i).MasslessTorqueRate(t, side); }
  double OwnConductance(int i) const { return net_.nodes[i].ground_damping + DriveAt(i).MasslessConductance(); }

  // A massless end without dashpots: F_rest - (Z + c) v + a - b v - T(v) = 0, F_rest = 2 Z w_in.
  class MasslessEnd : public WaveChain::EndClosure {
   public:
    MasslessEnd(const NetworkProcess& p, int i, double string_conductance)
        : p_(p), i_(i), conductance_(p.OwnConductance(i) + string_conductance),
          friction_(i == p.bit_ && p.net_.bit().friction ? &*p.net_.bit().friction : nullptr) {}
    double Speed(double t, Side side, double force_at_rest) const override {
      const double a = force_at_rest + p_.OwnDrive(i_, t, side);
      return friction_ ? SmoothFrictionSpeed(*friction_, a, conductance_) : a / conductance_;
    }
    double Rate(double t, Side side, double speed, double force_rate_at_rest) const override {
      return (force_rate_at_rest + p_.OwnDriveRate(i_, t, side)) /
             (conductance_ + (friction_ ? friction_->SlipTorqueDerivative(speed) : 0.0));
    }

   private:
    const NetworkProcess& p_;
    int i_;
    double conductance_;
    const bitrock::FrictionLaw* friction_;
  };

  // Which massless ends' speeds a caller asks for: without dashpots each costs a look-up, and the chain closes them
  // itself (Prepare), the right-hand side needs a massless top's only for the dashpots' power.
  enum class Massless { kBoth, kBit, kNeither };

  ChainEnds EndSpeeds(const State& x, double t, Side side, Massless asked = Massless::kBoth) const {
    const bool top_known = KnownSpeed(0), bit_known = KnownSpeed(bit_);
    ChainEnds v{top_known ? KnownSpeedOf(0, x, t, side) : 0.0, bit_known ? KnownSpeedOf(bit_, x, t, side) : 0.0};
    if (top_known && bit_known) return v;
    if (!kelvin_voigt_) {
      if (!top_known && asked == Massless::kBoth) v.top = top_end_->Speed(t, side, chain_.TopForce(t, side, {0, 0}));
      if (!bit_known && asked != Massless::kNeither) v.bit = bit_end_->Speed(t, side, chain_.BitForce(t, side, {0, 0}));
      return v;
    }
    const auto& friction = net_.bit().friction;
    return FoldMasslessEnds(v, chain_.EndForces(t, side, v), {OwnDrive(0, t, side), OwnDrive(bit_, t, side)},
                            [&](double a, double b) { return friction ? SmoothFrictionSpeed(*friction, a, b) : a / b; });
  }
  // Their rates, for the chain: the known ones from the state's derivative or the set-point's slope; with dashpots
  // the massless ones from the derivative of their balances (the bit's friction by its slope at its speed); without,
  // the chain's MasslessEnd closes them.
  ChainEnds EndSpeedRates(const State& f, double t, Side side, ChainEnds v) const {
    const bool top_known = KnownSpeed(0), bit_known = KnownSpeed(bit_);
    ChainEnds r{top_known ? KnownRateOf(0, f, t, side) : 0.0, bit_known ? KnownRateOf(bit_, f, t, side) : 0.0};
    if ((top_known && bit_known) || !kelvin_voigt_) return r;
    const auto& friction = net_.bit().friction;
    const double slope = friction ? friction->SlipTorqueDerivative(v.bit) : 0.0;
    return FoldMasslessEnds(r, chain_.EndForceRates(t, side, v, r),
                            {OwnDriveRate(0, t, side), OwnDriveRate(bit_, t, side)},
                            [&](double a, double b) { return a / (b + slope); });
  }
  // With dashpots, the massless ends of `known` (its other entries kept): the string's force f0 + S v (f0 at the
  // unknown ends' 0, S the chain's EndSlopes) against each end's own a - b v, the top's linear balance folded into the
  // bit's, which close_bit(a, b) solves (a - b v - T(v) = 0 for speeds, its derivative for rates).
  template <class CloseBit>
  ChainEnds FoldMasslessEnds(ChainEnds known, ChainEnds f0, ChainEnds own, CloseBit close_bit) const {
    const bool top_known = KnownSpeed(0), bit_known = KnownSpeed(bit_);
    const WaveChain::EndSlopes& s = slopes_;
    // The top: f0.top + s.top_top v_t + s.top_bit v_b + a_t - b_t v_t = 0.
    const double top_a = f0.top + own.top, top_b = OwnConductance(0) - s.top_top;
    if (!bit_known) {  // the bit: f0.bit + s.bit_top v_t + s.bit_bit v_b + a_b - b_b v_b - T(v_b) = 0
      const double a = f0.bit + own.bit + (top_known ? 0.0 : s.bit_top * top_a / top_b);
      const double b = OwnConductance(bit_) - s.bit_bit - (top_known ? 0.0 : s.bit_top * s.top_bit / top_b);
      known.bit = close_bit(a, b);
    }
    if (!top_known) known.top = (top_a + s.top_bit * known.bit) / top_b;
    return known;
  }

  // Smooth friction T at a massless node whose linear balance is a - b v: the root of r(v) = a - b v - T(v). r falls
  // with v wherever b > -T'(v), so from the frictionless speed the root lies on the side r points to: bracket it by
  // doubling steps, then Newton kept inside the bracket (a velocity-weakening law can send plain Newton out of it).
  static double SmoothFrictionSpeed(const bitrock::FrictionLaw& f, double a, double b) {
    auto residual = [&](double v) { return a - b * v - f.SlipTorque(v); };
    const double v0 = a / b, r0 = residual(v0);
    if (r0 == 0) return v0;
    double step = std::abs(r0) / b, v1 = v0 + std::copysign(step, r0);
    for (int k = 0; k < 60 && (residual(v1) > 0) == (r0 > 0); ++k) step *= 2, v1 = v0 + std::copysign(step, r0);
    return boost::math::tools::newton_raphson_iterate(
        [&](double v) { return std::make_pair(residual(v), -b - f.SlipTorqueDerivative(v)); }, v0,
        std::min(v0, v1), std::max(v0, v1), 46);
  }

  double BitTorque(const State& x, double t, double v) const {
    if (!net_.bit().friction) return 0;
    if (regime_[bit_] == Turn::kStuck) return DrivingTorqueAtRest(bit_, t, x);
    return SlipFriction(bit_, v);
  }

  model::JeffcottBha::Lateral Lateral(const State& x) const {
    return {x[lateral_index_], x[lateral_index_ + 1], x[lateral_index_ + 2], x[lateral_index_ + 3]};
  }
  // The power the Kelvin-Voigt dashpots dissipate at node speeds v.
  double DashpotPower(const std::vector<double>& v) const {
    double power = 0;
    for (int k = 0; k + 1 < num_nodes_; ++k) power += net_.sections[k].dashpot * (v[k + 1] - v[k]) * (v[k + 1] - v[k]);
    return power;
  }

  const Network& net_;
  const NetworkRunOptions& options_;
  int num_nodes_, bit_;
  int dimension_ = 0;
  WaveChain chain_;
  WaveChain::EndSlopes slopes_;
  std::vector<int> speed_index_;
  std::vector<int> frictional_nodes_;
  std::vector<Turn> regime_;
  std::vector<RegimeChange> changes_;
  std::priority_queue<double, std::vector<double>, std::greater<double>> end_breaks_;
  std::vector<double> arriving_, state_quarter_;
  double passed_ = -kInf;  // the last breakpoint passed
  double step_start_ = 0;
  double steady_torque_ = 0;
  double read_back_ = 0;
  double t_end_ = kInf;
  std::array<std::optional<dynamics::TopDrive>, 2> drives_;  // the top's and the bit's
  int lateral_index_ = kNone;  // the bit's lateral BHA
  bool kelvin_voigt_ = false;
  int dissipated_index_ = kNone;
  mutable std::vector<double> speeds_;
  std::optional<MasslessEnd> top_end_, bit_end_;  // massless ends without dashpots
};

}  // namespace

dynamics::TopDriveParts DriveParts(const Node& node) {
  dynamics::TopDriveParts parts;
  parts.drive = node.drive;
  parts.setpoint = &node.setpoint;
  parts.dashpot = node.drive_damping;
  parts.pi = &node.pi, parts.law = &node.law;
  parts.dc = node.motor;
  parts.dc.motor_constant = node.motor.motor_constant * node.gear.ratio;
  parts.induction = &node.induction;
  parts.gear = node.gear;
  parts.inertia = node.LumpedInertia();
  return parts;
}

bool NetworkRunOptions::IsValid(std::string* error) const {
  return PositiveField(error, "t_end_s", t_end_s) && NonNegativeField(error, "output_interval_s", output_interval_s) &&
         NestedValid(error, "integrator", integrator.IsValid(error));
}

NetworkRun SimulateNetwork(const Network& network, const NetworkRunOptions& options) {
  ThrowIfInvalid(options);
  network.Validate();
  NetworkProcess process(network, options);
  process.set_t_end(options.t_end_s);
  State x = process.InitialState();
  process.InitializeRegimes(0.0, x);

  NetworkRun run;
  run.t_end_s = options.t_end_s;
  if (options.output_interval_s > 0) {  // one allocation per channel instead of a growing series of them
    const auto samples = static_cast<std::size_t>(options.t_end_s / options.output_interval_s) + 2;
    NetworkTrajectory& tr = run.trajectory;
    for (auto* v : {&tr.time_s, &tr.top_speed_rad_s, &tr.bit_speed_rad_s, &tr.top_torque_nm, &tr.bit_torque_nm,
                    &tr.bit_angle_rad, &tr.bit_stuck})
      v->reserve(samples);
    if (options.record_energy) tr.energy_j.reserve(samples);
  }
  process.Sample(0.0, x, run.trajectory);
  const auto observer = integration::SampleEvery(
      options.output_interval_s, [&](double t, const State& xs) { process.Sample(t, xs, run.trajectory); });
  integration::Simulator<NetworkProcess> simulator(process, options.integrator);
  const State x_end = simulator.Integrate(0.0, x, options.t_end_s, observer);
  run.stats = simulator.stats();
  run.regime_changes = process.changes();
  run.final_bit_angle_rad = x_end[0];
  return run;
}

}  // namespace drillwave::waves
