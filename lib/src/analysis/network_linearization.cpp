#include "drillwave/analysis/network_linearization.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "drillwave/analysis/bha_whirl_linearization.hpp"
#include "drillwave/analysis/induction_linearization.hpp"
#include "drillwave/core/constants.hpp"

namespace drillwave::analysis {
namespace {

using waves::Drive;
using waves::Network;
using waves::Node;

double Clamp(double u, double limit) { return limit > 0 ? std::clamp(u, -limit, limit) : u; }

// Torque a node takes from the string in steady rotation at w: ground damping, friction, and the steady whirl of a
// lateral BHA.
double NodeTorque(const Node& n, double w) {
  return n.ground_damping * w + (n.friction ? n.friction->SlipTorque(w) : 0.0) +
         (n.lateral ? n.lateral->SteadyDragTorque(w) : 0.0);
}

double Load(const Network& net, double w) {
  double load = 0;
  for (const Node& n : net.nodes) load += NodeTorque(n, w);
  return load;
}

// Its slope without the whirl's (AddBhaWhirl linearizes the whirl with its own states).
double NodeTorqueSlope(const Node& n, double w) {
  return n.ground_damping + (n.friction ? n.friction->SlipTorqueDerivative(w) : 0.0);
}

// Tops whose integral action (or imposition) holds the speed at the set-point in steady state.
bool HoldsSpeed(const Node& top) {
  return top.drive == Drive::kPrescribedSpeed || (top.has_speed_integral() && top.pi.ki > 0);
}

// A DC motor's constant referred to the node's side of its gear: torque n k I, back-emf n k w (as the simulation).
double ReferredMotorConstant(const Node& top) { return top.gear.ratio * top.motor.motor_constant; }

// An induction motor's supply in steady rotation at w carrying `torque` (on the node's side): the set-point in open
// loop; under a proportional controller the supply of its demand; with an integral gain the frequency the simulation
// starts from (model::InductionMotor::SteadySupplyFrequency at the motor's shaft speed n w; it throws
// std::domain_error beyond the pull-out torque).
double SteadySupplyHz(const Node& top, double set, double w, double torque) {
  if (top.drive == Drive::kInductionMotor) return set;
  const double n = top.gear.ratio;
  if (!(top.pi.ki > 0)) return top.induction.SupplyForTorque(top.pi.Proportional(set, w) / n, n * w);
  return top.induction.SteadySupplyFrequency(torque / n, n * w);
}

// The torque a balancing top supplies when it turns at w, and whether its limit (torque, voltage or the slip of a
// slip-frequency drive) is reached there. Everything on the node's side of the gear.
double Supply(const Node& top, double set, double w, bool& saturated) {
  const waves::DcMotor& m = top.motor;
  const double n = top.gear.ratio;
  double u = 0;
  switch (top.drive) {
    case Drive::kSpeedDashpot: return top.drive_damping * (set - w);
    case Drive::kTorque: return set;
    case Drive::kPiSpeedController:
      u = top.pi.Proportional(set, w);
      saturated = top.law.torque_limit > 0 && std::abs(u) >= top.law.torque_limit;
      return Clamp(u, top.law.torque_limit);
    case Drive::kDcMotorVoltage:
    case Drive::kDcMotorSpeed: {
      const double k = ReferredMotorConstant(top);
      u = top.drive == Drive::kDcMotorVoltage ? set : top.pi.Proportional(set, w);
      saturated = m.voltage_limit > 0 && std::abs(u) >= m.voltage_limit;
      return k * (Clamp(u, m.voltage_limit) - k * w) / m.armature_resistance;
    }
    case Drive::kInductionMotor: return n * top.induction.Torque(top.induction.SteadyFluxes(set, n * w));
    case Drive::kInductionMotorSpeed: {  // proportional only: the demand's slip at the measured speed
      const model::InductionMotor& im = top.induction;
      u = top.pi.Proportional(set, w);
      saturated = std::abs(u / n) >= im.SlipTorqueGain() * im.PullOutSlipFrequency();
      const double f = im.SupplyForTorque(u / n, n * w);
      return n * im.Torque(im.SteadyFluxes(f, n * w));
    }
    default: return 0;
  }
}

// Where a balancing top's supply falls to zero (no steady forward rotation beyond it), or a bound for a torque top.
double LargestSpeed(const Network& net, double set) {
  const Node& top = net.top();
  const waves::DcMotor& m = top.motor;
  switch (top.drive) {
    case Drive::kSpeedDashpot:
    case Drive::kPiSpeedController:
    case Drive::kInductionMotorSpeed: return set;  // no demand, no slip: no torque
    case Drive::kDcMotorVoltage: return Clamp(set, m.voltage_limit) / ReferredMotorConstant(top);
    case Drive::kDcMotorSpeed: return top.pi.kp * set / (top.pi.kp + ReferredMotorConstant(top));
    case Drive::kInductionMotor: return 2 * kPi * set / (top.induction.pole_pairs * top.gear.ratio);  // synchronous
    case Drive::kTorque: {
      double damping = 0;
      for (const Node& n : net.nodes) damping += n.ground_damping;
      return damping > 0 ? set / damping : 1e3;  // undamped: friction alone balances; searched up to 1000 rad/s
    }
    default: return 0;
  }
}

NetworkOperatingPoint PointAt(const Network& net, double set, double w) {
  return {set, w, Load(net, w), NodeTorque(net.bit(), w), NodeTorqueSlope(net.bit(), w)};
}

// Whether a speed-holding top can supply the load at the set-point: within its torque or voltage limit, and for an
// induction motor below its pull-out torque (SteadySupplyFrequency throws beyond it).
bool CanHold(const Node& top, const NetworkOperatingPoint& p) {
  const waves::DcMotor& m = top.motor;
  if (top.drive == Drive::kPiSpeedController && top.law.torque_limit > 0 && p.top_torque_Nm >= top.law.torque_limit)
    return false;
  if (top.has_dc_motor() && m.voltage_limit > 0) {
    const double k = ReferredMotorConstant(top);
    if (m.armature_resistance * p.top_torque_Nm / k + k * p.speed_rad_s >= m.voltage_limit) return false;
  }
  if (top.drive == Drive::kInductionMotorSpeed) {
    try {
      SteadySupplyHz(top, p.top_setpoint, p.speed_rad_s, p.top_torque_Nm);
    } catch (const std::domain_error&) {
      return false;
    }
  }
  return true;
}

// The linearization of one network about an operating point (LinearizeNetwork), assembled node by node into a neutral
// delay system: the states named in the simulation's order, every node's speed perturbation as a linear form, the
// outgoing waves, then each inertial node's torque balance with its drive's and controller's states.
class NetworkLinearizer {
 public:
  NetworkLinearizer(const Network& net, const NetworkOperatingPoint& point)
      : net_(net), w0_(point.speed_rad_s), point_(point), sections_(static_cast<int>(net.sections.size())),
        nodes_(sections_ + 1) {}

