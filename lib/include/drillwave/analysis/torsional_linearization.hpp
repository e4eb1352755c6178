#pragma once
// Steady sliding states of a torsional string and its linearization about one (DESIGN.md §1 and §4).
//
// A one-section string with a dissipative top (torque beta (Omega - v), plus any ground damping of the top, which
// makes it beta' = beta + c_top and Omega' = beta Omega / beta') and a bit of inertia I_B with friction T(w) and
// ground damping c_bit reduces exactly to the neutral DDE of DESIGN.md §1. About a steady bit speed w0 > 0
// (beta' (Omega' - w0) = T(w0) + c_bit w0) the perturbation y of the bit speed satisfies
//   y'(t) - U y'(t - 2 tau) = -(Psi + c) y(t) - U (Psi - c) y(t - 2 tau),
//   U = (beta' - Z)/(beta' + Z), Psi = Z / I_B, c = (T'(w0) + c_bit) / I_B,
// a scalar neutral system whose difference operator has the root chain Re s = ln|U| / (2 tau).
#include <vector>

#include "drillwave/analysis/spectrum.hpp"
#include "drillwave/waves/network.hpp"

namespace drillwave::analysis {

struct TorsionalOperatingPoint {
  double top_speed_rad_s = 0;  // Omega, the top set-point
  double bit_speed_rad_s = 0;  // w0
  double bit_torque_Nm = 0;    // T(w0) + c_bit w0, carried by the whole string
  double torque_slope_Nms_per_rad = 0;  // T'(w0) + c_bit (negative: velocity weakening)
};

// Throws std::invalid_argument unless the network is one section, a massless top of kind kSpeedDashpot, and a bit
// with inertia > 0, without Kelvin-Voigt dashpots or a lateral BHA (the form the reduction holds for).
void CheckLinearizable(const waves::Network& net);

// Every steady sliding speed w0 > 0 for the top set-point Omega, ascending (found on a fine grid of (0, Omega']
// and refined by bisection). Empty if the bit cannot slide steadily (e.g. Omega below the break-away speed).
std::vector<TorsionalOperatingPoint> SteadySlidingStates(const waves::Network& net, double top_speed_rad_s);

LinearDelaySystem LinearizeTorsionalString(const waves::Network& net, const TorsionalOperatingPoint& point);

}  // namespace drillwave::analysis
