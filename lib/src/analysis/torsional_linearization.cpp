#include "drillwave/analysis/torsional_linearization.hpp"

#include <cmath>
#include <stdexcept>

#include "drillwave/analysis/network_linearization.hpp"

namespace drillwave::analysis {
namespace {

// The top as an equivalent dashpot: beta' and Omega'.
void EffectiveTop(const waves::Node& top, double omega, double& beta, double& omega_eff) {
  beta = top.drive_damping + top.ground_damping;
  omega_eff = top.drive_damping * omega / beta;
}

}  // namespace

void CheckLinearizable(const waves::Network& net) {
  net.Validate();
  if (net.sections.size() != 1)
    throw std::invalid_argument("the linearization covers one uniform section; this string has " +
                                std::to_string(net.sections.size()));
  const waves::Node& top = net.top();
  if (top.drive != waves::Drive::kSpeedDashpot || !top.massless())
    throw std::invalid_argument("the linearization covers a massless dissipative top (type \"dissipative\")");
  if (!(top.drive_damping > 0)) throw std::invalid_argument("the top's beta must be > 0");
  if (net.bit().massless()) throw std::invalid_argument("the linearization needs a bit inertia > 0");
  if (net.HasKelvinVoigt()) throw std::invalid_argument("the scalar form has no Kelvin-Voigt dashpot");
  if (net.bit().lateral) throw std::invalid_argument("the scalar form has no lateral BHA");
}

std::vector<TorsionalOperatingPoint> SteadySlidingStates(const waves::Network& net, double top_speed_rad_s) {
  CheckLinearizable(net);
  waves::Network at_speed = net;
  at_speed.nodes.front().setpoint = model::Schedule(top_speed_rad_s);
  std::vector<TorsionalOperatingPoint> points;
  for (const NetworkOperatingPoint& p : NetworkSteadyStates(at_speed))
    points.push_back({top_speed_rad_s, p.speed_rad_s, p.bit_torque_Nm, p.bit_torque_slope_Nms_per_rad});
  return points;
}

LinearDelaySystem LinearizeTorsionalString(const waves::Network& net, const TorsionalOperatingPoint& point) {
  CheckLinearizable(net);
  double beta, omega_eff;
  EffectiveTop(net.top(), point.top_speed_rad_s, beta, omega_eff);
  const double z = net.sections[0].impedance, tau = net.sections[0].travel_time_s;
  const double inertia = net.bit().inertia;
  const double u = (beta - z) / (beta + z), psi = z / inertia, c = point.torque_slope_Nms_per_rad / inertia;
  LinearDelaySystem sys;
  sys.a0 = Eigen::MatrixXd::Constant(1, 1, -(psi + c));
  sys.delays.push_back({2 * tau, Eigen::MatrixXd::Constant(1, 1, -u * (psi - c)), Eigen::MatrixXd::Constant(1, 1, u)});
  return sys;
}

}  // namespace drillwave::analysis