  NetworkLinearization Build() {
    NameStates();
    sys_.a0 = Eigen::MatrixXd::Zero(n_, n_);
    sys_.derivative_only_states = 2 * sections_;
    for (int k = 0; k < sections_; ++k)
      sys_.delays.push_back({net_.sections[k].travel_time_s, {}, Eigen::MatrixXd::Zero(n_, n_)});
    FormSpeeds();
    for (int i = 0; i < nodes_; ++i) {
      AddOutgoingWaves(i);
      if (speed_[i] < 0) continue;
      if (net_.nodes[i].law.wave_cancellation.active()) AddWaveCancellingTop(i);
      else AddDrivenNode(i);
    }
    const Node& bit = net_.bit();
    if (bit.lateral)
      AddBhaWhirl(out_, speed_[nodes_ - 1], bit.LumpedInertia(), bit.LumpedInertia() - bit.lateral->AddedInertia(),
                  *bit.lateral, w0_);
    return std::move(out_);
  }

 private:
  // A wave arriving at a node: from the section above (p_{i-1}) or below (q_i), one travel time late.
  struct Arrival {
    int section, column;
    double impedance;
  };
  // A node's speed perturbation as a linear form: coefficients of the states (into A_0) and of the arriving waves'
  // derivatives (into the neutral term of the wave's section, one travel time late).
  struct SpeedForm {
    Eigen::RowVectorXd state, wave;  // wave: by the arriving wave's column
    // What it holds `late` ago (a wave-cancelling top's speed follows what its law read an actuator delay ago):
    // retarded coefficients of the states and neutral ones of the arriving waves, that much later still.
    double late = 0;
    Eigen::RowVectorXd late_state, late_wave;
  };

