#pragma once
// Runs a wave network in time: the Simulator loop with a process that keeps the travel-time buffers (one dense
// history of all outgoing waves), the set-valued friction modes and the breakpoint echoes.
#include <string>
#include <vector>

#include "drillwave/bitrock/stick_slip.hpp"
#include "drillwave/integration/options.hpp"
#include "drillwave/waves/network.hpp"

namespace drillwave::waves {

struct NetworkRunOptions {
  double t_end_s = 10;
  double output_interval_s = 1e-3;  // trajectory sampling; 0 samples only the integrator's steps
  integration::IntegratorOptions integrator;
  // Breakpoint echoes: a jump or kink travels on after each node, scaled by the node's reflection or transmission
  // coefficient; echoes that arrive together are merged. Value jumps are followed while their weight exceeds
  // AutomaticJumpThreshold. Kinks, which the step-size control can resolve by itself at the price of rejected steps,
  // are followed while their weight exceeds echo_weight_threshold and fewer than max_pending_kinks are pending.
  // 0 means AutomaticKinkThreshold(tolerance).
  double echo_weight_threshold = 0;
  std::size_t max_pending_kinks = 4096;
  bool record_energy = false;           // sample the mechanical energy (for conservation checks; costs time)
};

// A change of the friction regime of a node with set-valued friction.
struct RegimeChange {
  double time_s;
  int node;
  bitrock::Turn from, to;
};

// Sampled outputs. Torques: top = torque the top feeds into the string, bit = torque on bit (reaction of the rock:
// the friction torque, equal to the driving torque while stuck).
struct NetworkTrajectory {
  std::vector<double> time_s;
  std::vector<double> top_speed_rad_s, bit_speed_rad_s;
  std::vector<double> top_torque_nm, bit_torque_nm;
  std::vector<double> bit_angle_rad;
  std::vector<double> bit_stuck;  // 1 while the bit is stuck
  std::vector<double> top_current_a;  // DC motor top: armature current; induction motor: stator rms (empty otherwise)
  std::vector<double> motor_speed_rad_s, gear_torque_nm;  // top behind a compliant gear: motor shaft, gear (else empty)
  std::vector<double> energy_j;   // kinetic energy of the nodes + energy of the waves in flight (record_energy)
  std::vector<double> lateral_displacement_m;  // bit with a lateral BHA: whirl radius sqrt(x^2 + y^2)
  std::vector<double> dissipated_j;  // energy the Kelvin-Voigt dashpots have dissipated since t = 0 (record_energy)
};

struct NetworkRun {
  NetworkTrajectory trajectory;
  std::vector<RegimeChange> regime_changes;
  integration::IntegrationStats stats;
  double final_bit_angle_rad = 0;
  double t_end_s = 0;
};

// sqrt(max(abs_tol, rel_tol)) clamped to [1e-5, 3e-2]. A kink left inside a step costs the stored waves a few
// rejected steps; a followed one costs a forced step end. Measured (80 s of saldivar-stickslip with 200 m of collars,
// tol 1e-8): threshold 1e-3 with at most 64 pending kinks, 3.9e6 derivative evaluations of which 228 000 steps were
// redone; 1e-4 and 4096 pending, 1.7e6 and 3 700; 1e-5, 2.4e6 and 111. At tol 1e-3, 3e-2 (about 11 round trips
// of the single-section string) saves 40% of the evaluations against 1e-3 (apps/bench).
double AutomaticKinkThreshold(const integration::IntegratorOptions& integrator);

// Value jumps are followed while their weight exceeds a tenth of the tighter tolerance (clamped to [1e-15, 1e-6]):
// a smaller jump, left inside a step, changes the stored waves by less than the tolerance allows.
double AutomaticJumpThreshold(const integration::IntegratorOptions& integrator);

NetworkRun SimulateNetwork(const Network& network, const NetworkRunOptions& options);

}  // namespace drillwave::waves
