#pragma once
// The wave network of a drill string (DESIGN.md §1): uniform sections carrying d'Alembert waves between nodes.
// One channel (torsional here; the axial channel has the same structure with force and linear speed).
// Sections and nodes form a chain: node 0 is the top, node i sits between sections i-1 and i, the last node is
// the bit. The model is immutable; a run's changing state lives in NetworkProcess.
#include <optional>
#include <string>
#include <vector>

#include "drillwave/bitrock/friction.hpp"
#include "drillwave/model/dc_motor.hpp"
#include "drillwave/model/drive.hpp"
#include "drillwave/model/gear.hpp"
#include "drillwave/model/induction_motor.hpp"
#include "drillwave/model/jeffcott_bha.hpp"
#include "drillwave/model/pi_controller.hpp"
#include "drillwave/model/schedule.hpp"
#include "drillwave/model/top_drive_law.hpp"

namespace drillwave::waves {

// A uniform section: the 1-D wave equation reduced to its travel time and impedance.
struct Section {
  double length_m = 0;
  double travel_time_s = 0;  // tau = L / c
  double impedance = 0;      // Z = K / c = sqrt(K rho X): N·m·s/rad for torsion
  // Kelvin-Voigt damping (chapter eq. 2.20, T += eta K dw/ds) lumped as a dashpot eta K / length across the section,
  // between its end nodes [N·m·s/rad]; 0: none. It ties neighbouring massless nodes into one linear system.
  double dashpot = 0;

  // Torsion of a section of polar moment J [m^4], shear modulus G [Pa], density rho [kg/m^3].
  static Section Torsional(double length_m, double shear_modulus_pa, double density_kg_m3, double polar_moment_m4);
  double wave_speed() const { return length_m / travel_time_s; }
  double stiffness() const { return impedance * wave_speed() / length_m; }  // K / L: lumped spring of the section
  double inertia() const { return impedance * travel_time_s; }              // rho J L: lumped inertia of the section
};

using Drive = model::Drive;
using DcMotor = model::DcMotor;

struct Node {
  std::string name;                  // e.g. "top", "junction", "bit": used in messages and outputs
  double inertia = 0;                // kg·m^2; 0 makes the node massless (algebraic)
  double ground_damping = 0;         // torque -c v to the borehole or frame (local dampers, lumped viscous damping)
  Drive drive = Drive::kNone;
  model::Schedule setpoint;          // speed [rad/s] or torque [N·m], by drive
  double drive_damping = 0;          // beta of kSpeedDashpot [N·m·s/rad]
  model::PiController pi;            // kPiSpeedController gains [N·m·s/rad], [N·m/rad]
  // kPiSpeedController: its torque limit; at the top also its law against stick-slip (model::TopDriveLaw): torque
  // feedback (rigid gear), actuator delay (rigid gear, no Kelvin-Voigt dashpots), handover.
  model::TopDriveLaw law;
  DcMotor motor;                     // kDcMotorVoltage, kDcMotorSpeed; kp [V·s/rad], ki [V/rad] for the latter
  model::InductionMotor induction;   // kInductionMotor
  // Between the drive (PI, DC or induction motor) and the node. The drive's speed, torque and gains are referred to
  // the node's side; a DC motor's constant and an induction motor's shaft speed are the motor's own.
  model::Gear gear;
  std::optional<bitrock::FrictionLaw> friction;  // contact torque (bit–rock); set-valued laws need inertia > 0
  // The BHA's lateral motion with a mass unbalance turning with the node (the bit only: it turns with the bit angle,
  // the one angle the network integrates). Needs inertia > 0.
  std::optional<model::JeffcottBha> lateral;

  bool massless() const { return inertia == 0; }
  bool has_dc_motor() const { return drive == Drive::kDcMotorVoltage || drive == Drive::kDcMotorSpeed; }
  bool has_induction_motor() const { return drive == Drive::kInductionMotor || drive == Drive::kInductionMotorSpeed; }
  bool has_speed_integral() const {
    return drive == Drive::kPiSpeedController || drive == Drive::kDcMotorSpeed || drive == Drive::kInductionMotorSpeed;
  }
  bool has_torque_feedback() const { return drive == Drive::kPiSpeedController && law.torque_feedback.active(); }
  // A PI drive's filter state: the torque feedback's low-passed string torque or the filtered wave cancellation's wave.
  bool has_drive_filter() const {
    return drive == Drive::kPiSpeedController && (law.torque_feedback.active() || law.wave_cancellation.filtered());
  }
  bool has_set_valued_friction() const { return friction && friction->IsSetValued(); }
  bool has_compliant_gear() const { return gear.compliant(); }
  // The inertia the node's own speed carries: with a rigid gear the motor's too, with a lateral BHA the unbalance's
  // share (model::JeffcottBha::AddedInertia).
  double LumpedInertia() const {
    return inertia + gear.InertiaAddedToNode() + (lateral ? lateral->AddedInertia() : 0.0);
  }
  // Torque that turning steadily at v costs the node: its dampers and its friction.
  double SteadyLoad(double v) const { return ground_damping * v + (friction && v != 0 ? friction->SlipTorque(v) : 0.0); }
};

// Initial condition: at rest, or turning rigidly at a given speed with the steady torque carried by every section.
struct InitialCondition {
  double speed_rad_s = 0;
};

struct Network {
  std::vector<Section> sections;
  std::vector<Node> nodes;  // sections.size() + 1
  InitialCondition initial;

  // Throws std::invalid_argument describing the first inconsistency (the case parser reports JSON paths first).
  void Validate() const;
  const Node& top() const { return nodes.front(); }
  const Node& bit() const { return nodes.back(); }
  double SmallestTravelTime() const;
  // Torque the top feeds in while everything turns rigidly at the initial speed.
  double SteadyTopTorque() const;
  double LargestTravelTime() const;
  bool HasKelvinVoigt() const;
};

}  // namespace drillwave::waves