  std::string NodeLabel(int i) const {
    return i == 0 ? std::string("top") : i == nodes_ - 1 ? std::string("bit") : "node" + std::to_string(i);
  }

  // Node states in the simulation's order: speeds of inertial nodes, integrals of speed controllers with an integral
  // gain, torque-feedback filters (the low-passed string torque), DC currents, induction fluxes, then behind a
  // compliant gear the motor's speed (referred to the node) and the gear's twist; then the sections' wave integrals.
  void NameStates() {
    auto& names = out_.state_names;
    speed_.assign(nodes_, -1), integral_.assign(nodes_, -1), filter_.assign(nodes_, -1);
    current_.assign(nodes_, -1), flux_.assign(nodes_, -1), motor_.assign(nodes_, -1);
    auto add = [&](std::vector<int>& index, int i, std::initializer_list<std::string> suffixes) {
      index[i] = static_cast<int>(names.size());
      for (const std::string& suffix : suffixes) names.push_back(NodeLabel(i) + suffix);
    };
    // A wave-cancelling top's state is its speed's error to the law's speed (AddWaveCancellingTop).
    for (int i = 0; i < nodes_; ++i)
      if (!net_.nodes[i].massless())
        add(speed_, i,
            {net_.nodes[i].law.wave_cancellation.active() ? "_speed_off_wave_law_rad_s" : "_speed_rad_s"});
    for (int i = 0; i < nodes_; ++i)
      if (net_.nodes[i].has_speed_integral() && net_.nodes[i].pi.ki > 0) add(integral_, i, {"_speed_error_integral_rad"});
    for (int i = 0; i < nodes_; ++i)
      if (net_.nodes[i].has_drive_filter())
        add(filter_, i,
            {net_.nodes[i].has_torque_feedback() ? "_low_passed_string_torque_Nm" : "_low_passed_arriving_wave_rad_s"});
    for (int i = 0; i < nodes_; ++i)
      if (net_.nodes[i].has_dc_motor()) add(current_, i, {"_current_A"});
    for (int i = 0; i < nodes_; ++i)
      if (net_.nodes[i].has_induction_motor())
        add(flux_, i, {"_stator_flux_d_Wb", "_stator_flux_q_Wb", "_rotor_flux_d_Wb", "_rotor_flux_q_Wb"});
    for (int i = 0; i < nodes_; ++i)
      if (net_.nodes[i].has_compliant_gear()) add(motor_, i, {"_motor_speed_referred_rad_s", "_gear_twist_rad"});
    first_wave_ = static_cast<int>(names.size());
    for (int k = 0; k < sections_; ++k) {
      names.push_back("section" + std::to_string(k) + "_down_wave_integral_rad");
      names.push_back("section" + std::to_string(k) + "_up_wave_integral_rad");
    }
    n_ = static_cast<int>(names.size());
  }

  int Down(int k) const { return first_wave_ + 2 * k; }     // p_k: leaves node k into section k
  int Up(int k) const { return first_wave_ + 2 * k + 1; }   // q_k: leaves node k + 1 into section k
  int SectionOf(int column) const { return (column - first_wave_) / 2; }

