#include "drillwave/waves/network_simulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include <boost/math/tools/roots.hpp>

#include "drillwave/integration/breakpoints.hpp"
#include "drillwave/integration/hermite_history.hpp"
#include "drillwave/integration/simulator.hpp"

namespace drillwave::waves {
namespace {

using bitrock::Turn;
using integration::Side;
using State = std::vector<double>;

constexpr int kNone = -1;
constexpr int kBitAngle = 0;
// Kelvin-Voigt dashpots pass a discontinuity on to the neighbouring nodes at once up to this order (Echo).
constexpr int kMaxSpreadOrder = 2;

struct Arrivals {
  double above = 0, below = 0;
};
// The slip branch of a set-valued law is continued to the far side of zero by its limit at zero (trial stages can
// overshoot a stop before the event that ends the regime is located).
constexpr double kTinySpeed = 1e-300;

// The mutable side of a run: committed wave buffers, friction regimes, pending breakpoints.
// State layout: the bit angle (for statistics and, later, the cut-depth delay), then the speeds of nodes with
// inertia, then PI integrals, DC motor currents, induction motor fluxes (4 each), for a node behind a compliant
// gear its motor's speed (referred to the node) and the gear's twist, the bit's lateral BHA (x, y, x', y'), and with
// Kelvin-Voigt damping and record_energy the energy the dashpots have dissipated. Other angles are not integrated:
// nothing reads them and they would only add work.
class NetworkProcess {
 public:
  NetworkProcess(const Network& net, const NetworkRunOptions& options)
      : net_(net),
        options_(options),
        kink_threshold_(options.echo_weight_threshold > 0 ? options.echo_weight_threshold
                                                          : AutomaticKinkThreshold(options.integrator)),
        jump_threshold_(AutomaticJumpThreshold(options.integrator)),
        num_nodes_(static_cast<int>(net.nodes.size())),
        waves_(2 * static_cast<int>(net.sections.size())) {
    int next = 1;  // index 0: bit angle
    speed_index_.assign(num_nodes_, kNone);
    integral_index_.assign(num_nodes_, kNone);
    current_index_.assign(num_nodes_, kNone);
    flux_index_.assign(num_nodes_, kNone);
    motor_speed_index_.assign(num_nodes_, kNone);
    regime_.assign(num_nodes_, Turn::kForward);
    for (int i = 0; i < num_nodes_; ++i)
      if (!net.nodes[i].massless()) speed_index_[i] = next++;
    for (int i = 0; i < num_nodes_; ++i)
      if (net.nodes[i].has_speed_integral()) integral_index_[i] = next++;
    for (int i = 0; i < num_nodes_; ++i)
      if (net.nodes[i].has_dc_motor()) current_index_[i] = next++;
    for (int i = 0; i < num_nodes_; ++i)
      if (net.nodes[i].has_induction_motor()) flux_index_[i] = next, next += 4;
    for (int i = 0; i < num_nodes_; ++i)
      if (net.nodes[i].has_compliant_gear()) motor_speed_index_[i] = next, next += 2;  // motor speed, then twist
    if (net.bit().lateral) lateral_index_ = next, next += 4;  // x, y, x', y'
    kelvin_voigt_ = net.HasKelvinVoigt();
    massless_bit_friction_ = kelvin_voigt_ && net.bit().massless() && net.bit().friction;
    if (kelvin_voigt_ && options.record_energy) dissipated_index_ = next++;
    dimension_ = next;
    for (int i = 0; i < num_nodes_; ++i)
      if (net.nodes[i].has_set_valued_friction()) frictional_nodes_.push_back(i);
    max_travel_time_ = net.LargestTravelTime();
    if (kelvin_voigt_) FactorNodeSystem();
    InitializeWaves();
  }

  int Dimension() const { return dimension_; }
  double MaxStep() const { return net_.SmallestTravelTime(); }
  void BeginStep(double t0) { step_start_ = t0; }

