#include "drillwave/analysis/network_linearization.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "drillwave/analysis/bha_whirl_linearization.hpp"

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
  const double pi = 3.14159265358979323846;
  switch (top.drive) {
    case Drive::kSpeedDashpot:
    case Drive::kPiSpeedController:
    case Drive::kInductionMotorSpeed: return set;  // no demand, no slip: no torque
    case Drive::kDcMotorVoltage: return Clamp(set, m.voltage_limit) / ReferredMotorConstant(top);
    case Drive::kDcMotorSpeed: return top.pi.kp * set / (top.pi.kp + ReferredMotorConstant(top));
    case Drive::kInductionMotor: return 2 * pi * set / (top.induction.pole_pairs * top.gear.ratio);  // synchronous
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

// The induction motor's flux equations and torque linearized about the fluxes psi0 that hold still at supply f0 and
// shaft speed wm0, by central differences of the model's own FluxRates and Torque (so they cannot drift from what the
// simulation integrates). These are exact up to rounding: the flux rates are affine in the fluxes and in the shaft
// speed (currents are linear in the fluxes), the torque is a quadratic form of the fluxes, and a central difference
// of a quadratic has no truncation error. The steps are therefore large (1e-4 of the scale), which keeps the rounding
// near 1e-12 relative. In the supply the rates are affine too except where the V/f line meets the voltage limit: the
// step stays within half the distance to that corner.
struct InductionJacobian {
  Eigen::Matrix4d flux = Eigen::Matrix4d::Zero();             // d psi' / d psi
  Eigen::Vector4d supply_hz = Eigen::Vector4d::Zero();        // d psi' / d f
  Eigen::Vector4d shaft_speed = Eigen::Vector4d::Zero();      // d psi' / d w_m
  Eigen::RowVector4d torque = Eigen::RowVector4d::Zero();     // d T / d psi
};

InductionJacobian LinearizeInductionMotor(const model::InductionMotor& m, double f0, double wm0) {
  using Fluxes = model::InductionMotor::Fluxes;
  const Fluxes psi0 = m.SteadyFluxes(f0, wm0);
  auto column = [](const Fluxes& plus, const Fluxes& minus, double h) {
    Eigen::Vector4d d;
    for (int r = 0; r < 4; ++r) d(r) = (plus[r] - minus[r]) / (2 * h);
    return d;
  };
  InductionJacobian jac;
  double scale = 0;
  for (double p : psi0) scale = std::max(scale, std::abs(p));
  const double h = 1e-4 * scale;
  for (int j = 0; j < 4; ++j) {
    Fluxes plus = psi0, minus = psi0;
    plus[j] += h, minus[j] -= h;
    jac.flux.col(j) = column(m.FluxRates(plus, f0, wm0), m.FluxRates(minus, f0, wm0), h);
    jac.torque(j) = (m.Torque(plus) - m.Torque(minus)) / (2 * h);
  }
  const double pi = 3.14159265358979323846;
  const double hw = 1e-4 * std::max(std::abs(wm0), 2 * pi * std::abs(f0) / m.pole_pairs + 1.0);
  jac.shaft_speed = column(m.FluxRates(psi0, f0, wm0 + hw), m.FluxRates(psi0, f0, wm0 - hw), hw);
  double hf = 1e-4 * std::max(std::abs(f0), 1.0);
  if (m.voltage_limit > 0) {
    const double corner = m.voltage_limit / m.volts_per_hertz, distance = std::abs(std::abs(f0) - corner);
    if (distance > 0) hf = std::min(hf, 0.5 * distance);
  }
  jac.supply_hz = column(m.FluxRates(psi0, f0 + hf, wm0), m.FluxRates(psi0, f0 - hf, wm0), hf);
  return jac;
}

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
  const int sections = static_cast<int>(net.sections.size()), nodes = sections + 1;
  const double w0 = point.speed_rad_s;
  NetworkLinearization out;
  auto& names = out.state_names;
  auto node_label = [&](int i) {
    return i == 0 ? std::string("top") : i == nodes - 1 ? std::string("bit") : "node" + std::to_string(i);
  };
  // Node states in the simulation's order: speeds of inertial nodes, integrals of speed controllers with an integral
  // gain, torque-feedback filters (the low-passed string torque), DC currents, induction fluxes, then behind a
  // compliant gear the motor's speed (referred to the node) and the gear's twist.
  std::vector<int> speed(nodes, -1), integral(nodes, -1), filter(nodes, -1), current(nodes, -1), flux(nodes, -1),
      motor(nodes, -1);
  // A wave-cancelling top's state is its speed's error to the law's speed (see its rows below).
  auto speed_name = [&](int i) {
    return node_label(i) + (net.nodes[i].law.wave_cancellation.active() ? "_speed_off_wave_law_rad_s" : "_speed_rad_s");
  };
  for (int i = 0; i < nodes; ++i)
    if (!net.nodes[i].massless()) speed[i] = static_cast<int>(names.size()), names.push_back(speed_name(i));
  for (int i = 0; i < nodes; ++i)
    if (net.nodes[i].has_speed_integral() && net.nodes[i].pi.ki > 0)
      integral[i] = static_cast<int>(names.size()), names.push_back(node_label(i) + "_speed_error_integral_rad");
  for (int i = 0; i < nodes; ++i)
    if (net.nodes[i].has_torque_feedback())
      filter[i] = static_cast<int>(names.size()), names.push_back(node_label(i) + "_low_passed_string_torque_Nm");
  for (int i = 0; i < nodes; ++i)
    if (net.nodes[i].has_dc_motor()) current[i] = static_cast<int>(names.size()), names.push_back(node_label(i) + "_current_A");
  for (int i = 0; i < nodes; ++i)
    if (net.nodes[i].has_induction_motor()) {
      flux[i] = static_cast<int>(names.size());
      for (const char* axis : {"_stator_flux_d_Wb", "_stator_flux_q_Wb", "_rotor_flux_d_Wb", "_rotor_flux_q_Wb"})
        names.push_back(node_label(i) + axis);
    }
  for (int i = 0; i < nodes; ++i)
    if (net.nodes[i].has_compliant_gear()) {
      motor[i] = static_cast<int>(names.size());
      names.push_back(node_label(i) + "_motor_speed_referred_rad_s");
      names.push_back(node_label(i) + "_gear_twist_rad");
    }
  const int first_wave = static_cast<int>(names.size());
  for (int k = 0; k < sections; ++k) {
    names.push_back("section" + std::to_string(k) + "_down_wave_integral_rad");
    names.push_back("section" + std::to_string(k) + "_up_wave_integral_rad");
  }
  auto down = [&](int k) { return first_wave + 2 * k; };  // p_k: leaves node k into section k
  auto up = [&](int k) { return first_wave + 2 * k + 1; };  // q_k: leaves node k + 1 into section k
  const int n = static_cast<int>(names.size());

  LinearDelaySystem& sys = out.system;
  sys.a0 = Eigen::MatrixXd::Zero(n, n);
  sys.derivative_only_states = 2 * sections;
  for (int k = 0; k < sections; ++k) sys.delays.push_back({net.sections[k].travel_time_s, {}, Eigen::MatrixXd::Zero(n, n)});

  // The waves arriving at node i: from the section above (p_{i-1}) and below (q_i), one travel time late.
  struct Arrival {
    int section, column;
    double impedance;
  };
  auto arrivals = [&](int i) {
    std::vector<Arrival> a;
    if (i > 0) a.push_back({i - 1, down(i - 1), net.sections[i - 1].impedance});
    if (i < sections) a.push_back({i, up(i), net.sections[i].impedance});
    return a;
  };
  auto impedance_sum = [&](int i) {
    double z = 0;
    for (const Arrival& a : arrivals(i)) z += a.impedance;
    return z;
  };
  // Every node's speed perturbation as a linear form: coefficients of the states (into A_0) and of the arriving waves'
  // derivatives (into the neutral term of the wave's section, one travel time late). An inertial node's speed is its
  // state, an imposed one's nothing; the massless nodes balance the arrivals against their damping (the ground's, the
  // friction slope and a dissipative top's beta) and, with Kelvin-Voigt dashpots kv across the sections, against their
  // neighbours' speeds, as the simulation's node system:
  //   (sum Z + damping + kv_above + kv_below) v_i - kv_above v_{i-1} - kv_below v_{i+1} = sum 2 Z w_in,
  // with the known speeds of inertial neighbours moved to the right. One linear system over the massless nodes
  // (diagonal without dashpots).
  struct SpeedForm {
    Eigen::RowVectorXd state, wave;  // wave: by the arriving wave's column
    // What it holds `late` ago (a wave-cancelling top's speed follows what its law read an actuator delay ago):
    // retarded coefficients of the states and neutral ones of the arriving waves, that much later still.
    double late = 0;
    Eigen::RowVectorXd late_state, late_wave;
  };
  const Eigen::RowVectorXd none = Eigen::RowVectorXd::Zero(n);
  std::vector<SpeedForm> speed_form(nodes, {none, none, 0.0, none, none});
  std::vector<int> unknown(nodes, -1);  // massless nodes of free speed, numbered
  int unknowns = 0;
  for (int i = 0; i < nodes; ++i) {
    if (speed[i] >= 0) speed_form[i].state(speed[i]) = 1;
    else if (net.nodes[i].drive != Drive::kPrescribedSpeed) unknown[i] = unknowns++;
  }
  auto section_of = [&](int column) { return (column - first_wave) / 2; };
  if (unknowns > 0) {
    Eigen::MatrixXd balance = Eigen::MatrixXd::Zero(unknowns, unknowns), rhs = Eigen::MatrixXd::Zero(unknowns, 2 * n);
    for (int i = 0; i < nodes; ++i) {
      const int u = unknown[i];
      if (u < 0) continue;
      const Node& node = net.nodes[i];
      balance(u, u) = impedance_sum(i) + NodeTorqueSlope(node, w0) +
                      (node.drive == Drive::kSpeedDashpot ? node.drive_damping : 0.0);
      for (const Arrival& a : arrivals(i)) {
        rhs(u, n + a.column) += 2 * a.impedance;
        const double kv = net.sections[a.section].dashpot;
        if (kv == 0) continue;
        const int neighbour = a.section == i ? i + 1 : i - 1;
        balance(u, u) += kv;
        if (unknown[neighbour] >= 0) balance(u, unknown[neighbour]) -= kv;
        else rhs.block(u, 0, 1, n) += kv * speed_form[neighbour].state;  // imposed: no perturbation
      }
      if (!(std::abs(balance(u, u)) > 1e-12 * impedance_sum(i)))
        throw std::invalid_argument("node '" + node.name + "' is massless and its torque slope cancels the string's "
                                    "impedance: the linearization is singular");
    }
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(balance);
    if (!(lu.rcond() > 1e-12))
      throw std::invalid_argument("the massless nodes' balance with the Kelvin-Voigt dashpots is singular");
    const Eigen::MatrixXd solved = lu.solve(rhs);
    for (int i = 0; i < nodes; ++i)
      if (unknown[i] >= 0) {
        speed_form[i].state = solved.block(unknown[i], 0, 1, n);
        speed_form[i].wave = solved.block(unknown[i], n, 1, n);
      }
  }
  // The delay term at tau, added (with zero matrices) if there is none yet: an actuator delay's.
  auto delay_term = [&](double tau) -> DelayTerm& {
    auto it = std::find_if(sys.delays.begin(), sys.delays.end(), [&](const DelayTerm& d) { return d.tau == tau; });
    if (it == sys.delays.end()) it = sys.delays.insert(sys.delays.end(), {tau, {}, Eigen::MatrixXd::Zero(n, n)});
    if (it->retarded.size() == 0) it->retarded = Eigen::MatrixXd::Zero(n, n);
    if (it->neutral.size() == 0) it->neutral = Eigen::MatrixXd::Zero(n, n);
    return *it;
  };
  // value * (state `column`, `lag` ago) and value * (the wave of `column` arriving `lag` ago) into row `row`.
  auto add_state = [&](int row, int column, double value, double lag) {
    if (lag == 0) sys.a0(row, column) += value;
    else delay_term(lag).retarded(row, column) += value;
  };
  auto add_wave = [&](int row, int column, double value, double lag) {
    const int k = section_of(column);
    if (lag == 0) sys.delays[k].neutral(row, column) += value;
    else delay_term(net.sections[k].travel_time_s + lag).neutral(row, column) += value;
  };
  // factor * (speed of node i, `lag` ago) into row `row`.
  auto add_speed = [&](int row, int i, double factor, double lag = 0) {
    const SpeedForm& form = speed_form[i];
    if (lag == 0) sys.a0.row(row) += factor * form.state;
    else delay_term(lag).retarded.row(row) += factor * form.state;
    for (int c = first_wave; c < n; ++c)
      if (form.wave(c) != 0) add_wave(row, c, factor * form.wave(c), lag);
    if (form.late == 0) return;
    for (int c = 0; c < n; ++c) {
      if (form.late_state(c) != 0) add_state(row, c, factor * form.late_state(c), lag + form.late);
      if (form.late_wave(c) != 0) add_wave(row, c, factor * form.late_wave(c), lag + form.late);
    }
  };
  // A wave-cancelling top turns at v = e + w(t - late) + k I(t - late): the speed its law asked for an actuator delay
  // ago (model::WaveCancellation: the arriving wave w plus d, whose perturbation is k I) and the error e, its state.
  if (net.top().law.wave_cancellation.active()) {
    const Node& top = net.top();
    SpeedForm& form = speed_form[0];
    form.late = top.law.actuator_delay_s;
    (form.late > 0 ? form.late_state : form.state)(integral[0]) += top.law.wave_cancellation.Corner(top.pi.ki);
    (form.late > 0 ? form.late_wave : form.wave)(up(0)) += 1;
  }

  for (int i = 0; i < nodes; ++i) {
    const Node& node = net.nodes[i];
    // Outgoing waves: speed minus the arriving wave of the same section.
    for (const Arrival& a : arrivals(i)) {
      const int row = a.column == down(a.section) ? up(a.section) : down(a.section);
      add_speed(row, i, 1.0);
      sys.delays[a.section].neutral(row, a.column) -= 1.0;
    }
    if (speed[i] < 0) continue;
    const int v = speed[i];
    if (node.law.wave_cancellation.active()) {
      // Its torque cancels g, the torque of the string and its dampers, as read: J e' = g(t) - g(t - late) -
      // kp (v - w - d)(t - late), g = sum 2 Z w_in - (sum Z + c) v (without a delay e' = -kp e / J); I' = -v, as read.
      const double late = node.law.actuator_delay_s, inertia = node.LumpedInertia(), kp = node.pi.kp;
      auto add_string_and_dampers = [&](double factor, double lag) {
        for (const Arrival& a : arrivals(i)) add_wave(v, a.column, factor * 2 * a.impedance, lag);
        add_speed(v, i, -factor * (impedance_sum(i) + NodeTorqueSlope(node, w0)), lag);
      };
      if (late > 0) add_string_and_dampers(1 / inertia, 0), add_string_and_dampers(-1 / inertia, late);
      add_speed(v, i, -kp / inertia, late);
      add_wave(v, up(0), kp / inertia, late);
      add_state(v, integral[i], kp / inertia * node.law.wave_cancellation.Corner(node.pi.ki), late);
      add_speed(integral[i], i, -1, late);
      continue;
    }
    // The speed the drive sees (referred to the node's side): the node's, or its motor's behind a compliant gear.
    const int vd = motor[i] >= 0 ? motor[i] : v;
    const double n_gear = node.gear.ratio;
    InductionJacobian induction;
    if (flux[i] >= 0) {
      if (i != 0)  // its steady supply comes from the top's set-point and torque
        throw std::invalid_argument("node '" + node.name + "': an induction motor is linearized at the top only");
      const double f0 = SteadySupplyHz(node, point.top_setpoint, w0, point.top_torque_Nm);
      induction = LinearizeInductionMotor(node.induction, f0, n_gear * w0);
    }
    // What a PI top's controller reads (its speed and the string torque) it reads an actuator delay late: those terms
    // are retarded by the delay, and the arriving waves in the string torque neutral at travel time + delay.
    const double late = node.drive == Drive::kPiSpeedController ? node.law.actuator_delay_s : 0.0;
    auto add_read_speed = [&](int row, double value) {
      if (late == 0) sys.a0(row, vd) += value;
      else delay_term(late).retarded(row, vd) += value;
    };
    // factor * (the torque the node feeds into the string, as the controller reads it) into row `row`: minus the
    // string's force on it, sum Z (v - 2 w_in) and the dashpots' kv (v - v_neighbour) (no delay with dashpots).
    auto add_string_torque = [&](int row, double factor) {
      for (const Arrival& a : arrivals(i)) {
        const double wave = -factor * 2 * a.impedance;
        if (late == 0) {
          sys.a0(row, v) += factor * a.impedance;
          sys.delays[a.section].neutral(row, a.column) += wave;
        } else {
          delay_term(late).retarded(row, v) += factor * a.impedance;
          delay_term(net.sections[a.section].travel_time_s + late).neutral(row, a.column) += wave;
        }
        const double kv = net.sections[a.section].dashpot;
        if (kv == 0) continue;
        sys.a0(row, v) += factor * kv;
        add_speed(row, a.section == i ? i + 1 : i - 1, -factor * kv);
      }
    };
    // factor * (the PI's speed command less the set-point) into row `row`: -gain (T - T_lp) with torque feedback.
    auto add_command = [&](int row, double factor) {
      if (filter[i] < 0) return;
      const double gain = node.law.torque_feedback.gain;
      add_string_torque(row, -factor * gain);
      sys.a0(row, filter[i]) += factor * gain;
    };
    // factor * (the drive's torque on the node's side) into row `row`.
    auto add_drive_torque = [&](int row, double factor) {
      switch (node.drive) {
        case Drive::kSpeedDashpot: sys.a0(row, vd) -= factor * node.drive_damping; break;
        case Drive::kPiSpeedController:
          add_read_speed(row, -factor * node.pi.kp);
          add_command(row, factor * node.pi.kp);
          if (integral[i] >= 0) sys.a0(row, integral[i]) += factor * node.pi.ki;
          break;
        case Drive::kDcMotorVoltage:
        case Drive::kDcMotorSpeed: sys.a0(row, current[i]) += factor * ReferredMotorConstant(node); break;
        case Drive::kInductionMotor:
        case Drive::kInductionMotorSpeed:
          for (int j = 0; j < 4; ++j) sys.a0(row, flux[i] + j) += factor * n_gear * induction.torque(j);
          break;
        default: break;
      }
    };

    const double inertia = node.LumpedInertia();
    for (const Arrival& a : arrivals(i)) {
      sys.delays[a.section].neutral(v, a.column) += 2 * a.impedance / inertia;
      const double kv = net.sections[a.section].dashpot;  // Kelvin-Voigt: kv (v_neighbour - v)
      if (kv == 0) continue;
      add_speed(v, a.section == i ? i + 1 : i - 1, kv / inertia);
      sys.a0(v, v) -= kv / inertia;
    }
    sys.a0(v, v) -= (impedance_sum(i) + NodeTorqueSlope(node, w0)) / inertia;
    if (motor[i] >= 0) {  // the gear passes k twist + c (w_m - w) to the node
      const model::Gear& g = node.gear;
      const int vm = motor[i], twist = motor[i] + 1;
      const double jm = g.ReferredMotorInertia();
      sys.a0(v, twist) += g.stiffness / inertia;
      sys.a0(v, vm) += g.damping / inertia;
      sys.a0(v, v) -= g.damping / inertia;
      add_drive_torque(vm, 1 / jm);
      sys.a0(vm, twist) -= g.stiffness / jm;
      sys.a0(vm, vm) -= g.damping / jm;
      sys.a0(vm, v) += g.damping / jm;
      sys.a0(twist, vm) = 1;
      sys.a0(twist, v) = -1;
    } else {
      add_drive_torque(v, 1 / inertia);
    }
    if (integral[i] >= 0) {  // d/dt integral of (command - drive speed)
      if (node.drive == Drive::kPiSpeedController) add_read_speed(integral[i], -1);
      else sys.a0(integral[i], vd) = -1;
      add_command(integral[i], 1.0);
    }
    if (filter[i] >= 0) {  // T_lp' = (T - T_lp) / time constant
      const double rate = 1 / node.law.torque_feedback.time_constant_s;
      add_string_torque(filter[i], rate);
      sys.a0(filter[i], filter[i]) -= rate;
    }
    if (current[i] >= 0) {  // L I' = V - R I - n k w_d, V = the set-point or kp (set - w_d) + ki integral
      const waves::DcMotor& m = node.motor;
      const int c = current[i];
      sys.a0(c, c) = -m.armature_resistance / m.armature_inductance;
      sys.a0(c, vd) -= ReferredMotorConstant(node) / m.armature_inductance;
      if (node.drive == Drive::kDcMotorSpeed) {
        sys.a0(c, vd) -= node.pi.kp / m.armature_inductance;
        if (integral[i] >= 0) sys.a0(c, integral[i]) += node.pi.ki / m.armature_inductance;
      }
    }
    if (flux[i] >= 0) {
      // psi' = F(psi, f, n w_d). Open loop f is the set-point; slip-frequency control sets
      // f = (p n w_d + u / (n G)) / 2 pi for the PI's demand u = kp (set - w_d) + ki integral.
      const int f = flux[i];
      sys.a0.block(f, f, 4, 4) += induction.flux;
      sys.a0.block(f, vd, 4, 1) += n_gear * induction.shaft_speed;
      if (node.drive == Drive::kInductionMotorSpeed) {
        const double two_pi = 6.283185307179586, gain = n_gear * node.induction.SlipTorqueGain();
        const double supply_per_speed = (node.induction.pole_pairs * n_gear - node.pi.kp / gain) / two_pi;
        sys.a0.block(f, vd, 4, 1) += supply_per_speed * induction.supply_hz;
        if (integral[i] >= 0) sys.a0.block(f, integral[i], 4, 1) += node.pi.ki / gain / two_pi * induction.supply_hz;
      }
    }
  }
  const Node& bit = net.bit();
  if (bit.lateral)
    AddBhaWhirl(out, speed[nodes - 1], bit.LumpedInertia(), bit.LumpedInertia() - bit.lateral->AddedInertia(),
                *bit.lateral, w0);
  return out;
}

}  // namespace drillwave::analysis