  std::vector<Arrival> Arrivals(int i) const {
    std::vector<Arrival> a;
    if (i > 0) a.push_back({i - 1, Down(i - 1), net_.sections[i - 1].impedance});
    if (i < sections_) a.push_back({i, Up(i), net_.sections[i].impedance});
    return a;
  }
  double ImpedanceSum(int i) const {
    double z = 0;
    for (const Arrival& a : Arrivals(i)) z += a.impedance;
    return z;
  }

  // An inertial node's speed is its state, an imposed one's nothing; the massless nodes balance the arrivals against
  // their damping (the ground's, the friction slope and a dissipative top's beta) and, with Kelvin-Voigt dashpots kv
  // across the sections, against their neighbours' speeds, as the simulation's node system:
  //   (sum Z + damping + kv_above + kv_below) v_i - kv_above v_{i-1} - kv_below v_{i+1} = sum 2 Z w_in,
  // with the known speeds of inertial neighbours moved to the right. One linear system over the massless nodes
  // (diagonal without dashpots).
  void FormSpeeds() {
    const Eigen::RowVectorXd none = Eigen::RowVectorXd::Zero(n_);
    speed_form_.assign(nodes_, {none, none, 0.0, none, none});
    std::vector<int> unknown(nodes_, -1);  // massless nodes of free speed, numbered
    int unknowns = 0;
    for (int i = 0; i < nodes_; ++i) {
      if (speed_[i] >= 0) speed_form_[i].state(speed_[i]) = 1;
      else if (net_.nodes[i].drive != Drive::kPrescribedSpeed) unknown[i] = unknowns++;
    }
    if (unknowns > 0) {
      Eigen::MatrixXd balance = Eigen::MatrixXd::Zero(unknowns, unknowns), rhs = Eigen::MatrixXd::Zero(unknowns, 2 * n_);
      for (int i = 0; i < nodes_; ++i) {
        const int u = unknown[i];
        if (u < 0) continue;
        const Node& node = net_.nodes[i];
        balance(u, u) = ImpedanceSum(i) + NodeTorqueSlope(node, w0_) +
                        (node.drive == Drive::kSpeedDashpot ? node.drive_damping : 0.0);
        for (const Arrival& a : Arrivals(i)) {
          rhs(u, n_ + a.column) += 2 * a.impedance;
          const double kv = net_.sections[a.section].dashpot;
          if (kv == 0) continue;
          const int neighbour = a.section == i ? i + 1 : i - 1;
          balance(u, u) += kv;
          if (unknown[neighbour] >= 0) balance(u, unknown[neighbour]) -= kv;
          else rhs.block(u, 0, 1, n_) += kv * speed_form_[neighbour].state;  // imposed: no perturbation
        }
        if (!(std::abs(balance(u, u)) > 1e-12 * ImpedanceSum(i)))
          throw std::invalid_argument("node '" + node.name + "' is massless and its torque slope cancels the string's "
                                      "impedance: the linearization is singular");
      }
      const Eigen::PartialPivLU<Eigen::MatrixXd> lu(balance);
      if (!(lu.rcond() > 1e-12))
        throw std::invalid_argument("the massless nodes' balance with the Kelvin-Voigt dashpots is singular");
      const Eigen::MatrixXd solved = lu.solve(rhs);
      for (int i = 0; i < nodes_; ++i)
        if (unknown[i] >= 0) {
          speed_form_[i].state = solved.block(unknown[i], 0, 1, n_);
          speed_form_[i].wave = solved.block(unknown[i], n_, 1, n_);
        }
    }
    // A wave-cancelling top turns at v = e + w(t - late) + k I(t - late): the speed its law asked for an actuator
    // delay ago (model::WaveCancellation: the arriving wave w plus d, whose perturbation is k I) and the error e, its
    // state. Filtered, the low-passed wave a(t) stands for w(t - late): the filter reads the wave late and is a state.
    if (net_.top().law.wave_cancellation.active()) {
      const Node& top = net_.top();
      SpeedForm& form = speed_form_[0];
      form.late = top.law.actuator_delay_s;
      (form.late > 0 ? form.late_state : form.state)(integral_[0]) += top.law.wave_cancellation.Corner(top.pi.ki);
      if (top.law.wave_cancellation.filtered())
        form.state(filter_[0]) += 1;
      else
        (form.late > 0 ? form.late_wave : form.wave)(Up(0)) += 1;
    }
  }