  State InitialState() const {
    State x(dimension_, 0.0);
    for (int i = 0; i < num_nodes_; ++i)
      if (speed_index_[i] != kNone) x[speed_index_[i]] = net_.initial.speed_rad_s;
    // In steady state a PI controller holds the steady torque (a DC motor: the steady voltage) with its integral part,
    // a DC motor carries the current of the steady torque and a compliant gear the twist of it. An induction motor
    // starts with the fluxes that are steady at its initial speed and supply: under the speed controller the supply
    // that gives the steady torque; in open loop the scheduled one, whatever torque that gives.
    const double v0 = net_.initial.speed_rad_s;
    for (int i = 0; i < num_nodes_; ++i) {
      const Node& node = net_.nodes[i];
      double held = steady_torque_;
      if (current_index_[i] != kNone) {
        const double k = node.motor.motor_constant * node.gear.ratio;  // referred to the node's side
        x[current_index_[i]] = steady_torque_ / k;
        held = node.motor.armature_resistance * x[current_index_[i]] + k * v0;
      }
      if (flux_index_[i] != kNone) {
        const double n = node.gear.ratio;
        const double supply = node.drive == Drive::kInductionMotor
                                  ? node.setpoint.Value(0.0)
                                  : node.induction.SteadySupplyFrequency(steady_torque_ / n, n * v0);
        const auto psi = node.induction.SteadyFluxes(supply, n * v0);
        std::copy(psi.begin(), psi.end(), x.begin() + flux_index_[i]);
        if (node.drive == Drive::kInductionMotorSpeed)  // the demand that asks for this supply
          held = n * node.induction.TorqueDemandFor(supply, n * v0);
      }
      if (integral_index_[i] != kNone) x[integral_index_[i]] = node.pi.IntegralHolding(held);
      if (motor_speed_index_[i] != kNone) {
        x[motor_speed_index_[i]] = v0;
        x[motor_speed_index_[i] + 1] = steady_torque_ / node.gear.stiffness;
      }
    }
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
    if (kelvin_voigt_) {  // every node's speed at once: the dashpots couple them
      SolveNodeSpeeds(x, t, side, speeds_);
      if (dissipated_index_ != kNone) dxdt[dissipated_index_] = DashpotPower(speeds_);
    }
    dxdt[kBitAngle] = Speed(num_nodes_ - 1, x, t, side);
    for (int i = 0; i < num_nodes_; ++i) {
      const Node& node = net_.nodes[i];
      if (speed_index_[i] == kNone) continue;  // drives, motors and gears sit on nodes with inertia (Validate)
      const double v = Speed(i, x, t, side), vd = DriveSpeed(i, x, v);
      if (integral_index_[i] != kNone) dxdt[integral_index_[i]] = Setpoint(node, t, side) - vd;
      if (current_index_[i] != kNone) {
        const DcMotor& m = node.motor;
        const double current = x[current_index_[i]];
        dxdt[current_index_[i]] = (MotorVoltage(i, x, vd, t, side) - m.armature_resistance * current -
                                   m.motor_constant * node.gear.ratio * vd) / m.armature_inductance;
      }
      if (flux_index_[i] != kNone) {
        const auto rates = node.induction.FluxRates(Fluxes(i, x), SupplyFrequency(i, x, vd, t, side), node.gear.ratio * vd);
        std::copy(rates.begin(), rates.end(), dxdt.begin() + flux_index_[i]);
      }
      if (motor_speed_index_[i] != kNone) {
        dxdt[motor_speed_index_[i]] =
            (DriveTorque(i, x, vd, t, side) - GearTorque(i, x, v)) / node.gear.ReferredMotorInertia();
        dxdt[motor_speed_index_[i] + 1] = vd - v;
      }
      double& a = dxdt[speed_index_[i]];
      if (regime_[i] == Turn::kStuck) {
        a = 0;
        continue;
      }
      double torque = StringTorqueOnNode(i, v, t, side) - node.ground_damping * v + TorqueIntoNode(i, x, v, t, side);
      if (kelvin_voigt_) torque += DashpotTorque(i, speeds_);
      if (node.lateral) torque += node.lateral->Reaction(x[kBitAngle], v, Lateral(x));
      if (node.friction) torque -= SlipFriction(i, v);
      a = torque / node.LumpedInertia();
    }
    if (lateral_index_ != kNone) {  // the bit's lateral BHA, driven by the bit's angular acceleration
      const int bit = num_nodes_ - 1;
      const auto rates = net_.bit().lateral->Rates(x[kBitAngle], Speed(bit, x, t, side), dxdt[speed_index_[bit]], Lateral(x));
      std::copy(rates.begin(), rates.end(), dxdt.begin() + lateral_index_);
    }
  }

  // The waves leaving every node over the piece, and how well their cubic Hermite interpolant matches the exact
  // midpoint value: a wave buffer is history too, and its interpolation error is invisible to the stepper.
  double PrepareCommit(const integration::Piece& p, double abs_tol, double rel_tol) {
    const int m = waves_.dimension();
    out0_.resize(m), out1_.resize(m), outm_.resize(m), d0_.resize(m), d1_.resize(m);
    // Without a breakpoint or event in between, the start of this piece is the end of the last one.
    if (!(start_is_last_end_ && p.t0 == last_end_time_)) OutgoingWaves(p.t0, p.x0, p.f0, Side::kRight, out0_.data(), d0_.data());
    OutgoingWaves(p.t1, p.x1, p.f1, Side::kLeft, out1_.data(), d1_.data());
    OutgoingWaves(0.5 * (p.t0 + p.t1), p.x_mid, p.f1, Side::kLeft, outm_.data(), nullptr);
    // The stored quartic against the exact outgoing waves at a quarter of the piece (state from the piece's own
    // interpolant): the error of what later look-ups will read.
    const double h = p.t1 - p.t0, tq = p.t0 + 0.25 * h;
    state_quarter_.resize(p.x0.size());
    outq_.resize(m);
    integration::InterpolatePiece(p, tq, state_quarter_);
    OutgoingWaves(tq, state_quarter_, p.f1, Side::kLeft, outq_.data(), nullptr);
    return integration::QuarterPointError(m, h, out0_.data(), out1_.data(), d0_.data(), d1_.data(), outm_.data(),
                                          outq_.data(), abs_tol, rel_tol);
  }

  void Commit(const integration::Piece& p) {
    waves_.Append(p.t0, out0_.data(), d0_.data(), p.t1, out1_.data(), d1_.data(), outm_.data());
    out0_.swap(out1_);
    d0_.swap(d1_);
    last_end_time_ = p.t1;
    start_is_last_end_ = true;
    // Keep what the delays can still reach, plus a margin for output look-ups.
    waves_.DiscardBefore(p.t1 - 2.0 * max_travel_time_ - 1.0);
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
    start_is_last_end_ = false;
    Source(i, t, 1);
    return after != before;
  }

  double NextBreakpoint() const { return breakpoints_.NextTime(); }
  void OnBreakpoint(double t) {
    start_is_last_end_ = false;
    std::vector<integration::Breakpoint> due = breakpoints_.PopAt(t, 1e-12 * std::max(1.0, std::abs(t)));
    if (kelvin_voigt_) EchoArrivalsThroughDashpots(t, due);  // takes the arrivals at massless nodes out of `due`
    for (const auto& b : due) Echo(b);
  }

