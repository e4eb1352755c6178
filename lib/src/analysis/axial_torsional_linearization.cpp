#include "drillwave/analysis/axial_torsional_linearization.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <tuple>

#include "drillwave/analysis/bha_whirl_linearization.hpp"
#include "drillwave/analysis/induction_linearization.hpp"
#include "drillwave/core/constants.hpp"

namespace drillwave::analysis {
namespace {

// The channel as a wave network (massless nodes between the pieces): its linearization is the network's. The top
// drive's PI, motor and gear are a network top; the hoist under a constant hook force has no drive term.
waves::Network ChannelNetwork(const WaveChannel& ch, const AxialTorsionalString* top_drive, double speed) {
  const bool torsion = top_drive != nullptr;
  const std::size_t pieces = ch.impedance.size();
  if (pieces == 0 || ch.travel_time_s.size() != pieces || ch.node_damping.size() != pieces + 1 ||
      !(ch.dashpot.empty() || ch.dashpot.size() == pieces))
    throw std::invalid_argument("a channel needs impedances and travel times per piece (and dashpots, if any) and a "
                                "damping per node");
  if (!(ch.top_inertia > 0) || !(ch.bit_inertia > 0))
    throw std::invalid_argument("the coupled model's top and bit need inertias (masses) > 0");
  waves::Network net;
  for (std::size_t k = 0; k < pieces; ++k) {
    waves::Section s;
    s.travel_time_s = ch.travel_time_s[k];
    s.impedance = ch.impedance[k];
    if (!ch.dashpot.empty()) s.dashpot = ch.dashpot[k];
    net.sections.push_back(s);
  }
  net.nodes.resize(pieces + 1);
  for (std::size_t j = 0; j <= pieces; ++j) net.nodes[j].ground_damping = ch.node_damping[j];
  waves::Node& top = net.nodes.front();
  top.name = torsion ? "top" : "hoist";
  top.inertia = ch.top_inertia;
  if (torsion) {
    top.drive = top_drive->top_drive;
    top.pi = top_drive->pi;
    top.motor = top_drive->dc_motor;
    top.induction = top_drive->induction_motor;
    top.gear = top_drive->gear;
    top.law = top_drive->top_law;
    top.setpoint = model::Schedule(speed);
  }
  net.nodes.back().name = "bit";
  net.nodes.back().inertia = ch.bit_inertia;
  return net;
}

// The network's damping terms are linear: only the speed matters, and for an induction motor the top's torque.
NetworkLinearization LinearizeChannel(const WaveChannel& ch, const AxialTorsionalString* top_drive, double speed,
                                      double top_torque) {
  NetworkOperatingPoint point;
  point.top_setpoint = point.speed_rad_s = speed;
  point.top_torque_Nm = top_torque;
  return LinearizeNetwork(ChannelNetwork(ch, top_drive, speed), point);
}

int IndexOf(const std::vector<std::string>& names, const std::string& name) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  throw std::logic_error("no state named " + name);
}

// Axial states in metres: the network names them in radians.
std::string AxialName(std::string name) {
  for (const char* unit : {"_rad_s", "_rad"}) {
    const auto at = name.rfind(unit);
    if (at != std::string::npos && at + std::string(unit).size() == name.size())
      return name.substr(0, at) + (std::string(unit) == "_rad_s" ? "_m_s" : "_m");
  }
  return name;
}

}  // namespace

