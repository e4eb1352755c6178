#include "drillwave/analysis/torsional_linearization.hpp"

#include <cmath>
#include <stdexcept>

namespace drillwave::analysis {
namespace {

// The top as an equivalent dashpot: beta' and Omega'.
void EffectiveTop(const waves::Node& top, double omega, double& beta, double& omega_eff) {
  beta = top.drive_damping + top.ground_damping;
  omega_eff = top.drive_damping * omega / beta;
}

// Torque the bit needs to slide at w (friction plus ground damping).
double BitTorque(const waves::Node& bit, double w) {
  return (bit.friction ? bit.friction->SlipTorque(w) : 0.0) + bit.ground_damping * w;
}

double BitSlope(const waves::Node& bit, double w) {
  return (bit.friction ? bit.friction->SlipTorqueDerivative(w) : 0.0) + bit.ground_damping;
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
}

std::vector<TorsionalOperatingPoint> SteadySlidingStates(const waves::Network& net, double top_speed_rad_s) {
  CheckLinearizable(net);
  double beta, omega_eff;
  EffectiveTop(net.top(), top_speed_rad_s, beta, omega_eff);
  const waves::Node& bit = net.bit();
  // Balance: beta' (Omega' - w) = T(w) + c_bit w. For w > 0 the bit torque is >= 0, so w <= Omega'.
  auto f = [&](double w) { return beta * (omega_eff - w) - BitTorque(bit, w); };
  std::vector<TorsionalOperatingPoint> points;
  if (!(omega_eff > 0)) return points;
  const int samples = 20000;
  double w_prev = omega_eff * 1e-9, f_prev = f(w_prev);
  for (int i = 1; i <= samples; ++i) {
    const double w = omega_eff * i / samples;
    const double fw = f(w);
    if (f_prev == 0 || (f_prev > 0) != (fw > 0) || fw == 0) {
      double lo = w_prev, hi = w, flo = f_prev;
      for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
        const double mid = 0.5 * (lo + hi), fm = f(mid);
        if ((fm > 0) == (flo > 0)) lo = mid, flo = fm; else hi = mid;
      }
      const double w0 = 0.5 * (lo + hi);
      if (points.empty() || w0 - points.back().bit_speed_rad_s > 1e-9 * omega_eff)
        points.push_back({top_speed_rad_s, w0, BitTorque(bit, w0), BitSlope(bit, w0)});
    }
    w_prev = w;
    f_prev = fw;
  }
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