  // Sources of breakpoints: every knot of every input schedule (a repeated knot time is a jump) and the start,
  // which is followed as a jump: the initial waves need not match the inputs at t0 (a string at rest under a
  // top speed that starts at 20 rad/s).
  void SeedBreakpoints(double t0, double t_end) {
    for (int i = 0; i < num_nodes_; ++i) {
      const auto& knots = net_.nodes[i].setpoint.knots();
      for (std::size_t k = 0; k < knots.size(); ++k) {
        const double tk = knots[k].first;
        const bool repeated = k > 0 && knots[k - 1].first == tk;
        const bool jump = repeated || (k + 1 < knots.size() && knots[k + 1].first == tk);
        if (tk > t0 && tk < t_end && !repeated) breakpoints_.Push({tk, i, 1.0, jump ? 0 : 1, kNone, 0});
      }
      const Node& node = net_.nodes[i];
      if (!node.massless()) Source(i, t0, 1);
      else if (node.drive != Drive::kNone) Source(i, t0, 0);  // a driven massless end can jump at t0
    }
  }

  // Outputs at time t for a state x (interpolated by the caller).
  void Sample(double t, const State& x, NetworkTrajectory& out) const {
    const Side side = Side::kLeft;
    const int top = 0, bit = num_nodes_ - 1;
    const double v_top = Speed(top, x, t, side), v_bit = Speed(bit, x, t, side);
    out.time_s.push_back(t);
    out.top_speed_rad_s.push_back(v_top);
    out.bit_speed_rad_s.push_back(v_bit);
    double top_torque = -StringTorqueOnNode(top, v_top, t, side);
    if (kelvin_voigt_) {
      SolveNodeSpeeds(x, t, side, speeds_);
      top_torque -= DashpotTorque(top, speeds_);
    }
    out.top_torque_nm.push_back(top_torque);
    out.bit_torque_nm.push_back(BitTorque(bit, x, t, side));
    out.bit_angle_rad.push_back(x[kBitAngle]);
    out.bit_stuck.push_back(regime_[bit] == Turn::kStuck && net_.nodes[bit].has_set_valued_friction() ? 1.0 : 0.0);
    if (current_index_[top] != kNone) out.top_current_a.push_back(x[current_index_[top]]);
    if (flux_index_[top] != kNone)
      out.top_current_a.push_back(net_.nodes[top].induction.StatorCurrentRms(Fluxes(top, x)));
    if (motor_speed_index_[top] != kNone) {
      out.motor_speed_rad_s.push_back(net_.nodes[top].gear.ratio * x[motor_speed_index_[top]]);
      out.gear_torque_nm.push_back(GearTorque(top, x, v_top));
    }
    if (options_.record_energy) out.energy_j.push_back(StoredEnergy(t, x));
    if (dissipated_index_ != kNone) out.dissipated_j.push_back(x[dissipated_index_]);
    if (lateral_index_ != kNone) out.lateral_displacement_m.push_back(std::hypot(x[lateral_index_], x[lateral_index_ + 1]));
  }

  const std::vector<RegimeChange>& changes() const { return changes_; }

  // Kinetic energy of the nodes plus the energy in flight in every section: the energy density of a section is
  // rho J (D^2 + U^2), so a section holds Z times the integral of D^2 + U^2 over the last travel time.
  double StoredEnergy(double t, const State& x) const {
    double e = 0;
    for (int i = 0; i < num_nodes_; ++i)
      if (speed_index_[i] != kNone) {
        const double v = Speed(i, x, t, Side::kLeft);
        e += 0.5 * net_.nodes[i].LumpedInertia() * v * v;
      }
    if (lateral_index_ != kNone) {  // the bit's lateral BHA: the kinetic energy of eqs. 21-23 beyond J_eff w^2 / 2
      const model::JeffcottBha& b = *net_.bit().lateral;
      const auto s = Lateral(x);
      const double w = Speed(num_nodes_ - 1, x, t, Side::kLeft), phi = x[kBitAngle];
      const double me_w = b.Moment() * w, along = -s[2] * std::sin(phi) + s[3] * std::cos(phi);
      // 1/2 (M + m) |r' + (m e w / (M + m)) (-sin, cos)|^2 = 1/2 (M + m)|r'|^2 + m e w along + (m e w)^2 / 2 (M + m)
      e += 0.5 * b.TotalMass() * (s[2] * s[2] + s[3] * s[3]) + me_w * along + 0.5 * me_w * me_w / b.TotalMass() +
           0.5 * b.stiffness * (s[0] * s[0] + s[1] * s[1]);
    }
    for (int i = 0; i < num_nodes_; ++i)
      if (motor_speed_index_[i] != kNone) {
        const model::Gear& g = net_.nodes[i].gear;
        const double vm = x[motor_speed_index_[i]], twist = x[motor_speed_index_[i] + 1];
        e += 0.5 * g.ReferredMotorInertia() * vm * vm + 0.5 * g.stiffness * twist * twist;
      }
    for (std::size_t k = 0; k < net_.sections.size(); ++k) {
      const double tau = net_.sections[k].travel_time_s;
      e += net_.sections[k].impedance * (waves_.IntegrateSquare(2 * static_cast<int>(k), t - tau, t) +
                                         waves_.IntegrateSquare(2 * static_cast<int>(k) + 1, t - tau, t));
    }
    return e;
  }

 private:
  Side SideAt(double t) const { return t <= step_start_ ? Side::kRight : Side::kLeft; }

  // Components of the wave history: 2k is the wave leaving the top of section k (going down), 2k+1 the wave
  // leaving its bottom (going up). A wave arrives at the far end one travel time later.
  // Waves arriving at node i at time t from the section above and the section below (0 where there is none).
  Arrivals Arriving(int i, double t, Side side) const {
    Arrivals in;
    if (HasAbove(i)) in.above = waves_.Value(t - net_.sections[i - 1].travel_time_s, 2 * (i - 1), side);
    if (HasBelow(i)) in.below = waves_.Value(t - net_.sections[i].travel_time_s, 2 * i + 1, side);
    return in;
  }
  Arrivals ArrivingRate(int i, double t, Side side) const {
    Arrivals in;
    if (HasAbove(i)) in.above = waves_.Derivative(t - net_.sections[i - 1].travel_time_s, 2 * (i - 1), side);
    if (HasBelow(i)) in.below = waves_.Derivative(t - net_.sections[i].travel_time_s, 2 * i + 1, side);
    return in;
  }
  bool HasAbove(int i) const { return i > 0; }
  bool HasBelow(int i) const { return i < num_nodes_ - 1; }