  // The delay term at tau, added (with zero matrices) if there is none yet: an actuator delay's.
  DelayTerm& DelayAt(double tau) {
    auto it = std::find_if(sys_.delays.begin(), sys_.delays.end(), [&](const DelayTerm& d) { return d.tau == tau; });
    if (it == sys_.delays.end()) it = sys_.delays.insert(sys_.delays.end(), {tau, {}, Eigen::MatrixXd::Zero(n_, n_)});
    if (it->retarded.size() == 0) it->retarded = Eigen::MatrixXd::Zero(n_, n_);
    if (it->neutral.size() == 0) it->neutral = Eigen::MatrixXd::Zero(n_, n_);
    return *it;
  }
  // value * (state `column`, `lag` ago) and value * (the wave of `column` arriving `lag` ago) into row `row`.
  void AddState(int row, int column, double value, double lag) {
    if (lag == 0) sys_.a0(row, column) += value;
    else DelayAt(lag).retarded(row, column) += value;
  }
  void AddWave(int row, int column, double value, double lag) {
    const int k = SectionOf(column);
    if (lag == 0) sys_.delays[k].neutral(row, column) += value;
    else DelayAt(net_.sections[k].travel_time_s + lag).neutral(row, column) += value;
  }
  // factor * (speed of node i, `lag` ago) into row `row`.
  void AddSpeed(int row, int i, double factor, double lag = 0) {
    const SpeedForm& form = speed_form_[i];
    if (lag == 0) sys_.a0.row(row) += factor * form.state;
    else DelayAt(lag).retarded.row(row) += factor * form.state;
    for (int c = first_wave_; c < n_; ++c)
      if (form.wave(c) != 0) AddWave(row, c, factor * form.wave(c), lag);
    if (form.late == 0) return;
    for (int c = 0; c < n_; ++c) {
      if (form.late_state(c) != 0) AddState(row, c, factor * form.late_state(c), lag + form.late);
      if (form.late_wave(c) != 0) AddWave(row, c, factor * form.late_wave(c), lag + form.late);
    }
  }

  // Outgoing waves: speed minus the arriving wave of the same section.
  void AddOutgoingWaves(int i) {
    for (const Arrival& a : Arrivals(i)) {
      const int row = a.column == Down(a.section) ? Up(a.section) : Down(a.section);
      AddSpeed(row, i, 1.0);
      sys_.delays[a.section].neutral(row, a.column) -= 1.0;
    }
  }

  // Its torque cancels g, the torque of the string and its dampers, as read: J e' = g(t) - g(t - late) -
  // kp (v - w - d)(t - late), g = sum 2 Z w_in - (sum Z + c) v (without a delay e' = -kp e / J); I' = -v, as read.
  // Filtered, a(t) stands for w(t - late) there.
  void AddWaveCancellingTop(int i) {
    const Node& node = net_.nodes[i];
    const int v = speed_[i];
    const double late = node.law.actuator_delay_s, inertia = node.LumpedInertia(), kp = node.pi.kp;
    auto add_string_and_dampers = [&](double factor, double lag) {
      for (const Arrival& a : Arrivals(i)) AddWave(v, a.column, factor * 2 * a.impedance, lag);
      AddSpeed(v, i, -factor * (ImpedanceSum(i) + NodeTorqueSlope(node, w0_)), lag);
    };
    if (late > 0) add_string_and_dampers(1 / inertia, 0), add_string_and_dampers(-1 / inertia, late);
    AddSpeed(v, i, -kp / inertia, late);
    AddState(v, integral_[i], kp / inertia * node.law.wave_cancellation.Corner(node.pi.ki), late);
    AddSpeed(integral_[i], i, -1, late);
    const model::WaveCancellation& law = node.law.wave_cancellation;
    if (!law.filtered()) {
      AddWave(v, Up(0), kp / inertia, late);
      return;
    }
    // kp a(t) instead of kp w(t - late); tf a' = w(t - late) - a.
    const int a = filter_[i];
    AddState(v, a, kp / inertia, 0);
    AddWave(a, Up(0), 1 / law.filter_time_constant_s, late);
    sys_.a0(a, a) -= 1 / law.filter_time_constant_s;
  }

