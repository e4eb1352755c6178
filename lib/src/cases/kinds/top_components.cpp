#include "top_components.hpp"

#include <algorithm>
#include <cmath>

#include "drillwave/core/constants.hpp"
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

namespace {

// The speed loop of a soft-torque top: explicit PI gains, or tuned to a stick-slip period P (Kyllingstad & Nessjoen
// 2009, SoftSpeed): the top's impedance J s + kp + ki / s is then real at s = i 2 pi / P (ki = J (2 pi / P)^2, the
// inertia resonating with the integral's spring) and equal to the pipe's Z (kp = Z), so a wave arriving at the top at
// that frequency is absorbed, not reflected. The inertia is the top's lumped one, known after its gear is read.
void ReadSoftTorqueSpeedLoop(const JsonReader& r, double pipe_impedance, PiTopDriveSpec& drive) {
  if (!r.Has("tuning_period_s")) {
    drive.pi = ReadPiController(r);
    return;
  }
  for (const char* key : {"kp_Nms_per_rad", "ki_Nm_per_rad"})
    if (r.Has(key))
      throw InputError(r.PathOf(key), "a soft_torque top takes either tuning_period_s (the SoftSpeed tuning) or "
                                      "kp_Nms_per_rad and ki_Nm_per_rad, not both");
  drive.tuning_period_s = r.Number("tuning_period_s", Range::Positive());
  drive.pi.kp = pipe_impedance;
}

// The torque feedback's high-pass filter time constant, required with a feedback gain.
double ReadFeedbackTimeConstant(const JsonReader& r) { return r.Number("feedback_time_constant_s", Range::Positive()); }

// A wave-cancelling top's gains (model::WaveCancellation): kp pulls the top onto the speed that absorbs the arriving
// wave, the slow speed loop's corner k [1/s] makes the integral gain ki = 2 Z k (the injected wave d = setpoint / 2 +
// k I). Both > 0: kp = 0 would leave a speed error standing, k = 0 the mean speed short of the set-point under load.
model::PiController ReadWaveCancellationGains(const JsonReader& r, double pipe_impedance) {
  if (r.Has("ki_Nm_per_rad"))
    throw InputError(r.PathOf("ki_Nm_per_rad"), "a wave_cancellation top's integral gain is 2 Z k, Z = " +
                                                    ReadableNumber(pipe_impedance) + " N m s of the top section: "
                                                    "expected speed_loop_corner_rad_s = k instead");
  model::PiController pi;
  pi.kp = r.Number("kp_Nms_per_rad", Range::Positive());
  pi.ki = 2 * pipe_impedance * r.Number("speed_loop_corner_rad_s", Range::Positive());
  return pi;
}

// top/handover: the stiff PI the law takes over from, and when.
model::Handover ReadHandover(const JsonReader& h) {
  model::Handover handover;
  handover.time_s = h.Number("time_s", Range::Positive());
  handover.before = ReadPiController(h);
  h.Finish();
  return handover;
}

}  // namespace

const std::vector<std::string>& PiTopDriveTypes() {
  static const std::vector<std::string> types = {"top_drive", "soft_torque", "z_torque", "wave_cancellation",
                                                 "sliding_mode"};
  return types;
}

bool IsPiTopDriveType(const std::string& type) {
  const std::vector<std::string>& types = PiTopDriveTypes();
  return std::find(types.begin(), types.end(), type) != types.end();
}