  double ImpedanceSum(int i) const {
    return (HasAbove(i) ? net_.sections[i - 1].impedance : 0.0) + (HasBelow(i) ? net_.sections[i].impedance : 0.0);
  }
  // Sum of Z_k * 2 w_in,k over the sections at node i (torque the string would exert on the node held at rest).
  double TwiceIncoming(int i, const Arrivals& in) const {
    return (HasAbove(i) ? 2 * net_.sections[i - 1].impedance * in.above : 0.0) +
           (HasBelow(i) ? 2 * net_.sections[i].impedance * in.below : 0.0);
  }
  double TwiceIncoming(int i, double t, Side side) const { return TwiceIncoming(i, Arriving(i, t, side)); }
  // Torque of the string on node i turning at v: sum of Z_k (2 w_in,k - v).
  double StringTorqueOnNode(int i, double v, double t, Side side) const {
    return TwiceIncoming(i, t, side) - ImpedanceSum(i) * v;
  }

  static double Setpoint(const Node& node, double t, Side side) {
    return side == Side::kLeft ? node.setpoint.ValueBefore(t) : node.setpoint.Value(t);
  }
  static double SetpointRate(const Node& node, double t, Side side) {
    return side == Side::kLeft ? node.setpoint.SlopeBefore(t) : node.setpoint.Slope(t);
  }

  double DriveTorque(int i, const State& x, double v, double t, Side side) const {
    const Node& node = net_.nodes[i];
    switch (node.drive) {
      case Drive::kNone:
      case Drive::kPrescribedSpeed: return 0;
      case Drive::kSpeedDashpot: return node.drive_damping * (Setpoint(node, t, side) - v);
      case Drive::kTorque: return Setpoint(node, t, side);
      case Drive::kPiSpeedController: {
        const double u = SpeedControllerOutput(i, x, v, t, side);
        return node.torque_limit > 0 ? std::clamp(u, -node.torque_limit, node.torque_limit) : u;
      }
      case Drive::kDcMotorVoltage:
      case Drive::kDcMotorSpeed: return node.gear.ratio * node.motor.motor_constant * x[current_index_[i]];
      case Drive::kInductionMotor:
      case Drive::kInductionMotorSpeed: return node.gear.ratio * node.induction.Torque(Fluxes(i, x));
    }
    return 0;
  }

  // The PI speed controller of node i at drive speed v: kp (setpoint - v) + ki * integral. A torque for the PI top
  // drive and the induction motor's demand, a voltage for the DC motor's speed loop.
  double SpeedControllerOutput(int i, const State& x, double v, double t, Side side) const {
    const Node& node = net_.nodes[i];
    return node.pi.Output(Setpoint(node, t, side), v, x[integral_index_[i]]);
  }

  // An induction motor's supply: the setpoint (open loop), or the supply for the PI's torque demand at the drive's
  // speed (slip-frequency control).
  double SupplyFrequency(int i, const State& x, double vd, double t, Side side) const {
    const Node& node = net_.nodes[i];
    if (node.drive == Drive::kInductionMotor) return Setpoint(node, t, side);
    const double n = node.gear.ratio;
    const double demand = SpeedControllerOutput(i, x, vd, t, side);
    return node.induction.SupplyForTorque(demand / n, n * vd);
  }

  // The drive acts on the node itself, or on the motor behind a compliant gear, which passes on the gear torque.
  double TorqueIntoNode(int i, const State& x, double v, double t, Side side) const {
    return motor_speed_index_[i] != kNone ? GearTorque(i, x, v) : DriveTorque(i, x, v, t, side);
  }
  double GearTorque(int i, const State& x, double v) const {
    return net_.nodes[i].gear.Torque(x[motor_speed_index_[i] + 1], x[motor_speed_index_[i]], v);
  }
  // The speed the drive sees, referred to the node's side: the node's, or its motor's behind a compliant gear.
  double DriveSpeed(int i, const State& x, double v) const {
    return motor_speed_index_[i] != kNone ? x[motor_speed_index_[i]] : v;
  }
  model::InductionMotor::Fluxes Fluxes(int i, const State& x) const {
    model::InductionMotor::Fluxes psi;
    std::copy(x.begin() + flux_index_[i], x.begin() + flux_index_[i] + 4, psi.begin());
    return psi;
  }

  // The armature voltage of a DC motor: the setpoint (open loop) or the speed controller's output, clamped.
  double MotorVoltage(int i, const State& x, double v, double t, Side side) const {
    const Node& node = net_.nodes[i];
    const double u = node.drive == Drive::kDcMotorVoltage
                         ? Setpoint(node, t, side)
                         : SpeedControllerOutput(i, x, v, t, side);
    const double limit = node.motor.voltage_limit;
    return limit > 0 ? std::clamp(u, -limit, limit) : u;
  }

  double SlipFriction(int i, double v) const {
    const auto& f = *net_.nodes[i].friction;
    if (!f.IsSetValued()) return f.SlipTorque(v);
    return regime_[i] == Turn::kForward ? f.SlipTorque(std::max(v, kTinySpeed))
                                               : f.SlipTorque(std::min(v, -kTinySpeed));
  }

