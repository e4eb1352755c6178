#pragma once
// The torsional string as a continuum with Kelvin-Voigt (and distributed viscous) damping: its exact characteristic
// function and its rightmost roots (DESIGN.md §4), beside the discretized network the simulation integrates (a dashpot
// eta Z / tau_piece across every piece, network_linearization.hpp), whose root count and cost grow with the pieces
// and whose lumped dashpots leave a chain of nearly undamped roots near Im s = pi / tau_piece.
//
// A uniform section: rho J phi_tt = G J (phi_xx + eta phi_xxt) - gamma phi_t (x downward). In the Laplace domain, with
// the speed W = s Phi and the torque carried downward D = -G J (1 + eta s) Phi_x:
//   W_x = -s D / (G J (1 + eta s)),  D_x = -(rho J s + gamma) W,
// so k^2 = s (rho J s + gamma) / (G J (1 + eta s)) and the impedance Z = (rho J s + gamma) / k; without gamma,
// k = s sqrt(rho / (G (1 + eta s))) and Z = J sqrt(rho G (1 + eta s)). From the section's lower end to its upper:
//   [W; D]_upper = [[cosh kL, sinh kL / Z], [Z sinh kL, cosh kL]] [W; D]_lower.
// With the lossless travel time tau and impedance Z0 and a = gamma / (rho J): (kL)^2 = s (s + a) tau^2 / (1 + eta s),
// Z sinh kL = Z0 tau (s + a) S and sinh kL / Z = s tau S / (Z0 (1 + eta s)), S = sinh(kL) / kL. All are even in k:
// entire in s but for s = -1/eta, where the overdamped modes' roots accumulate (the essential spectrum).
//
// The bit (W_bit = 1): D_bit = (I_B s + c) with c the friction slope plus the bit's damper. The top closes the chain:
//   imposed speed   f(s) = W_top
//   dashpot         f(s) = D_top + beta' W_top                       (beta' = beta + the top's damper)
//   PI speed drive  f(s) = (I_T s^2 + (c_T + kp) s + ki) W_top + s D_top   (ki > 0; without ki, divided by s)
// Depends on Eigen only through spectrum.hpp; no simulation.
#include <complex>
#include <vector>

#include "drillwave/analysis/spectrum.hpp"

namespace drillwave::analysis {

struct ContinuumSection {
  double travel_time_s = 0;  // lossless: L / sqrt(G / rho)
  double impedance = 0;      // lossless: J sqrt(rho G) [N m s/rad]
  double length_m = 0;
};

struct ContinuumTop {
  enum class Kind { kImposedSpeed, kDashpot, kPiSpeed } kind = Kind::kImposedSpeed;
  double damping_Nms_per_rad = 0;  // kDashpot: beta'; kPiSpeed: the top's damper plus kp
  double inertia_kgm2 = 0;         // kPiSpeed (with a rigid gear's motor)
  double ki_Nm_per_rad = 0;        // kPiSpeed
};

struct KelvinVoigtString {
  std::vector<ContinuumSection> sections;  // top to bit
  double kelvin_voigt_s = 0;               // eta >= 0
  double viscous_damping_Nms_per_rad_m = 0;  // gamma >= 0
  ContinuumTop top;
  double bit_inertia_kgm2 = 0;
  double bit_torque_slope_Nms_per_rad = 0;  // friction slope plus the bit's damper (negative: velocity weakening)
};

// f(s) = a + b as above (a: the W_top term, b: the D_top term): |a + b| / (|a| + |b|) is the relative residual.
struct ContinuumValue {
  std::complex<double> a, b;
  std::complex<double> value() const { return a + b; }
};
ContinuumValue ContinuumCharacteristic(const KelvinVoigtString& string, std::complex<double> s);

struct ContinuumSpectrum {
  // roots: every root in the box, distinct, Im s >= 0, rightmost first; essential_abscissa -1/eta (NaN for eta = 0:
  // not computed); residual |f| / (|a| + |b|).
  Spectrum spectrum;
  double re_left = 0, re_right = 0, im_max = 0;  // the box: max(re_min, -0.9 / eta) <= Re s <= re_right
  // The argument principle counts as many roots in the box as were found: none is missed.
  bool certified = false;
};

// Newton's method from a grid of starts over the box, each run with the roots found divided out, until the argument
// principle counts no more roots than found (the grid refined up to three times). re_right bounds every root: a
// passive string (Re Z_in >= 0 for Re s >= 0) behind an inertial bit has none beyond -c / I_B.
ContinuumSpectrum ComputeContinuumSpectrum(const KelvinVoigtString& string, const SpectrumOptions& options = {});

}  // namespace drillwave::analysis
