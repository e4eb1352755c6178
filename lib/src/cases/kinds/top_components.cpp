#include "top_components.hpp"

#include "drillwave/core/error.hpp"

namespace drillwave::cases {

using io::JsonReader;
using Range = io::Range;

model::InductionMotor ReadInductionMotor(const JsonReader& r) {
  model::InductionMotor m;
  m.pole_pairs = r.Integer("pole_pairs", 1, 64);
  m.stator_resistance = r.Number("stator_resistance_ohm", Range::Positive());
  m.rotor_resistance = r.Number("rotor_resistance_ohm", Range::Positive());
  m.stator_leakage_inductance = r.Number("stator_leakage_inductance_H", Range::Positive());
  m.rotor_leakage_inductance = r.Number("rotor_leakage_inductance_H", Range::Positive());
  m.magnetizing_inductance = r.Number("magnetizing_inductance_H", Range::Positive());
  m.volts_per_hertz = r.Number("volts_per_hertz_V_per_Hz", Range::Positive());
  m.voltage_limit = r.Number("voltage_limit_V", Range::NonNegative(), 0.0);
  r.Finish();
  return m;
}

model::Gear ReadGear(const JsonReader& top) {
  model::Gear gear;  // absent: ratio 1, rigid (a motor inertia alone adds to the top's)
  if (top.Has("gear")) {
    const JsonReader g = top.Object("gear");
    gear.ratio = g.Number("ratio", Range::Positive(), 1.0);
    gear.stiffness = g.Number("stiffness_Nm_per_rad", Range::NonNegative(), 0.0);
    gear.damping = g.Number("damping_Nms_per_rad", Range::NonNegative(), 0.0);
    g.Finish();
  }
  const Range motor_inertia = gear.compliant() ? Range::Positive() : Range::NonNegative();
  gear.motor_inertia = top.Number("motor_inertia_kgm2", motor_inertia, 0.0);
  if (gear.compliant() && !top.Has("motor_inertia_kgm2"))
    throw InputError(top.PathOf("motor_inertia_kgm2"), "a compliant gear (gear/stiffness_Nm_per_rad > 0) needs the "
                                                       "motor's inertia behind it: expected a number > 0");
  return gear;
}

model::PiController ReadPiController(const JsonReader& top, const char* kp_key, const char* ki_key) {
  model::PiController pi;
  pi.kp = top.Number(kp_key, Range::NonNegative());
  pi.ki = top.Number(ki_key, Range::NonNegative());
  return pi;
}

nlohmann::json TopComponentFields(const std::string& top) {
  const std::string im = top + "/induction_motor/";
  return {
      {im + "pole_pairs", "p, integer in [1, 64] (synchronous shaft speed 2 pi f / p)"},
      {im + "stator_resistance_ohm", "R_s > 0, per phase"},
      {im + "rotor_resistance_ohm", "R_r > 0, per phase, referred to the stator"},
      {im + "stator_leakage_inductance_H", "L_ls > 0"},
      {im + "rotor_leakage_inductance_H", "L_lr > 0"},
      {im + "magnetizing_inductance_H", "L_m > 0"},
      {im + "volts_per_hertz_V_per_Hz", "> 0: line-to-line rms voltage per hertz of supply"},
      {im + "voltage_limit_V", ">= 0, default 0 = none: line-to-line rms limit (field weakening above it)"},
      {top + "/gear/ratio", "> 0, default 1: motor turns per top-drive turn (optional block; drive gains, set-points "
                            "and stiffness are on the top drive's side)"},
      {top + "/gear/stiffness_Nm_per_rad", ">= 0, default 0 = rigid; > 0: the rig's two-mass model, motor inertia "
                                           "behind a compliant gear"},
      {top + "/gear/damping_Nms_per_rad", ">= 0, default 0: gear damping (compliant gear)"},
      {top + "/motor_inertia_kgm2", "J_m on the motor shaft: > 0 with a compliant gear, >= 0 (default 0) with a rigid "
                                    "one (then ratio^2 J_m adds to the top inertia)"},
  };
}

}  // namespace drillwave::cases
