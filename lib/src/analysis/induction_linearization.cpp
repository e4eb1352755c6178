#include "drillwave/analysis/induction_linearization.hpp"

#include <algorithm>
#include <cmath>

#include "drillwave/core/constants.hpp"

namespace drillwave::analysis {

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
  const double hw = 1e-4 * std::max(std::abs(wm0), 2 * kPi * std::abs(f0) / m.pole_pairs + 1.0);
  jac.shaft_speed = column(m.FluxRates(psi0, f0, wm0 + hw), m.FluxRates(psi0, f0, wm0 - hw), hw);
  double hf = 1e-4 * std::max(std::abs(f0), 1.0);
  if (m.voltage_limit > 0) {
    const double corner = m.voltage_limit / m.volts_per_hertz, distance = std::abs(std::abs(f0) - corner);
    if (distance > 0) hf = std::min(hf, 0.5 * distance);
  }
  jac.supply_hz = column(m.FluxRates(psi0, f0 + hf, wm0), m.FluxRates(psi0, f0 - hf, wm0), hf);
  return jac;
}

}  // namespace drillwave::analysis
