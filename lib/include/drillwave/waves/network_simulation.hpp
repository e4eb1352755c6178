#pragma once
// Runs a wave network in time: the Simulator loop with a process that keeps the string's waves (a WaveChain, the
// wave channel the coupled kind uses too), the ends' drives and set-valued friction modes, and the breakpoints where a
// kink or a jump reaches an end.
#include <string>
#include <vector>

#include "drillwave/bitrock/stick_slip.hpp"
#include "drillwave/dynamics/top_drive.hpp"
#include "drillwave/integration/options.hpp"
#include "drillwave/waves/network.hpp"

namespace drillwave::waves {

struct NetworkRunOptions {
  double t_end_s = 10;
  double output_interval_s = 1e-3;  // trajectory sampling; 0 samples only the integrator's steps
  integration::IntegratorOptions integrator;
  bool record_energy = false;           // sample the mechanical energy (for conservation checks; costs time)

  // t_end_s finite and > 0, output_interval_s finite and >= 0, valid integrator options (core/validity.hpp).
  bool IsValid(std::string* error) const;
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

// Throws ParameterError for options that are not valid, before the network is run.
NetworkRun SimulateNetwork(const Network& network, const NetworkRunOptions& options);

// The drive a node's process runs (dynamics::TopDrive): its parts, pointing into the node, with a DC motor's constant
// referred to the node through its gear.
dynamics::TopDriveParts DriveParts(const Node& node);

}  // namespace drillwave::waves