  // Everything but friction acting on node i held at rest: what the friction must balance to keep it stuck.
  // (The callers set the node's regime to stuck first, so that its neighbours' speeds are solved with it at rest.)
  double DrivingTorqueAtRest(int i, double t, const State& x) const {
    const Side side = SideAt(t);
    double torque = TwiceIncoming(i, t, side) + TorqueIntoNode(i, x, 0.0, t, side);
    if (net_.nodes[i].lateral) torque += net_.nodes[i].lateral->Reaction(x[kBitAngle], 0.0, Lateral(x));
    if (kelvin_voigt_) {
      SolveNodeSpeeds(x, t, side, speeds_);
      torque += DashpotTorque(i, speeds_);
    }
    return torque;
  }

  // The driving torque on node i held at rest and the static range of its friction.
  bitrock::AtRest AtRest(int i, double t, const State& x) const {
    const auto& f = *net_.nodes[i].friction;
    return {DrivingTorqueAtRest(i, t, x), {f.StaticPositive(), f.StaticNegative()}};
  }

  // Speed of node i: a state for nodes with inertia, algebraic for massless ones (the balance of the incoming
  // waves and the external torques, DESIGN.md §1).
  double Speed(int i, const State& x, double t, Side side) const {
    if (speed_index_[i] != kNone) return regime_[i] == Turn::kStuck ? 0.0 : x[speed_index_[i]];
    if (kelvin_voigt_) {
      SolveNodeSpeeds(x, t, side, speeds_);
      return speeds_[i];
    }
    return MasslessSpeed(i, Arriving(i, t, side), t, side);
  }

