#pragma once
// The per-phase T equivalent circuit of an induction machine (Krause et al., Analysis of Electric Machinery, ch. 6):
// the independent reference for the simulators' two-axis flux model in steady state.
#include <algorithm>
#include <cmath>
#include <complex>

#include "drillwave/core/constants.hpp"
#include "drillwave/model/induction_motor.hpp"

namespace drillwave::testing {

// A 690 V, 60 Hz four-pole machine of about 800 kW (illustrative values of the size that drives top drives).
inline model::InductionMotor IllustrativeMachine() {
  model::InductionMotor m;
  m.pole_pairs = 2;
  m.stator_resistance = m.rotor_resistance = 0.01;
  m.stator_leakage_inductance = m.rotor_leakage_inductance = 0.2e-3;
  m.magnetizing_inductance = 8e-3;
  m.volts_per_hertz = 690.0 / 60;
  return m;
}

struct CircuitPoint {
  double torque;          // 3 p |I_r|^2 R_r / (s w_e) [N·m]
  double stator_current;  // rms [A]
};

// At supply frequency f [Hz] and shaft speed w [rad/s], with the phase voltage of the V/f line (and its limit).
inline CircuitPoint EquivalentCircuit(const model::InductionMotor& m, double f, double w) {
  const double w_e = 2 * kPi * f, s = (w_e - m.pole_pairs * w) / w_e;
  const std::complex<double> j(0, 1);
  const std::complex<double> z_m = j * w_e * m.magnetizing_inductance;
  const std::complex<double> z_r = m.rotor_resistance / s + j * w_e * m.rotor_leakage_inductance;
  const std::complex<double> z_s = m.stator_resistance + j * w_e * m.stator_leakage_inductance;
  const double line = m.voltage_limit > 0 ? std::min(m.volts_per_hertz * f, m.voltage_limit) : m.volts_per_hertz * f;
  const std::complex<double> i_s = line / std::sqrt(3.0) / (z_s + z_m * z_r / (z_m + z_r));
  const std::complex<double> i_r = i_s * z_m / (z_m + z_r);
  return {3 * m.pole_pairs * std::norm(i_r) * m.rotor_resistance / (s * w_e), std::abs(i_s)};
}

// The root of g on [lo, hi] where g(lo) > 0 > g(hi), by bisection to rounding.
template <class F>
double Bisect(F g, double lo, double hi) {
  for (int k = 0; k < 200 && std::abs(hi - lo) > 1e-15 * std::max(std::abs(lo), std::abs(hi)); ++k)
    (g(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

}  // namespace drillwave::testing
