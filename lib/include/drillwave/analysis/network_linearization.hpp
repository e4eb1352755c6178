#pragma once
// Steady rotation of a torsional wave network (any chain of sections, any top of waves::Drive) and the linear
// neutral system of small perturbations about it (DESIGN.md §1 and §4).
//
// In steady rotation every node turns at the bit speed w0 and the top supplies the load: the ground damping of
// every node and the friction of the bit. About it, each section k carries two waves; their integrals p_k (down-going,
// leaving the upper node) and q_k (up-going, leaving the lower node) are the derivative-only states of the system
// (LinearDelaySystem::derivative_only_states): a wave arriving at a node is p_k' or q_k' one travel time ago, so every
// scattering is a neutral term. Nodes with inertia add their speed, PI controllers their integral, DC motors their
// current, induction motors their four fluxes (about the fluxes that hold still in the simulation's own equations),
// and a motor behind a compliant gear its speed (referred to the node) and the gear's twist; a wave-cancelling top
// (model::WaveCancellation) has its speed's error to the law's speed instead of its speed, which then reads the
// arriving wave and the integral an actuator delay late (retarded and neutral terms at d, tau + d, 2 d, tau + 2 d).
// A rigid gear adds n^2 J_m to the node's inertia; the drives' constants are referred to the node's side as the
// simulation refers them.
// A massless node's speed is algebraic in the arriving waves and is substituted; Kelvin-Voigt dashpots across the
// sections (waves::Section::dashpot) tie it to its neighbours' speeds, and the massless nodes' speeds then solve one
// linear system (as in the simulation), substituted likewise; an inertial node feels kv (v_neighbour - v). A lateral
// BHA at the bit adds its whirl in the frame turning with the bit (bha_whirl_linearization.hpp).
//
// At high frequency an inertial node reflects like a fixed end (-1), as does an imposed speed: between two such ends
// a lossless string has its essential spectrum on the imaginary axis (Spectrum::Verdict::kMarginal).
#include <string>
#include <vector>

#include "drillwave/analysis/spectrum.hpp"
#include "drillwave/waves/network.hpp"

namespace drillwave::analysis {

struct NetworkOperatingPoint {
  double top_setpoint = 0;     // the top's final set-point (speed, torque or voltage, by drive)
  double speed_rad_s = 0;      // w0: every node turns at it
  double top_torque_Nm = 0;    // what the top supplies: the whole load (fixes a slip-controlled motor's supply)
  double bit_torque_Nm = 0;    // friction plus ground damping of the bit, plus a lateral BHA's steady whirl drag
  double bit_torque_slope_Nms_per_rad = 0;  // d/dw of friction plus damping (negative: velocity weakening)
};

// Every steady rotation w0 > 0 at the final set-point, ascending. Imposed-speed, PI, DC and induction speed-controlled
// tops (with an integral gain) hold w0 at the set-point (and drop it when the torque or voltage limit or the induction
// motor's pull-out torque cannot hold the load);
// the other tops balance their torque against the load, found on a grid of 4000 speeds and refined by bisection. Empty when
// nothing turns steadily forward (a set-point <= 0, a bit held by static friction).
std::vector<NetworkOperatingPoint> NetworkSteadyStates(const waves::Network& net);

struct NetworkLinearization {
  LinearDelaySystem system;
  std::vector<std::string> state_names;  // node states first, then the wave integrals
};

// Throws std::invalid_argument when the linearization is singular (a massless node whose damping cancels the
// impedances it joins).
NetworkLinearization LinearizeNetwork(const waves::Network& net, const NetworkOperatingPoint& point);

}  // namespace drillwave::analysis
