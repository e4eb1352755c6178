#include "drillwave/analysis/network_linearization.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace drillwave::analysis {
namespace {

using waves::Drive;
using waves::Network;
using waves::Node;

double Clamp(double u, double limit) { return limit > 0 ? std::clamp(u, -limit, limit) : u; }

// Torque the nodes take from the string in steady rotation at w: ground damping everywhere plus friction.
double Load(const Network& net, double w) {
  double load = 0;
  for (const Node& n : net.nodes) load += n.ground_damping * w + (n.friction ? n.friction->SlipTorque(w) : 0.0);
  return load;
}

double NodeTorque(const Node& n, double w) {
  return n.ground_damping * w + (n.friction ? n.friction->SlipTorque(w) : 0.0);
}

double NodeTorqueSlope(const Node& n, double w) {
  return n.ground_damping + (n.friction ? n.friction->SlipTorqueDerivative(w) : 0.0);
}

// Tops whose integral action (or imposition) holds the speed at the set-point in steady state.
bool HoldsSpeed(const Node& top) {
  return top.drive == Drive::kPrescribedSpeed || (top.has_speed_integral() && top.ki > 0);
}

// The torque a balancing top supplies when it turns at w, and whether its limit (torque or voltage) is reached there.
double Supply(const Node& top, double set, double w, bool& saturated) {
  const waves::DcMotor& m = top.motor;
  double u = 0;
  switch (top.drive) {
    case Drive::kSpeedDashpot: return top.drive_damping * (set - w);
    case Drive::kTorque: return set;
    case Drive::kPiSpeedController:
      u = top.kp * (set - w);
      saturated = top.torque_limit > 0 && std::abs(u) >= top.torque_limit;
      return Clamp(u, top.torque_limit);
    case Drive::kDcMotorVoltage:
    case Drive::kDcMotorSpeed:
      u = top.drive == Drive::kDcMotorVoltage ? set : top.kp * (set - w);
      saturated = m.voltage_limit > 0 && std::abs(u) >= m.voltage_limit;
      return m.motor_constant * (Clamp(u, m.voltage_limit) - m.motor_constant * w) / m.armature_resistance;
    default: return 0;
  }
}

// Where a balancing top's supply falls to zero (no steady forward rotation beyond it), or a bound for a torque top.
double LargestSpeed(const Network& net, double set) {
  const Node& top = net.top();
  const waves::DcMotor& m = top.motor;
  switch (top.drive) {
    case Drive::kSpeedDashpot:
    case Drive::kPiSpeedController: return set;
    case Drive::kDcMotorVoltage: return Clamp(set, m.voltage_limit) / m.motor_constant;
    case Drive::kDcMotorSpeed: return top.kp * set / (top.kp + m.motor_constant);
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

// The drives this linearization has equations for: an induction motor's fluxes and a gear's motor side (its
// inertia, its compliance, the referred motor constant) are not among its states, so such a top is refused rather
// than linearized as if it were a plain one.
void RequireLinearizedDrives(const Network& net) {
  for (const Node& node : net.nodes) {
    if (node.drive == Drive::kInductionMotor || node.drive == Drive::kInductionMotorSpeed)
      throw std::invalid_argument("node '" + node.name + "': an induction motor top has no linearization yet");
    if (node.gear.compliant() || node.gear.ratio != 1 || node.gear.motor_inertia != 0)
      throw std::invalid_argument("node '" + node.name + "': a gear and motor inertia have no linearization yet");
  }
}

}  // namespace

std::vector<NetworkOperatingPoint> NetworkSteadyStates(const Network& net) {
  net.Validate();
  RequireLinearizedDrives(net);
  const Node& top = net.top();
  const double set = top.setpoint.knots().back().second;
  std::vector<NetworkOperatingPoint> points;
  if (HoldsSpeed(top)) {
    if (!(set > 0)) return points;
    const NetworkOperatingPoint p = PointAt(net, set, set);
    const waves::DcMotor& m = top.motor;
    if (top.drive == Drive::kPiSpeedController && top.torque_limit > 0 && p.top_torque_Nm >= top.torque_limit)
      return points;  // the controller saturates: the set-point cannot be held
    if (top.has_dc_motor() && m.voltage_limit > 0 &&
        m.armature_resistance * p.top_torque_Nm / m.motor_constant + m.motor_constant * set >= m.voltage_limit)
      return points;
    points.push_back(p);
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
  RequireLinearizedDrives(net);
  const int sections = static_cast<int>(net.sections.size()), nodes = sections + 1;
  const double w0 = point.speed_rad_s;
  NetworkLinearization out;
  auto& names = out.state_names;
  auto node_label = [&](int i) {
    return i == 0 ? std::string("top") : i == nodes - 1 ? std::string("bit") : "node" + std::to_string(i);
  };
  // Node states: speeds of inertial nodes, then integrals of speed controllers with an integral gain, then currents.
  std::vector<int> speed(nodes, -1), integral(nodes, -1), current(nodes, -1);
  for (int i = 0; i < nodes; ++i)
    if (!net.nodes[i].massless()) speed[i] = static_cast<int>(names.size()), names.push_back(node_label(i) + "_speed_rad_s");
  for (int i = 0; i < nodes; ++i)
    if (net.nodes[i].has_speed_integral() && net.nodes[i].ki > 0)
      integral[i] = static_cast<int>(names.size()), names.push_back(node_label(i) + "_speed_error_integral_rad");
  for (int i = 0; i < nodes; ++i)
    if (net.nodes[i].has_dc_motor()) current[i] = static_cast<int>(names.size()), names.push_back(node_label(i) + "_current_A");
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
  // Damping of node i in the linearization: ground, friction slope, and a top's proportional torque on the speed.
  auto damping = [&](int i) {
    const Node& node = net.nodes[i];
    double c = NodeTorqueSlope(node, w0);
    if (node.drive == Drive::kSpeedDashpot) c += node.drive_damping;
    if (node.drive == Drive::kPiSpeedController) c += node.kp;
    return c;
  };
  auto impedance_sum = [&](int i) {
    double z = 0;
    for (const Arrival& a : arrivals(i)) z += a.impedance;
    return z;
  };
  // factor * (speed of node i) into row `row`: a state, nothing (imposed), or the massless balance of the arrivals.
  auto add_speed = [&](int row, int i, double factor) {
    const Node& node = net.nodes[i];
    if (speed[i] >= 0) {
      sys.a0(row, speed[i]) += factor;
    } else if (node.drive != Drive::kPrescribedSpeed) {
      const double denominator = impedance_sum(i) + damping(i);
      if (!(std::abs(denominator) > 1e-12 * impedance_sum(i)))
        throw std::invalid_argument("node '" + node.name + "' is massless and its torque slope cancels the string's "
                                    "impedance: the linearization is singular");
      for (const Arrival& a : arrivals(i)) sys.delays[a.section].neutral(row, a.column) += factor * 2 * a.impedance / denominator;
    }
  };

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
    const double inertia = node.inertia;
    for (const Arrival& a : arrivals(i)) sys.delays[a.section].neutral(v, a.column) += 2 * a.impedance / inertia;
    sys.a0(v, v) -= (impedance_sum(i) + damping(i)) / inertia;
    if (integral[i] >= 0) sys.a0(integral[i], v) = -1;  // d/dt integral of (set-point - speed)
    if (node.drive == Drive::kPiSpeedController && integral[i] >= 0) sys.a0(v, integral[i]) += node.ki / inertia;
    if (current[i] >= 0) {
      const waves::DcMotor& m = node.motor;
      const int c = current[i];
      sys.a0(v, c) += m.motor_constant / inertia;
      sys.a0(c, c) = -m.armature_resistance / m.armature_inductance;
      sys.a0(c, v) = -m.motor_constant / m.armature_inductance;
      if (node.drive == Drive::kDcMotorSpeed) {
        sys.a0(c, v) -= node.kp / m.armature_inductance;
        if (integral[i] >= 0) sys.a0(c, integral[i]) += node.ki / m.armature_inductance;
      }
    }
  }
  return out;
}

}  // namespace drillwave::analysis