PiTopDriveSpec ReadPiTopDrive(const JsonReader& r, const std::string& type, double pipe_impedance) {
  PiTopDriveSpec drive;
  drive.inertia = r.Number("inertia_kgm2", Range::Positive());
  if (type == "top_drive") {
    drive.pi = ReadPiController(r);
    drive.law.torque_limit = r.Number("torque_limit_Nm", Range::NonNegative(), 0.0);
    drive.speed = model::Schedule::FromJson(r.Raw("speed_rad_s"), r.PathOf("speed_rad_s"));
    return drive;  // the stiff PI itself: a handover is an unknown field here
  }
  // A law against stick-slip: the speed command corrected by the high-passed string torque (model::TorqueFeedback),
  // or the wave cancellation (model::WaveCancellation).
  model::TorqueFeedback& feedback = drive.law.torque_feedback;
  drive.law.torque_limit = r.Number("torque_limit_Nm", Range::NonNegative(), 0.0);
  drive.speed = model::Schedule::FromJson(r.Raw("speed_rad_s"), r.PathOf("speed_rad_s"));
  if (type == "soft_torque") {
    ReadSoftTorqueSpeedLoop(r, pipe_impedance, drive);
    feedback.gain = r.Number("feedback_gain_rad_per_Nms", Range::NonNegative(), 0.0);
    if (feedback.active() || r.Has("feedback_time_constant_s")) feedback.time_constant_s = ReadFeedbackTimeConstant(r);
  } else if (type == "z_torque") {  // a stiff speed loop made as soft as the pipe, 1 / gain = Z
    drive.pi = ReadPiController(r);
    feedback.gain = 1 / r.Number("impedance_Nms_per_rad", Range::Positive(), pipe_impedance);
    feedback.time_constant_s = ReadFeedbackTimeConstant(r);
  } else if (type == "sliding_mode") {  // Z-Torque's command held by a sliding surface (model::SlidingMode)
    for (const char* key : {"kp_Nms_per_rad", "ki_Nm_per_rad"})
      if (r.Has(key))
        throw InputError(r.PathOf(key),
                         "a sliding_mode top's gains follow from its surface and layer (inside the "
                         "layer kp = J (lambda + eta / phi), ki = J eta lambda / phi): expected "
                         "surface_corner_rad_s, reaching_rate_rad_s2 and boundary_layer_rad_s instead");
    feedback.gain = 1 / r.Number("impedance_Nms_per_rad", Range::Positive(), pipe_impedance);
    feedback.time_constant_s = ReadFeedbackTimeConstant(r);
    model::SlidingMode& sliding = drive.law.sliding_mode;
    sliding.surface_corner = r.Number("surface_corner_rad_s", Range::Positive());
    sliding.reaching_rate = r.Number("reaching_rate_rad_s2", Range::Positive());
    sliding.boundary_layer = r.Number("boundary_layer_rad_s", Range::Positive());
  } else {  // wave_cancellation: the arriving wave absorbed, exactly or below a low-pass's corner
    drive.pi = ReadWaveCancellationGains(r, pipe_impedance);
    drive.law.wave_cancellation.impedance = pipe_impedance;
    drive.law.wave_cancellation.filter_time_constant_s =
        r.Number("wave_filter_time_constant_s", Range::NonNegative(), 0.0);
  }
  if (r.Has("handover")) drive.law.handover = ReadHandover(r.Object("handover"));
  return drive;
}

void FinishPiTopDrive(const JsonReader& r, const std::string& type, const model::Gear& gear, double lumped_inertia,
                      PiTopDriveSpec& drive) {
  drive.law.actuator_delay_s = r.Number("actuator_delay_s", Range::Between(0, 10), 0.0);
  const model::TopDriveLaw& law = drive.law;
  if ((law.torque_feedback.active() || law.wave_cancellation.active()) && gear.compliant())
    throw InputError(r.PathOf("gear"), std::string(law.wave_cancellation.active() ? "the wave cancellation" :
                                       "the torque feedback") + " of a " + type + " top reads the string torque at a "
                                       "top driven directly: expected a rigid gear (no stiffness_Nm_per_rad)");
  if (law.sliding_mode.active()) drive.pi = law.sliding_mode.InLayer(lumped_inertia);
  if (drive.tuning_period_s > 0) {
    const double omega = 2 * kPi / drive.tuning_period_s;
    drive.pi.ki = lumped_inertia * omega * omega;
  }
  if (drive.law.handover.active() && !(drive.pi.ki > 0))
    throw InputError(r.PathOf("handover"), "the handover carries the integral torque over to the law's integral "
                                           "gain: expected ki_Nm_per_rad > 0 (or tuning_period_s)");
}

void CheckWaveCancellationString(const JsonReader& top, const model::TopDriveLaw& law, double kelvin_voigt_s) {
  if (law.wave_cancellation.active() && kelvin_voigt_s > 0)
    throw InputError(top.PathOf("type"), "wave_cancellation reads the wave arriving at the top alone, which "
                                         "Kelvin-Voigt dashpots next to it would add to: expected no "
                                         "string/kelvin_voigt_s (or 0)");
}

