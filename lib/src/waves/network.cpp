#include "drillwave/waves/network.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace drillwave::waves {

Section Section::Torsional(double length_m, double shear_modulus_pa, double density_kg_m3, double polar_moment_m4) {
  const double c = std::sqrt(shear_modulus_pa / density_kg_m3);
  return Section{length_m, length_m / c, polar_moment_m4 * std::sqrt(shear_modulus_pa * density_kg_m3)};
}

void Network::Validate() const {
  if (sections.empty()) throw std::invalid_argument("a network needs at least one section");
  if (nodes.size() != sections.size() + 1) throw std::invalid_argument("a chain of n sections has n + 1 nodes");
  for (const Section& s : sections)
    if (!(s.travel_time_s > 0) || !(s.impedance > 0) || !std::isfinite(s.travel_time_s) || !std::isfinite(s.impedance))
      throw std::invalid_argument("sections need positive finite travel time and impedance");
  for (const Section& s : sections)
    if (!(s.dashpot >= 0) || !std::isfinite(s.dashpot))
      throw std::invalid_argument("a section's Kelvin-Voigt dashpot must be >= 0 and finite");
  for (std::size_t i = 1; i + 1 < nodes.size(); ++i) {
    const Node& n = nodes[i];
    if (!n.massless() || n.drive != Drive::kNone || n.friction || n.lateral || !(n.ground_damping >= 0) ||
        !std::isfinite(n.ground_damping))
      throw std::invalid_argument("node '" + n.name + "': a node inside the string (between two sections) is massless, "
                                  "undriven and without friction, with a finite damper >= 0 at most");
  }
  // A massless bit's smooth friction is solved with its balance; a massless top's would be ignored.
  if (top().friction && top().massless())
    throw std::invalid_argument("node '" + top().name + "': friction at the top needs an inertia > 0");
  for (const Node& n : nodes) {
    if (n.lateral && (n.massless() || &n != &nodes.back()))
      throw std::invalid_argument("node '" + n.name + "': a lateral BHA (unbalance) sits at the bit, with an inertia "
                                  "> 0");
    if (n.has_set_valued_friction() && n.massless())
      throw std::invalid_argument("node '" + n.name + "': set-valued friction needs an inertia > 0");
    if (n.drive == Drive::kPiSpeedController && n.massless())
      throw std::invalid_argument("node '" + n.name + "': a PI speed controller needs an inertia > 0");
    const model::TopDriveLaw& law = n.law;
    const bool pi_top = n.drive == Drive::kPiSpeedController && &n == &nodes.front();
    if (law.torque_feedback.active() &&
        (!pi_top || n.gear.compliant() || !std::isfinite(law.torque_feedback.gain) ||
         !(law.torque_feedback.time_constant_s > 0) || !std::isfinite(law.torque_feedback.time_constant_s)))
      throw std::invalid_argument("node '" + n.name + "': torque feedback belongs to a PI top drive without a compliant "
                                  "gear, with a finite gain and a filter time constant > 0");
    if (law.actuator_delay_s != 0 &&
        (!pi_top || n.gear.compliant() || HasKelvinVoigt() || !(law.actuator_delay_s > 0) ||
         !std::isfinite(law.actuator_delay_s)))
      throw std::invalid_argument("node '" + n.name + "': an actuator delay (finite, > 0) belongs to a PI top drive "
                                  "without a compliant gear, on a string without Kelvin-Voigt dashpots");
    if (law.handover.time_s != 0 && (!pi_top || !(law.handover.time_s > 0) || !std::isfinite(law.handover.time_s) ||
                                     !(n.pi.ki > 0)))
      throw std::invalid_argument("node '" + n.name + "': a handover (at a finite time > 0) belongs to a PI top drive "
                                  "whose integral gain ki > 0 takes the integral torque over");
    const double z_law = law.wave_cancellation.impedance;
    if (z_law != 0 && (!pi_top || n.gear.compliant() || HasKelvinVoigt() || n.friction ||
                       law.torque_feedback.active() || !(z_law > 0) || !std::isfinite(z_law) || !(n.pi.kp > 0) ||
                       !(n.pi.ki > 0) || !(law.wave_cancellation.filter_time_constant_s >= 0) ||
                       !std::isfinite(law.wave_cancellation.filter_time_constant_s)))
      throw std::invalid_argument("node '" + n.name +
                                  "': wave cancellation belongs to a PI top drive without a "
                                  "compliant gear, friction or torque feedback, with kp and ki > 0, a finite "
                                  "impedance > 0 and a finite filter time constant >= 0, on a string without "
                                  "Kelvin-Voigt dashpots");
    if (n.has_dc_motor() && (n.massless() || !(n.motor.motor_constant > 0) || !(n.motor.armature_resistance > 0) ||
                             !(n.motor.armature_inductance > 0) || !(n.motor.voltage_limit >= 0)))
      throw std::invalid_argument("node '" + n.name + "': a DC motor needs an inertia, a motor constant, armature "
                                  "resistance and inductance > 0 and a voltage limit >= 0");
    if (n.has_induction_motor()) {
      if (n.massless()) throw std::invalid_argument("node '" + n.name + "': an induction motor needs an inertia > 0");
      const std::string problem = n.induction.Problem();
      if (!problem.empty()) throw std::invalid_argument("node '" + n.name + "': induction motor: " + problem);
    }
    if (n.drive == Drive::kInductionMotorSpeed && initial.speed_rad_s != 0) {
      try {
        n.induction.SteadySupplyFrequency(SteadyTopTorque() / n.gear.ratio, n.gear.ratio * initial.speed_rad_s);
      } catch (const std::domain_error& e) {
        throw std::invalid_argument("node '" + n.name + "': induction motor: no steady start at the initial speed: " +
                                    e.what());
      }
    }
    const model::Gear& g = n.gear;
    if (!(g.ratio > 0) || !(g.stiffness >= 0) || !(g.damping >= 0) || !(g.motor_inertia >= 0) ||
        !std::isfinite(g.ratio + g.stiffness + g.damping + g.motor_inertia))
      throw std::invalid_argument("node '" + n.name + "': a gear needs a ratio > 0, stiffness, damping and motor "
                                  "inertia >= 0, all finite");
    const bool motor_driven =
        n.drive == Drive::kPiSpeedController || n.has_dc_motor() || n.has_induction_motor();
    if (g.compliant() && !(motor_driven && g.motor_inertia > 0 && !n.massless()))
      throw std::invalid_argument("node '" + n.name + "': a compliant gear sits between a PI, DC or induction motor "
                                  "drive with a motor inertia > 0 and a node with an inertia > 0");
    if (n.drive == Drive::kPrescribedSpeed && !n.massless())
      throw std::invalid_argument("node '" + n.name + "': a prescribed-speed node has no inertia");
  }
}

double Network::SteadyTopTorque() const {
  double torque = 0;
  for (const Node& n : nodes) torque += n.SteadyLoad(initial.speed_rad_s);
  return torque;
}

double Network::SmallestTravelTime() const {
  double m = sections.front().travel_time_s;
  for (const Section& s : sections) m = std::min(m, s.travel_time_s);
  return m;
}

bool Network::HasKelvinVoigt() const {
  return std::any_of(sections.begin(), sections.end(), [](const Section& s) { return s.dashpot > 0; });
}

double Network::LargestTravelTime() const {
  double m = 0;
  for (const Section& s : sections) m = std::max(m, s.travel_time_s);
  return m;
}

}  // namespace drillwave::waves