  // An inertial node under its drive: the string's waves, its dashpots and damping, a compliant gear's motor, and
  // the rows of its controller's integral, torque filter, DC current and induction fluxes.
  void AddDrivenNode(int i) {
    const DrivenNode d(*this, i);
    d.AddInertialRows();
    d.AddControllerRows();
  }

  // One driven node's rows (AddDrivenNode), with what its drive reads: its speed or its motor's behind a compliant
  // gear, an actuator delay late under a PI.
  class DrivenNode {
   public:
    DrivenNode(NetworkLinearizer& l, int i)
        : l_(l), i_(i), node_(l.net_.nodes[i]), v_(l.speed_[i]), vd_(l.motor_[i] >= 0 ? l.motor_[i] : v_),
          n_gear_(node_.gear.ratio),
          late_(node_.drive == Drive::kPiSpeedController ? node_.law.actuator_delay_s : 0.0) {
      if (l.flux_[i] >= 0) {
        if (i != 0)  // its steady supply comes from the top's set-point and torque
          throw std::invalid_argument("node '" + node_.name + "': an induction motor is linearized at the top only");
        const double f0 = SteadySupplyHz(node_, l.point_.top_setpoint, l.w0_, l.point_.top_torque_Nm);
        induction_ = LinearizeInductionMotor(node_.induction, f0, n_gear_ * l.w0_);
      }
    }

    void AddInertialRows() const {
      LinearDelaySystem& sys = l_.sys_;
      const int v = v_;
      const double inertia = node_.LumpedInertia();
      for (const Arrival& a : l_.Arrivals(i_)) {
        sys.delays[a.section].neutral(v, a.column) += 2 * a.impedance / inertia;
        const double kv = l_.net_.sections[a.section].dashpot;  // Kelvin-Voigt: kv (v_neighbour - v)
        if (kv == 0) continue;
        l_.AddSpeed(v, a.section == i_ ? i_ + 1 : i_ - 1, kv / inertia);
        sys.a0(v, v) -= kv / inertia;
      }
      sys.a0(v, v) -= (l_.ImpedanceSum(i_) + NodeTorqueSlope(node_, l_.w0_)) / inertia;
      if (l_.motor_[i_] >= 0) {  // the gear passes k twist + c (w_m - w) to the node
        const model::Gear& g = node_.gear;
        const int vm = l_.motor_[i_], twist = l_.motor_[i_] + 1;
        const double jm = g.ReferredMotorInertia();
        sys.a0(v, twist) += g.stiffness / inertia;
        sys.a0(v, vm) += g.damping / inertia;
        sys.a0(v, v) -= g.damping / inertia;
        AddDriveTorque(vm, 1 / jm);
        sys.a0(vm, twist) -= g.stiffness / jm;
        sys.a0(vm, vm) -= g.damping / jm;
        sys.a0(vm, v) += g.damping / jm;
        sys.a0(twist, vm) = 1;
        sys.a0(twist, v) = -1;
      } else {
        AddDriveTorque(v, 1 / inertia);
      }
    }