NetworkLinearization LinearizeAxialTorsional(const AxialTorsionalString& string, const SteadyDrilling& point) {
  const double w0 = point.speed_rad_s, v0 = point.rop_m_s;
  if (!(w0 > 0)) throw std::invalid_argument("steady drilling needs a bit speed > 0");
  NetworkLinearization torsion = LinearizeChannel(string.torsion, &string, w0, point.top_torque_Nm);
  const double bit_inertia = string.torsion.bit_inertia;
  const int tb = IndexOf(torsion.state_names, "bit_speed_rad_s");
  // Friction of the wear flats: only a Stribeck law's slope moves it.
  torsion.system.a0(tb, tb) -= point.friction_slope_Nms_per_rad / bit_inertia;
  if (!string.axial_coupling) {  // the depth of cut is held: the bit torque moves with friction alone
    if (string.unbalance) AddBhaWhirl(torsion, tb, bit_inertia, bit_inertia, *string.unbalance, w0);
    return torsion;
  }
  if (!(v0 > 0)) throw std::invalid_argument("steady drilling needs a rate of penetration > 0");

  // A rig: the block rides with the hoist (rigid hook), its damper on the hoist's speed.
  WaveChannel axial_channel = string.axial;
  if (string.rig) {
    axial_channel.top_inertia += string.rig->block_mass;
    axial_channel.node_damping.front() += string.rig->block_damping;
  }
  const NetworkLinearization axial = LinearizeChannel(axial_channel, nullptr, v0, 0);
  const LinearDelaySystem& ts = torsion.system;
  const LinearDelaySystem& as = axial.system;
  const int t_waves = ts.derivative_only_states, a_waves = as.derivative_only_states;
  const int t_nodes = ts.dimension() - t_waves, a_nodes = as.dimension() - a_waves;
  const model::Drawworks* drawworks = string.rig && string.rig->drawworks ? &*string.rig->drawworks : nullptr;
  const int rig = t_nodes + a_nodes, rig_states = string.rig ? (drawworks ? 8 : 3) : 0;
  // Node states of both channels, the rig's, then the derivative-only tail: bit angle, bit position, torsional and
  // axial waves.
  const int phi = rig + rig_states, u = phi + 1, n = u + 1 + t_waves + a_waves;
  auto map_t = [&](int i) { return i < t_nodes ? i : u + 1 + (i - t_nodes); };
  auto map_a = [&](int i) { return i < a_nodes ? t_nodes + i : u + 1 + t_waves + (i - a_nodes); };

  NetworkLinearization out;
  out.state_names.resize(n);
  for (int i = 0; i < ts.dimension(); ++i) out.state_names[map_t(i)] = "torsion_" + torsion.state_names[i];
  for (int i = 0; i < as.dimension(); ++i) out.state_names[map_a(i)] = "axial_" + AxialName(axial.state_names[i]);
  if (string.rig) {
    out.state_names[rig] = "rig_derrick_displacement_m";
    out.state_names[rig + 1] = "rig_derrick_speed_m_s";
    out.state_names[rig + 2] = "rig_cable_stretch_m";
    if (drawworks) {
      out.state_names[rig + 3] = "drawworks_drum_speed_rad_s";
      for (int j = 0; j < 4; ++j) out.state_names[rig + 4 + j] = "drawworks_flux_" + std::to_string(j) + "_Wb";
    }
  }
  out.state_names[phi] = "bit_angle_rad";
  out.state_names[u] = "bit_position_m";

  LinearDelaySystem& sys = out.system;
  sys.a0 = Eigen::MatrixXd::Zero(n, n);
  sys.derivative_only_states = 2 + t_waves + a_waves;
  auto scatter = [n](const Eigen::MatrixXd& from, auto map) {
    Eigen::MatrixXd to = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < from.rows(); ++i)
      for (int j = 0; j < from.cols(); ++j) to(map(i), map(j)) = from(i, j);
    return to;
  };
  sys.a0 = scatter(ts.a0, map_t) + scatter(as.a0, map_a);
  // One term per distinct travel time (the pieces of a channel share theirs): the characteristic matrix then costs a
  // few matrix sums instead of one per piece. The top drive's actuator delay brings retarded terms too.
  auto add_delay = [&](const DelayTerm& term, auto map) {
    const Eigen::MatrixXd b = scatter(term.neutral, map);
    auto it = std::find_if(sys.delays.begin(), sys.delays.end(), [&](const DelayTerm& d) { return d.tau == term.tau; });
    if (it == sys.delays.end()) {
      sys.delays.push_back({term.tau, {}, b});
      it = sys.delays.end() - 1;
    } else {
      it->neutral += b;
    }
    if (term.retarded.size() == 0) return;
    if (it->retarded.size() == 0) it->retarded = Eigen::MatrixXd::Zero(n, n);
    it->retarded += scatter(term.retarded, map);
  };
  for (const DelayTerm& d : ts.delays) add_delay(d, map_t);
  for (const DelayTerm& d : as.delays) add_delay(d, map_a);
  if (string.rig) {
    const model::HoistRig& r = *string.rig;
    const int y1 = rig, y1d = rig + 1, stretch = rig + 2, hoist = map_a(IndexOf(axial.state_names, "top_speed_rad_s"));
    sys.a0(y1, y1d) = 1;
    sys.a0(y1d, y1d) = -r.derrick_damping / r.derrick_mass;
    sys.a0(y1d, y1) = -r.ground_stiffness / r.derrick_mass;
    sys.a0(y1d, stretch) = r.cable_stiffness / r.derrick_mass;
    sys.a0(stretch, hoist) = 1;
    sys.a0(stretch, y1d) = -1;
    sys.a0(hoist, stretch) -= r.cable_stiffness / axial_channel.top_inertia;
    if (drawworks) {  // the drum pays out r w_d under the line's pull and its motor's torque
      const model::Drawworks& d = *drawworks;
      const int drum = rig + 3, flux = rig + 4;
      const InductionJacobian motor =
          LinearizeInductionMotor(d.motor, string.drawworks_supply_hz, d.gear_ratio * v0 / d.line_radius);
      sys.a0(stretch, drum) = -d.line_radius;
      sys.a0(drum, hoist) = d.line_radius * r.block_damping / d.inertia;
      sys.a0(drum, stretch) = d.line_radius * r.cable_stiffness / d.inertia;
      for (int j = 0; j < 4; ++j) {
        sys.a0(drum, flux + j) = d.gear_ratio * motor.torque(j) / d.inertia;
        sys.a0(flux + j, drum) = d.gear_ratio * motor.shaft_speed(j);
        for (int k = 0; k < 4; ++k) sys.a0(flux + j, flux + k) = motor.flux(j, k);
      }
    }
  }

  // The cut: delta d = n (u - u(t - t_n0)) - (n V0 / Omega0) (phi - phi(t - t_n0)), t_n0 = 2 pi / (n Omega0).
  const double tn0 = 2 * kPi / (string.blades * w0);
  const int wb = map_t(tb), vb = map_a(IndexOf(axial.state_names, "bit_speed_rad_s"));
  const double mass = string.axial.bit_inertia;
  DelayTerm cut{tn0, Eigen::MatrixXd::Zero(n, n), {}};
  sys.a0(phi, wb) = 1;
  sys.a0(u, vb) = 1;
  const double per_u = string.blades, per_phi = -string.blades * v0 / w0;  // d(delta d) / du, / dphi
  for (const auto& [row, force_per_depth, inertia] :
       {std::tuple{wb, string.cut_torque_per_depth, bit_inertia}, std::tuple{vb, string.cut_weight_per_depth, mass}}) {
    const double k = force_per_depth / inertia;  // the cutting force opposes the bit's motion
    sys.a0(row, u) -= k * per_u, cut.retarded(row, u) += k * per_u;
    sys.a0(row, phi) -= k * per_phi, cut.retarded(row, phi) += k * per_phi;
  }
  sys.delays.push_back(std::move(cut));
  if (string.unbalance) AddBhaWhirl(out, wb, bit_inertia, bit_inertia, *string.unbalance, w0);
  return out;
}

}  // namespace drillwave::analysis
