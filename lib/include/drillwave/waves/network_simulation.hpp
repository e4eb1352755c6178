#pragma once
// Runs a wave network in time: the Simulator loop with a process that keeps the travel-time buffers (one dense
// history of all outgoing waves), the set-valued friction modes and the breakpoint echoes.
#include <string>
#include <vector>

#include "drillwave/integration/simulator.hpp"
#include "drillwave/waves/network.hpp"

namespace drillwave::waves {

struct NetworkRunOptions {
  double t_end_s = 10;
  double output_interval_s = 1e-3;  // trajectory sampling; 0 samples only the integrator's steps
  integration::IntegratorOptions integrator;
  // Breakpoint echoes: a jump or kink travels on after each node. Value jumps are followed while their weight
  // (product of reflection/transmission coefficients) exceeds the threshold; kinks, which the step-size control
  // can resolve by itself, only while fewer than max_pending_kinks are pending, since in a network of several
  // sections their arrival times multiply. A kink the loop does not step onto costs the step control a few rejected
  // steps; a tracked one costs a forced step end. At loose tolerances the former is cheaper for weak kinks, so the
  // kink threshold follows the tolerance unless set: 0 means AutomaticKinkThreshold(tolerance).
  double echo_weight_threshold = 0;
  std::size_t max_pending_kinks = 64;
  bool record_energy = false;           // sample the mechanical energy (for conservation checks; costs time)
};

// Friction regime of a node with set-valued friction.
enum class Regime { kSlipNegative = -1, kStuck = 0, kSlipPositive = 1 };

struct RegimeChange {
  double time_s;
  int node;
  Regime from, to;
};

// Sampled outputs. Torques: top = torque the top feeds into the string, bit = torque on bit (reaction of the rock:
// the friction torque, equal to the driving torque while stuck).
struct NetworkTrajectory {
  std::vector<double> time_s;
  std::vector<double> top_speed_rad_s, bit_speed_rad_s;
  std::vector<double> top_torque_nm, bit_torque_nm;
  std::vector<double> bit_angle_rad;
  std::vector<double> bit_stuck;  // 1 while the bit is stuck
  std::vector<double> energy_j;   // kinetic energy of the nodes + energy of the waves in flight (record_energy)
};

struct NetworkRun {
  NetworkTrajectory trajectory;
  std::vector<RegimeChange> regime_changes;
  integration::IntegrationStats stats;
  double final_bit_angle_rad = 0;
  double t_end_s = 0;
};

// sqrt(max(abs_tol, rel_tol)) clamped to [1e-3, 3e-2]: 1e-3 (about 23 round trips of the saldivar string) at
// tolerances of 1e-6 and tighter, 3e-2 (about 11) at 1e-3. Measured on saldivar-stickslip at tol 1e-3: 40% fewer
// derivative evaluations with a period error of 2e-6 instead of 8e-6 (apps/bench).
double AutomaticKinkThreshold(const integration::IntegratorOptions& integrator);

NetworkRun SimulateNetwork(const Network& network, const NetworkRunOptions& options);

}  // namespace drillwave::waves