    void AddControllerRows() const {
      LinearDelaySystem& sys = l_.sys_;
      const int integral = l_.integral_[i_], filter = l_.filter_[i_], current = l_.current_[i_], flux = l_.flux_[i_];
      if (integral >= 0) {  // d/dt integral of (command - drive speed)
        if (node_.drive == Drive::kPiSpeedController) AddReadSpeed(integral, -1);
        else sys.a0(integral, vd_) = -1;
        AddCommand(integral, 1.0);
      }
      if (filter >= 0) {  // T_lp' = (T - T_lp) / time constant
        const double rate = 1 / node_.law.torque_feedback.time_constant_s;
        AddStringTorque(filter, rate);
        sys.a0(filter, filter) -= rate;
      }
      if (current >= 0) {  // L I' = V - R I - n k w_d, V = the set-point or kp (set - w_d) + ki integral
        const waves::DcMotor& m = node_.motor;
        sys.a0(current, current) = -m.armature_resistance / m.armature_inductance;
        sys.a0(current, vd_) -= ReferredMotorConstant(node_) / m.armature_inductance;
        if (node_.drive == Drive::kDcMotorSpeed) {
          sys.a0(current, vd_) -= node_.pi.kp / m.armature_inductance;
          if (integral >= 0) sys.a0(current, integral) += node_.pi.ki / m.armature_inductance;
        }
      }
      if (flux >= 0) {
        // psi' = F(psi, f, n w_d). Open loop f is the set-point; slip-frequency control sets
        // f = (p n w_d + u / (n G)) / 2 pi for the PI's demand u = kp (set - w_d) + ki integral.
        sys.a0.block(flux, flux, 4, 4) += induction_.flux;
        sys.a0.block(flux, vd_, 4, 1) += n_gear_ * induction_.shaft_speed;
        if (node_.drive == Drive::kInductionMotorSpeed) {
          const double two_pi = 6.283185307179586, gain = n_gear_ * node_.induction.SlipTorqueGain();
          const double supply_per_speed = (node_.induction.pole_pairs * n_gear_ - node_.pi.kp / gain) / two_pi;
          sys.a0.block(flux, vd_, 4, 1) += supply_per_speed * induction_.supply_hz;
          if (integral >= 0)
            sys.a0.block(flux, integral, 4, 1) += node_.pi.ki / gain / two_pi * induction_.supply_hz;
        }
      }
    }

   private:
    // What a PI top's controller reads (its speed and the string torque) it reads an actuator delay late: those terms
    // are retarded by the delay, and the arriving waves in the string torque neutral at travel time + delay.
    void AddReadSpeed(int row, double value) const {
      if (late_ == 0) l_.sys_.a0(row, vd_) += value;
      else l_.DelayAt(late_).retarded(row, vd_) += value;
    }
    // factor * (the torque the node feeds into the string, as the controller reads it) into row `row`: minus the
    // string's force on it, sum Z (v - 2 w_in) and the dashpots' kv (v - v_neighbour) (no delay with dashpots).
    void AddStringTorque(int row, double factor) const {
      for (const Arrival& a : l_.Arrivals(i_)) {
        const double wave = -factor * 2 * a.impedance;
        if (late_ == 0) {
          l_.sys_.a0(row, v_) += factor * a.impedance;
          l_.sys_.delays[a.section].neutral(row, a.column) += wave;
        } else {
          l_.DelayAt(late_).retarded(row, v_) += factor * a.impedance;
          l_.DelayAt(l_.net_.sections[a.section].travel_time_s + late_).neutral(row, a.column) += wave;
        }
        const double kv = l_.net_.sections[a.section].dashpot;
        if (kv == 0) continue;
        l_.sys_.a0(row, v_) += factor * kv;
        l_.AddSpeed(row, a.section == i_ ? i_ + 1 : i_ - 1, -factor * kv);
      }
    }
    // factor * (the PI's speed command less the set-point) into row `row`: -gain (T - T_lp) with torque feedback.
    void AddCommand(int row, double factor) const {
      const int filter = l_.filter_[i_];
      if (filter < 0) return;
      const double gain = node_.law.torque_feedback.gain;
      AddStringTorque(row, -factor * gain);
      l_.sys_.a0(row, filter) += factor * gain;
    }
    // factor * (the drive's torque on the node's side) into row `row`.
    void AddDriveTorque(int row, double factor) const {
      LinearDelaySystem& sys = l_.sys_;
      switch (node_.drive) {
        case Drive::kSpeedDashpot: sys.a0(row, vd_) -= factor * node_.drive_damping; break;
        case Drive::kPiSpeedController:
          AddReadSpeed(row, -factor * node_.pi.kp);
          AddCommand(row, factor * node_.pi.kp);
          if (l_.integral_[i_] >= 0) sys.a0(row, l_.integral_[i_]) += factor * node_.pi.ki;
          break;
        case Drive::kDcMotorVoltage:
        case Drive::kDcMotorSpeed: sys.a0(row, l_.current_[i_]) += factor * ReferredMotorConstant(node_); break;
        case Drive::kInductionMotor:
        case Drive::kInductionMotorSpeed:
          for (int j = 0; j < 4; ++j) sys.a0(row, l_.flux_[i_] + j) += factor * n_gear_ * induction_.torque(j);
          break;
        default: break;
      }
    }

