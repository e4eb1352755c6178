#include "drillwave/model/induction_motor.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

namespace drillwave::model {
namespace {

using Complex = std::complex<double>;
constexpr double kTwoPi = 6.283185307179586;

struct Currents {
  Complex stator, rotor;
};

// i = L^-1 psi for the 2 x 2 inductance matrix [L_s L_m; L_m L_r].
Currents CurrentsOf(const InductionMotor& m, Complex psi_s, Complex psi_r) {
  const double ls = m.StatorInductance(), lr = m.RotorInductance(), lm = m.magnetizing_inductance;
  const double det = ls * lr - lm * lm;
  return {(lr * psi_s - lm * psi_r) / det, (ls * psi_r - lm * psi_s) / det};
}

}  // namespace

std::string InductionMotor::Problem() const {
  if (pole_pairs < 1) return "pole pairs must be >= 1";
  for (double v : {stator_resistance, rotor_resistance, stator_leakage_inductance, rotor_leakage_inductance,
                   magnetizing_inductance, volts_per_hertz})
    if (!(v > 0) || !std::isfinite(v)) return "resistances, inductances and volts per hertz must be > 0 and finite";
  if (!(voltage_limit >= 0) || !std::isfinite(voltage_limit)) return "the voltage limit must be >= 0 and finite";
  return "";
}

double InductionMotor::LineVoltage(double supply_hz) const {
  const double v = volts_per_hertz * supply_hz;
  return voltage_limit > 0 ? std::clamp(v, -voltage_limit, voltage_limit) : v;
}

InductionMotor::Fluxes InductionMotor::FluxRates(const Fluxes& psi, double supply_hz, double shaft_speed) const {
  const Complex psi_s(psi[0], psi[1]), psi_r(psi[2], psi[3]);
  const Currents i = CurrentsOf(*this, psi_s, psi_r);
  const double w_e = kTwoPi * supply_hz, slip_frequency = w_e - pole_pairs * shaft_speed;
  // Phase rms V_LL / sqrt(3) as a space vector of length sqrt(2) V_ph.
  const double v = std::sqrt(2.0 / 3.0) * LineVoltage(supply_hz);
  const Complex j(0, 1);
  const Complex ds = v - stator_resistance * i.stator - j * w_e * psi_s;
  const Complex dr = -rotor_resistance * i.rotor - j * slip_frequency * psi_r;
  return {ds.real(), ds.imag(), dr.real(), dr.imag()};
}

double InductionMotor::Torque(const Fluxes& psi) const {
  const Currents i = CurrentsOf(*this, {psi[0], psi[1]}, {psi[2], psi[3]});
  const double mu = 1.5 * pole_pairs * magnetizing_inductance / RotorInductance();
  return mu * (psi[2] * i.stator.imag() - psi[3] * i.stator.real());
}

double InductionMotor::StatorCurrentRms(const Fluxes& psi) const {
  return std::abs(CurrentsOf(*this, {psi[0], psi[1]}, {psi[2], psi[3]}).stator) / std::sqrt(2.0);
}

// psi_r' = 0 gives psi_r = a psi_s; psi_s' = 0 then gives psi_s from the voltage.
InductionMotor::Fluxes InductionMotor::SteadyFluxes(double supply_hz, double shaft_speed) const {
  const double ls = StatorInductance(), lr = RotorInductance(), lm = magnetizing_inductance;
  const double det = ls * lr - lm * lm;
  const double w_e = kTwoPi * supply_hz, slip_frequency = w_e - pole_pairs * shaft_speed;
  const Complex j(0, 1);
  const Complex a = (rotor_resistance * lm / det) / (rotor_resistance * ls / det + j * slip_frequency);
  const Complex psi_s =
      std::sqrt(2.0 / 3.0) * LineVoltage(supply_hz) / (stator_resistance * (lr - lm * a) / det + j * w_e);
  const Complex psi_r = a * psi_s;
  return {psi_s.real(), psi_s.imag(), psi_r.real(), psi_r.imag()};
}

double InductionMotor::SlipTorqueGain() const {
  return pole_pairs * volts_per_hertz * volts_per_hertz / (kTwoPi * kTwoPi * rotor_resistance);
}

double InductionMotor::SupplyForTorque(double torque_demand, double shaft_speed) const {
  const double slip = std::clamp(torque_demand / SlipTorqueGain(), -PullOutSlipFrequency(), PullOutSlipFrequency());
  return (pole_pairs * shaft_speed + slip) / kTwoPi;
}

double InductionMotor::TorqueDemandFor(double supply_hz, double shaft_speed) const {
  return (kTwoPi * supply_hz - pole_pairs * shaft_speed) * SlipTorqueGain();
}

double InductionMotor::SteadySupplyFrequency(double torque, double shaft_speed) const {
  const double synchronous = pole_pairs * shaft_speed;  // electrical rad/s
  auto excess = [&](double slip_frequency) {
    const double f = (synchronous + slip_frequency) / kTwoPi;
    return Torque(SteadyFluxes(f, shaft_speed)) - torque;
  };
  const bool motoring = torque >= 0;
  const double pull_out = (motoring ? 1 : -1) * PullOutSlipFrequency();
  double lo = 0, hi = pull_out;  // excess(lo) <= 0 <= excess(hi) when motoring, mirrored when generating
  if (std::abs(excess(hi) + torque) < std::abs(torque))
    throw std::domain_error("the motor's torque at " + std::to_string(shaft_speed) + " rad/s stays below " +
                            std::to_string(std::abs(torque)) + " N m up to its pull-out slip");
  for (int k = 0; k < 200 && std::abs(hi - lo) > 1e-15 * std::abs(pull_out); ++k) {
    const double mid = 0.5 * (lo + hi);
    ((excess(mid) < 0) == motoring ? lo : hi) = mid;
  }
  return (synchronous + 0.5 * (lo + hi)) / kTwoPi;
}

}  // namespace drillwave::model
