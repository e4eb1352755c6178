// The effects of a laboratory rig modelled as a two-inertia pendulum (kind two_mass): its drive, its friction and the
// calibration of its disc's inertia.
#include <algorithm>
#include <cmath>

#include "effect_support.hpp"

namespace drillwave::diagnosis {

using namespace effect_support;

// The effects of a laboratory rig modelled as a two-inertia pendulum (kind two_mass): its drive and its friction.
std::vector<Effect> RigEffects(const nlohmann::json& doc, const FeatureSet& m, const FeatureSet& r) {
  std::vector<Effect> effects;
  const double k = Number(doc, "/model/string/stiffness_Nm_per_rad", 1);
  const double j = Number(doc, "/model/bit/inertia_kgm2", 1);
  // The shaft's characteristic impedance sqrt(k J) and frequency sqrt(k / J): a drive of that damping absorbs the
  // oscillation instead of reflecting it (the lumped counterpart of a pipe-matched drive).
  const double impedance = std::sqrt(k * j), frequency = std::sqrt(k / j);
  if (doc.value("/model/top/type"_json_pointer, std::string()) == "top_drive" &&
      doc.at("/model/top/speed_rad_s"_json_pointer).is_number()) {
    // A soft drive yields to the load: its speed falls by torque / kp below the no-load speed (droop), and its motor's
    // inertia stiffens it at high frequency (impedance kp + i w J). The no-load speed is set so that the mean speed
    // stays the set-point's at the recorded mean torque (torque channel tob_Nm; otherwise the friction's kinetic
    // level). No integral: a speed loop's integral slower than the recording is not identified by it, and where the
    // fit left one (the UFRJ rig: ki 1.5e-4 N m/rad, an integral time of 3000 s) it drifted the set-point by 0.36 %
    // within 32 s and carried the model out of stick-slip after the recording's end (issue 32).
    const double speed = Number(doc, "/model/top/speed_rad_s", 1);
    const double torque = std::isfinite(r.Value("tob_Nm mean"))
                              ? r.Value("tob_Nm mean")
                              : Number(doc, "/model/bit/friction/T_c_Nm", 0);
    const double motor = Number(doc, "/model/top/inertia_kgm2", j);
    Effect e{"soft_topdrive", "a soft drive: a speed loop with droop (gain, no-load speed) on the motor's inertia", {},
             nullptr, 0, ""};
    // The recorded droop (top rpm per N m of torque on bit, the shaft's torque on average) is the gain a lab would
    // read off its drive: the fit starts there (from the shaft's impedance without it).
    const double droop = r.Value(kDriveDroop);
    const double kp = std::isfinite(droop) && droop < 0
                          ? std::clamp(-30 / (kPi * droop), 0.01 * impedance, 100 * impedance)
                          : impedance;
    e.parameters = {{"kp_Nms_per_rad", "N m s/rad", 0.01 * impedance, 100 * impedance, true, kp},
                    {"motor_inertia_kgm2", "kg m^2", 0.05 * j, 10 * j, true, std::clamp(motor, 0.05 * j, 10 * j)}};
    e.apply = [speed, torque](nlohmann::json& d, const std::vector<double>& v) {
      d["model"]["top"]["kp_Nms_per_rad"] = v[0];
      d["model"]["top"]["ki_Nm_per_rad"] = 0.0;
      d["model"]["top"]["inertia_kgm2"] = v[1];
      d["model"]["top"]["speed_rad_s"] = speed + torque / v[0];
    };
    const double z = std::max(-Z(m, r, "top_rpm std"), -0.5 * Z(m, r, "top_rpm fast_std"));
    if (z > kWeakEvidence) e.strength = z, e.evidence = "the drive's speed moves more than the model's controller lets it: " +
                                            Describe(m, r, "top_rpm std");
    effects.push_back(e);
  }
  // Not an effect but a calibration: the recorded oscillation period against the model's (or, where the model does
  // not oscillate, the shaft-and-disc natural period 2 pi sqrt(J / k)) says how far the disc's inertia is off (a
  // period scales with its square root).
  {
    const double period = r.Value("period_s"), model_period = m.Value("period_s");
    const bool oscillates = std::isfinite(model_period);
    const double reference = oscillates ? model_period : 2 * kPi / frequency;
    const double estimate = std::isfinite(period) ? j * std::pow(period / reference, 2) : j;
    Effect e{"bit_inertia", "calibration: the bottom disc's inertia (with the shaft stiffness, the period)", {},
             nullptr, 0, ""};
    e.parameters = {{"inertia_kgm2", "kg m^2", 0.2 * j, 20 * j, true, std::clamp(estimate, 0.2 * j, 20 * j)}};
    e.apply = [](nlohmann::json& d, const std::vector<double>& v) { d["model"]["bit"]["inertia_kgm2"] = v[0]; };
    const double z = !std::isfinite(period) ? 0.0
                     : oscillates           ? std::abs(Z(m, r, "period_s"))
                                            : std::abs(std::log(period / reference)) / 0.05;
    if (z > kWeakEvidence)
      e.strength = z, e.evidence = "the recording oscillates with period " + Significant(period, 3) + " s, the " +
                                   (oscillates ? "model" : "shaft and disc's natural period") + " with " +
                                   Significant(reference, 3) + " s: the inertia " + Significant(estimate, 3) +
                                   " kg m^2 would give it";
    effects.push_back(e);
  }
  const nlohmann::json::json_pointer friction("/model/bit/friction");
  if (doc.contains(friction) && doc.at(friction).value("law", std::string()) == "coulomb") {
    const nlohmann::json coulomb = doc.at(friction);
    const double t_s = coulomb.value("T_s_Nm", coulomb.value("T_c_Nm", 1.0));
    const double viscous = coulomb.value("c_Nms_per_rad", 0.0);
    const double weight = Number(doc, "/model/bit/nominal_weight_on_bit_N", 1);
    Effect e{"stribeck", "friction at the bottom disc that weakens with speed (Stribeck)", {}, nullptr, 0, ""};
    e.parameters = {{"static_torque_Nm", "N m", 0.7 * t_s, 1.6 * t_s, false, t_s},
                    {"kinetic_to_static", "-", 0.0, 1.0, false, 0.7},
                    {"nu_f_rad_s", "rad/s", 0.3, 100, true, 5}};
    e.apply = [viscous, weight](nlohmann::json& d, const std::vector<double>& v) {
      const double mu_s = v[0] / weight;  // with R = 1 m: only mu R W is identified
      d["model"]["bit"]["friction"] = {{"law", "stribeck"}, {"W_N", weight},       {"R_m", 1.0},
                                       {"mu_s", mu_s},      {"mu_c", v[1] * mu_s}, {"gamma_b", 1.0},
                                       {"nu_f_rad_s", v[2]}, {"c_b_Nms_per_rad", viscous}};
    };
    // (A recording without a torque channel leaves that term out; NaN would void the evidence of the others.)
    const double torque_z = Z(m, r, "tob_Nm mean");
    const double z = -std::min(Z(m, r, "stick_fraction") - 1, 0.0) - std::min(Z(m, r, "bit_rpm std"), 0.0) +
                     (torque_z > 0 ? torque_z : 0.0);
    if (z > kWeakEvidence) e.strength = z, e.evidence = "the disc sticks or swings more, at less torque, than with Coulomb "
                                            "friction: " + Describe(m, r, "stick_fraction") + "; " +
                                            Describe(m, r, "bit_rpm std") + "; " + Describe(m, r, "tob_Nm mean");
    effects.push_back(e);
  }
  return effects;
}


}  // namespace drillwave::diagnosis