    NetworkLinearizer& l_;
    const int i_;
    const Node& node_;
    const int v_, vd_;
    const double n_gear_, late_;
    InductionJacobian induction_;
  };

  const Network& net_;
  const double w0_;
  const NetworkOperatingPoint& point_;
  const int sections_, nodes_;
  int first_wave_ = 0, n_ = 0;
  std::vector<int> speed_, integral_, filter_, current_, flux_, motor_;
  std::vector<SpeedForm> speed_form_;
  NetworkLinearization out_;
  LinearDelaySystem& sys_ = out_.system;
};

}  // namespace

std::vector<NetworkOperatingPoint> NetworkSteadyStates(const Network& net) {
  net.Validate();
  const Node& top = net.top();
  const double set = top.setpoint.knots().back().second;
  std::vector<NetworkOperatingPoint> points;
  if (HoldsSpeed(top)) {
    if (!(set > 0)) return points;
    const NetworkOperatingPoint p = PointAt(net, set, set);
    if (CanHold(top, p)) points.push_back(p);
    return points;
  }
  const double w_max = LargestSpeed(net, set);
  if (!(w_max > 0) || !std::isfinite(w_max)) return points;
  auto balance = [&](double w) {
    bool saturated = false;
    return Supply(top, set, w, saturated) - Load(net, w);
  };
  const int samples = 4000;  // two steady states closer than w_max / 4000 (at a fold) count as none or one
  double w_prev = w_max * 1e-9, f_prev = balance(w_prev);
  for (int i = 1; i <= samples; ++i) {
    const double w = w_max * i / samples;
    const double fw = balance(w);
    if (f_prev == 0 || (f_prev > 0) != (fw > 0) || fw == 0) {
      double lo = w_prev, hi = w, flo = f_prev;
      for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
        const double mid = 0.5 * (lo + hi), fm = balance(mid);
        if ((fm > 0) == (flo > 0)) lo = mid, flo = fm;
        else hi = mid;
      }
      const double w0 = 0.5 * (lo + hi);
      bool saturated = false;
      Supply(top, set, w0, saturated);
      // A saturated drive is a constant torque: the linearization would miss the clamp, so the point is left out.
      if (!saturated && (points.empty() || w0 - points.back().speed_rad_s > 1e-9 * w_max))
        points.push_back(PointAt(net, set, w0));
    }
    w_prev = w;
    f_prev = fw;
  }
  return points;
}

NetworkLinearization LinearizeNetwork(const Network& net, const NetworkOperatingPoint& point) {
  net.Validate();
  return NetworkLinearizer(net, point).Build();
}

}  // namespace drillwave::analysis