nlohmann::json PiTopDriveLawFields(const std::string& top) {
  return {
      {top + "/torque_limit_Nm",
       "top_drive, soft_torque, z_torque, wave_cancellation, sliding_mode: >= 0, 0 = unlimited"},
      {top + "/actuator_delay_s",
       "top_drive, soft_torque, z_torque, wave_cancellation, sliding_mode: pure delay [s] in [0, 10] of "
       "the drive's torque behind its controller, default 0; not with a compliant gear or "
       "Kelvin-Voigt damping"},
      {top + "/tuning_period_s",
       "soft_torque: the stick-slip period P [s] > 0 the speed loop is tuned to instead of "
       "kp/ki (SoftSpeed, Kyllingstad & Nessjoen 2009): kp = Z of the top section, "
       "ki = J (2 pi / P)^2, J the top's inertia with its rigid gear's motor"},
      {top + "/feedback_gain_rad_per_Nms",
       "soft_torque: torque feedback g [rad/s per N·m] >= 0, default 0: the PI "
       "tracks speed_rad_s - g T_hp, T_hp the string torque at the top high-passed "
       "by feedback_time_constant_s"},
      {top + "/feedback_time_constant_s",
       "soft_torque with a feedback gain, z_torque, sliding_mode: time constant [s] > 0 of the "
       "first-order high-pass filter on the string torque (the mean speed returns "
       "to the set-point on this scale)"},
      {top + "/impedance_Nms_per_rad",
       "z_torque, sliding_mode: the impedance Z [N·m·s/rad] > 0 the top is matched to, default the "
       "top section's G J / c; the PI (the sliding surface) tracks speed_rad_s - T_hp / Z"},
      {top + "/surface_corner_rad_s",
       "sliding_mode: lambda [1/s] > 0 of the surface s = e + lambda * integral(e), e the tracked speed less the "
       "top's (the integral's corner: keep it well below the stick-slip frequency)"},
      {top + "/reaching_rate_rad_s2",
       "sliding_mode: eta [rad/s^2] > 0: the torque u = J lambda e + J eta sat(s / phi), J the top's inertia with a "
       "rigid gear's motor; outside the layer the top reaches it while J eta exceeds the string's torque"},
      {top + "/boundary_layer_rad_s",
       "sliding_mode: phi [rad/s] > 0, the layer's half-width: inside it the law is a PI of kp = J (lambda + eta / "
       "phi), ki = J eta lambda / phi (its linearization); small phi is the near-discontinuous law"},
      {top + "/speed_loop_corner_rad_s",
       "wave_cancellation: the slow speed loop's corner k [rad/s] > 0: the top "
       "injects the down-going wave d = speed_rad_s / 2 + k * integral(speed_rad_s "
       "- w_top) (integral gain ki = 2 Z k, Z of the top section) and reflects what "
       "arrives below k (reflection -k / (s + k)): keep k well below the stick-slip "
       "frequency. Behind actuator_delay_s = delta > 0 the exact law is unstable: "
       "it sends down w(t - delta) - w(t), up to twice the arriving wave w (see "
       "wave_filter_time_constant_s)"},
      {top + "/wave_filter_time_constant_s",
       "wave_cancellation: time constant tf [s] >= 0 of a first-order low-pass "
       "on the arriving wave the law reads, default 0 (none): the top absorbs "
       "below 1 / tf and reflects as a stiff top above it, which keeps the "
       "delayed law's reflection at high frequencies at -1 instead of up to 2"},
      {top + "/handover/time_s",
       "soft_torque, z_torque, wave_cancellation, sliding_mode: optional block; the law takes over at "
       "this time [s] > 0 from the plain PI of the handover's gains (no torque feedback "
       "before it; the integral torque carries over to the law's ki > 0): a drive switched "
       "on while the bit sticks and slips"},
      {top + "/handover/kp_Nms_per_rad", "the PI before the handover: proportional gain >= 0"},
      {top + "/handover/ki_Nm_per_rad", "the PI before the handover: integral gain >= 0"},
  };
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