  double MasslessSpeed(int i, const Arrivals& in, double t, Side side) const {
    const Node& node = net_.nodes[i];
    if (node.drive == Drive::kPrescribedSpeed) return Setpoint(node, t, side);
    // Named variables, not a structured binding: C++17 lets no lambda capture one (GCC allows it, clang refuses).
    const std::pair<double, double> balance = MasslessBalance(i, TwiceIncoming(i, in), t, side);
    const double a = balance.first, b = balance.second;
    if (!node.friction) return a / b;
    return SmoothFrictionSpeed(*node.friction, a, b);
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

  // Linear part of a massless node's balance: a - b v = sum Z(2 w_in - v) - c v + drive torque.
  std::pair<double, double> MasslessBalance(int i, double twice_incoming, double t, Side side) const {
    const Node& node = net_.nodes[i];
    double a = twice_incoming;
    if (node.drive == Drive::kSpeedDashpot) a += node.drive_damping * Setpoint(node, t, side);
    else if (node.drive == Drive::kTorque) a += Setpoint(node, t, side);
    return {a, MasslessConductance(i)};
  }
  // b of that balance: the sections' impedances, the node's damper and a dissipative top's beta.
  double MasslessConductance(int i) const {
    const Node& node = net_.nodes[i];
    return ImpedanceSum(i) + node.ground_damping + (node.drive == Drive::kSpeedDashpot ? node.drive_damping : 0.0);
  }

  // Rate of change of a massless node's speed (implicit derivative of its balance), for the wave buffers.
  double MasslessSpeedRate(int i, double v, const Arrivals& rate, double t, Side side) const {
    const Node& node = net_.nodes[i];
    if (node.drive == Drive::kPrescribedSpeed) return SetpointRate(node, t, side);
    double b = MasslessConductance(i);
    if (node.friction) b += node.friction->SlipTorqueDerivative(v);
    return MasslessBalanceRate(i, rate, t, side) / b;
  }
  // Rate of the constant part a of a massless node's balance a - b v.
  double MasslessBalanceRate(int i, const Arrivals& rate, double t, Side side) const {
    const Node& node = net_.nodes[i];
    double da = TwiceIncoming(i, rate);
    if (node.drive == Drive::kSpeedDashpot) da += node.drive_damping * SetpointRate(node, t, side);
    else if (node.drive == Drive::kTorque) da += SetpointRate(node, t, side);
    return da;
  }

  double BitTorque(int i, const State& x, double t, Side side) const {
    const Node& node = net_.nodes[i];
    const double v = Speed(i, x, t, side);
    if (!node.friction) return 0;
    if (regime_[i] == Turn::kStuck) return DrivingTorqueAtRest(i, t, x);
    return SlipFriction(i, v);
  }

  // --- Kelvin-Voigt: the node system ---------------------------------------------------------------------------
  // With dashpots kv_k across the sections, a massless node i balances
  //   (sum Z + c + beta + kv_{i-1} + kv_i) v_i - kv_{i-1} v_{i-1} - kv_i v_{i+1} = sum 2 Z w_in + drive terms,
  // and a node of known speed (inertial, or imposed) holds it: one tridiagonal system over the chain, whose matrix
  // does not change during a run (a stuck node is a known speed of 0). Factored once (Thomas algorithm; diagonally
  // dominant, so stable without pivoting); the speeds' rates solve the same matrix with the rates on the right.
  model::JeffcottBha::Lateral Lateral(const State& x) const {
    return {x[lateral_index_], x[lateral_index_ + 1], x[lateral_index_ + 2], x[lateral_index_ + 3]};
  }

  bool KnownSpeed(int i) const { return speed_index_[i] != kNone || net_.nodes[i].drive == Drive::kPrescribedSpeed; }
  double DashpotAbove(int i) const { return HasAbove(i) ? net_.sections[i - 1].dashpot : 0.0; }
  double DashpotBelow(int i) const { return HasBelow(i) ? net_.sections[i].dashpot : 0.0; }

  void FactorNodeSystem() {
    lower_.assign(num_nodes_, 0.0), ratio_.assign(num_nodes_, 0.0), inv_pivot_.assign(num_nodes_, 0.0);
    for (int i = 0; i < num_nodes_; ++i) {
      double diagonal = 1, upper = 0;
      if (!KnownSpeed(i)) {
        diagonal = MasslessConductance(i) + DashpotAbove(i) + DashpotBelow(i);
        lower_[i] = -DashpotAbove(i), upper = -DashpotBelow(i);
      }
      inv_pivot_[i] = 1 / (diagonal - (i > 0 ? lower_[i] * ratio_[i - 1] : 0.0));
      ratio_[i] = upper * inv_pivot_[i];
    }
  }
  // Solves the node system in place: v holds the right-hand side on entry, the speeds on return. A massless bit
  // with (smooth) friction is the sweep's last node: there the forward sweep leaves the scalar balance a - b v - T(v)
  // with a its reduced right-hand side and b its pivot (the dashpot chain above folded in), solved as a lone massless
  // node's; with solve_bit_friction false the bit's balance is linear with T'(v) = bit_friction_slope instead (the
  // rates' implicit derivative; 0 for the echoes' linear response).
  void SolveNodeSystem(double* v, bool solve_bit_friction = false, double bit_friction_slope = 0) const {
    const int bit = num_nodes_ - 1, linear_rows = massless_bit_friction_ ? bit : num_nodes_;
    for (int i = 0; i < linear_rows; ++i) v[i] = (v[i] - (i > 0 ? lower_[i] * v[i - 1] : 0.0)) * inv_pivot_[i];
    if (massless_bit_friction_) {
      const double reduced = v[bit] - lower_[bit] * v[bit - 1];
      v[bit] = solve_bit_friction ? SmoothFrictionSpeed(*net_.bit().friction, reduced, 1 / inv_pivot_[bit])
                                  : reduced / (1 / inv_pivot_[bit] + bit_friction_slope);
    }
    for (int i = num_nodes_ - 2; i >= 0; --i) v[i] -= ratio_[i] * v[i + 1];
  }
  void SolveNodeSpeeds(const State& x, double t, Side side, std::vector<double>& v) const {
    v.resize(num_nodes_);
    for (int i = 0; i < num_nodes_; ++i) {
      const Node& node = net_.nodes[i];
      if (speed_index_[i] != kNone) v[i] = regime_[i] == Turn::kStuck ? 0.0 : x[speed_index_[i]];
      else if (node.drive == Drive::kPrescribedSpeed) v[i] = Setpoint(node, t, side);
      else v[i] = MasslessBalance(i, TwiceIncoming(i, t, side), t, side).first;
    }
    SolveNodeSystem(v.data(), true);
  }
  void SolveNodeSpeedRates(const State& f, double t, Side side, std::vector<double>& dv) const {
    dv.resize(num_nodes_);
    for (int i = 0; i < num_nodes_; ++i) {
      const Node& node = net_.nodes[i];
      if (speed_index_[i] != kNone) dv[i] = regime_[i] == Turn::kStuck ? 0.0 : f[speed_index_[i]];
      else if (node.drive == Drive::kPrescribedSpeed) dv[i] = SetpointRate(node, t, side);
      else dv[i] = MasslessBalanceRate(i, ArrivingRate(i, t, side), t, side);
    }
    // Called after SolveNodeSpeeds at the same state: speeds_ holds the bit's speed for its friction slope.
    SolveNodeSystem(dv.data(), false,
                    massless_bit_friction_ ? net_.bit().friction->SlipTorqueDerivative(speeds_[num_nodes_ - 1]) : 0.0);
  }
  // Torque of the dashpots of node i's sections on it, and the power all of them dissipate, at node speeds v.
  double DashpotTorque(int i, const std::vector<double>& v) const {
    return (HasAbove(i) ? DashpotAbove(i) * (v[i - 1] - v[i]) : 0.0) +
           (HasBelow(i) ? DashpotBelow(i) * (v[i + 1] - v[i]) : 0.0);
  }
  double DashpotPower(const std::vector<double>& v) const {
    double power = 0;
    for (int k = 0; k + 1 < num_nodes_; ++k) power += net_.sections[k].dashpot * (v[k + 1] - v[k]) * (v[k + 1] - v[k]);
    return power;
  }

  // Waves leaving every node at time t: w_out = v - w_in on each of its sections, with their rates if asked.
  void OutgoingWaves(double t, const State& x, const State& f, Side side, double* out, double* rate) const {
    if (kelvin_voigt_) {
      SolveNodeSpeeds(x, t, side, speeds_);
      if (rate) SolveNodeSpeedRates(f, t, side, speed_rates_);
    }
    for (int i = 0; i < num_nodes_; ++i) {
      const Arrivals in = Arriving(i, t, side);
      const bool inertial = speed_index_[i] != kNone;
      const double v = inertial ? (regime_[i] == Turn::kStuck ? 0.0 : x[speed_index_[i]])
                       : kelvin_voigt_ ? speeds_[i]
                                       : MasslessSpeed(i, in, t, side);
      if (HasAbove(i)) out[2 * (i - 1) + 1] = v - in.above;  // up-going wave at the bottom of section i-1
      if (HasBelow(i)) out[2 * i] = v - in.below;            // down-going wave at the top of section i
      if (!rate) continue;
      const Arrivals in_rate = ArrivingRate(i, t, side);
      const double dv = inertial ? (regime_[i] == Turn::kStuck ? 0.0 : f[speed_index_[i]])
                        : kelvin_voigt_ ? speed_rates_[i]
                                        : MasslessSpeedRate(i, v, in_rate, t, side);
      if (HasAbove(i)) rate[2 * (i - 1) + 1] = dv - in_rate.above;
      if (HasBelow(i)) rate[2 * i] = dv - in_rate.below;
    }
  }

  // Rigid rotation at the initial speed: every section carries the torque of everything below it.
  void InitializeWaves() {
    const double v0 = net_.initial.speed_rad_s;
    std::vector<double> torque_below(net_.sections.size(), 0.0);
    double acc = 0;
    for (int i = num_nodes_ - 1; i >= 1; --i) torque_below[i - 1] = acc += net_.nodes[i].SteadyLoad(v0);
    steady_torque_ = net_.SteadyTopTorque();
    const int m = waves_.dimension();
    std::vector<double> initial(m);
    for (std::size_t k = 0; k < net_.sections.size(); ++k) {
      const double z = net_.sections[k].impedance;
      initial[2 * k] = 0.5 * (v0 + torque_below[k] / z);      // down: D - U = T / Z, D + U = v0
      initial[2 * k + 1] = 0.5 * (v0 - torque_below[k] / z);  // up
    }
    waves_ = integration::HermiteHistory(m, [initial](double, double* value, double* rate) {
      std::copy(initial.begin(), initial.end(), value);
      std::fill(rate, rate + initial.size(), 0.0);
    });
  }

  // A discontinuity at node i at time t travels into each of its sections and reaches the far node one travel time
  // later. After a massless node its signed size is scaled by that node's reflection or transmission coefficient;
  // an inertial node (or an imposed speed) reflects a jump as a jump of opposite sign but passes it on to its other
  // sections smoothed by one order. Echoes arriving together are merged (BreakpointQueue), so that the signed sum of
  // all paths decides, as the waves themselves do, and an echo is dropped once it falls below its threshold.
  //
  // Kelvin-Voigt dashpots couple a node's speed to its neighbours' at the same instant. A discontinuity arriving at a
  // massless node then changes every massless node of its run (the nodes between two nodes of known speed) at once,
  // by the column of the inverse of the node system (EchoThroughDashpots): each sends its change into both its
  // sections, and the node it arrived at also passes on the arriving part (w_out = v - w_in). A known speed that
  // jumps or kinks (an imposed speed's knot, an inertial node's kink) enters its neighbours' balances through the
  // dashpot, kv dv, and spreads over their runs the same way. A jump at a massless node next to an inertial node
  // jumps the dashpot torque on it: the inertial node's speed kinks (weight kv dv / 2 Z, as an arriving wave's
  // 2 Z w). Spreading stops there: kinks that the dashpots pass on further, and kinks of order above 2, are left to
  // the step-size control (they cost rejected steps, not accuracy).
  void Echo(const integration::Breakpoint& b) {
    const int i = b.site;
    const Node& node = net_.nodes[i];
    if (kelvin_voigt_ && !KnownSpeed(i)) {
      EchoThroughDashpots(b);
      return;
    }
    const double sum = MasslessConductance(i);
    const bool scatters = node.massless() && node.drive != Drive::kPrescribedSpeed && b.via != kNone;
    for (int k : {i - 1, i}) {
      if (k < 0 || k >= static_cast<int>(net_.sections.size())) continue;
      double w = b.weight;
      int order = b.order;
      if (scatters) {
        const double share = 2 * net_.sections[b.via].impedance / sum;
        w *= k == b.via ? share - 1 : share;
      } else if (b.via != kNone && k == b.via) {
        w = -w;  // w_out = v - w_in with v continuous (inertia) or imposed
      } else if (!node.massless()) {
        order = std::max(order + (b.via == kNone ? 0 : 1), 1);  // the node's speed is continuous
      }
      PushEcho(b.time, i, k, w, order, b.generation + 1);
    }
    if (!kelvin_voigt_) return;
    // The known speed's own change: an imposed speed's knot as it is; an inertial node's speed one order smoother.
    const bool imposed = node.drive == Drive::kPrescribedSpeed;
    if (imposed && b.via != kNone) return;  // an arriving wave does not change an imposed speed
    const int order = imposed ? b.order : std::max(b.order + (b.via == kNone ? 0 : 1), 1);
    if (order > kMaxSpreadOrder) return;
    for (int k : {i - 1, i}) {
      if (k < 0 || k >= static_cast<int>(net_.sections.size()) || net_.sections[k].dashpot == 0) continue;
      const int neighbour = k == i - 1 ? i - 1 : i + 1;
      if (!KnownSpeed(neighbour)) SpreadOverRun(neighbour, net_.sections[k].dashpot * b.weight, b.time, order, b, false);
    }
  }

  // A breakpoint arriving at (or starting from) a massless node of a Kelvin-Voigt run.
  void EchoThroughDashpots(const integration::Breakpoint& b) {
    const int i = b.site;
    // An arriving wave adds 2 Z w to the node's balance; a source is a unit change of the node's own speed.
    const double balance_change = b.via != kNone ? 2 * net_.sections[b.via].impedance * b.weight : 0.0;
    SpreadOverRun(i, balance_change, b.time, b.order, b, b.via == kNone);
  }

  // The speeds of the run through node i change by A^-1 e_i times `balance_change` (or, for a source at i, so that
  // node i's own changes by the breakpoint's weight): each changed node sends its change into its sections.
  void SpreadOverRun(int i, double balance_change, double t, int order, const integration::Breakpoint& b,
                     bool unit_at_node) {
    std::vector<double> dv(num_nodes_, 0.0);
    dv[i] = 1;
    SolveNodeSystem(dv.data());
    const double scale = unit_at_node ? b.weight / dv[i] : balance_change;
    for (double& v : dv) v *= scale;
    std::vector<std::array<double, 2>> arrived(num_nodes_, {0.0, 0.0});
    if (b.site == i && b.via != kNone) arrived[i][b.via == i - 1 ? 0 : 1] = b.weight;
    EmitFromRuns(dv, arrived, t, order, b.generation + 1);
  }

  // All the breakpoints of one order that arrive at massless nodes at time t at once: the node system is linear, so
  // their balance changes add and one solve spreads them all (followed one by one, each would spread over its run and
  // the echoes would be merged afterwards: the same result, at the cost of one solve and 2 n pushes per arrival).
  void EchoArrivalsThroughDashpots(double t, std::vector<integration::Breakpoint>& due) {
    std::map<int, std::pair<std::vector<double>, std::vector<std::array<double, 2>>>> by_order;
    int generation = 0;
    auto arrival_here = [&](const integration::Breakpoint& b) { return b.via != kNone && !KnownSpeed(b.site); };
    for (const integration::Breakpoint& b : due) {
      if (!arrival_here(b)) continue;
      auto& [rhs, arrived] = by_order[b.order];
      if (rhs.empty()) rhs.assign(num_nodes_, 0.0), arrived.assign(num_nodes_, {0.0, 0.0});
      rhs[b.site] += 2 * net_.sections[b.via].impedance * b.weight;
      arrived[b.site][b.via == b.site - 1 ? 0 : 1] += b.weight;
      generation = std::max(generation, b.generation);
    }
    due.erase(std::remove_if(due.begin(), due.end(), arrival_here), due.end());
    for (auto& [order, change] : by_order) {
      SolveNodeSystem(change.first.data());
      EmitFromRuns(change.first, change.second, t, order, generation + 1);
    }
  }

  // Massless nodes whose speeds change by dv at time t send dv into both their sections, less the part `arrived`
  // through each (w_out = v - w_in; [0] from above, [1] from below).
  void EmitFromRuns(const std::vector<double>& dv, const std::vector<std::array<double, 2>>& arrived, double t,
                    int order, int generation) {
    for (int j = 0; j < num_nodes_; ++j) {
      if (dv[j] == 0 && arrived[j][0] == 0 && arrived[j][1] == 0) continue;
      for (int k : {j - 1, j}) {
        if (k < 0 || k >= static_cast<int>(net_.sections.size())) continue;
        PushEcho(t, j, k, dv[j] - arrived[j][k == j - 1 ? 0 : 1], order, generation);
        // A jump next to an inertial node kinks it through the dashpot between them.
        const int neighbour = k == j - 1 ? j - 1 : j + 1;
        if (order == 0 && speed_index_[neighbour] != kNone && net_.sections[k].dashpot > 0) {
          const double w = net_.sections[k].dashpot * dv[j] / (2 * net_.sections[k].impedance);
          if (std::abs(w) >= kink_threshold_) Echo({t, neighbour, w, 1, kNone, generation});
        }
      }
    }
  }

  // An echo of weight w leaving node i at time t into section k, unless it is below its threshold or past the end.
  void PushEcho(double t, int i, int k, double w, int order, int generation) {
    if (std::abs(w) < (order == 0 ? jump_threshold_ : kink_threshold_)) return;
    const int far = k == i - 1 ? i - 1 : i + 1;
    const double arrival = t + net_.sections[k].travel_time_s;
    if (arrival >= t_end_) return;
    const integration::Breakpoint echo{arrival, far, w, order, k, generation};
    // Past the cap a kink may still join one that is pending, but not add to their number.
    if (order > 0 && breakpoints_.size() >= options_.max_pending_kinks) breakpoints_.Merge(echo, MergeWindow(arrival));
    else breakpoints_.Push(echo, MergeWindow(arrival));
  }
  static double MergeWindow(double t) { return 1e-10 * std::max(1.0, std::abs(t)); }
  // A new discontinuity at node i: a regime change (kink, order 1) or an input knot (jump if the schedule jumps).
  void Source(int i, double t, int order) { Echo({t, i, 1.0, order, kNone, 0}); }

 public:
  void set_t_end(double t_end) { t_end_ = t_end; }

 private:
  const Network& net_;
  const NetworkRunOptions& options_;
  double kink_threshold_, jump_threshold_;
  int num_nodes_;
  int dimension_ = 0;
  std::vector<int> speed_index_, integral_index_, current_index_, flux_index_, motor_speed_index_;
  std::vector<int> frictional_nodes_;
  std::vector<Turn> regime_;
  integration::HermiteHistory waves_;
  integration::BreakpointQueue breakpoints_;
  std::vector<RegimeChange> changes_;
  double step_start_ = 0;
  double max_travel_time_ = 0;
  double steady_torque_ = 0;
  double t_end_ = std::numeric_limits<double>::infinity();
  std::vector<double> out0_, out1_, outm_, d0_, d1_, outq_, state_quarter_;  // the prepared piece's waves (ends, midpoint, rates)
  int lateral_index_ = kNone;  // the bit's lateral BHA
  // Kelvin-Voigt: the node system's factors (FactorNodeSystem), the dissipated energy's state, scratch.
  bool kelvin_voigt_ = false;
  bool massless_bit_friction_ = false;  // a massless bit with smooth friction closes the node system's sweep
  int dissipated_index_ = kNone;
  std::vector<double> lower_, ratio_, inv_pivot_;
  mutable std::vector<double> speeds_, speed_rates_;
  bool start_is_last_end_ = false;
  double last_end_time_ = 0;
};

}  // namespace

double AutomaticKinkThreshold(const integration::IntegratorOptions& integrator) {
  return std::clamp(std::sqrt(std::max(integrator.abs_tol, integrator.rel_tol)), 1e-5, 3e-2);
}

double AutomaticJumpThreshold(const integration::IntegratorOptions& integrator) {
  return std::clamp(0.1 * std::min(integrator.abs_tol, integrator.rel_tol), 1e-15, 1e-6);
}

NetworkRun SimulateNetwork(const Network& network, const NetworkRunOptions& options) {
  network.Validate();
  NetworkProcess process(network, options);
  process.set_t_end(options.t_end_s);
  State x = process.InitialState();
  process.InitializeRegimes(0.0, x);
  process.SeedBreakpoints(0.0, options.t_end_s);

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
