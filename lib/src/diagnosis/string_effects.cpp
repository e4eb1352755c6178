// The effects of a field string modelled as coupled axial and torsional waves (kind axial_torsional): the issue's
// vocabulary (soft drive, side friction, Stribeck friction, axial decoupling, BHA, Kelvin-Voigt damping, DC motor,
// unbalance, sensor delay) with the evidence each reads from the features, and the rock's base calibrations.
#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>

#include "drillwave/core/format.hpp"
#include "effect_support.hpp"

namespace drillwave::diagnosis {

using namespace effect_support;

namespace {

// The downhole channels of a sensors block (bit speed, weight on bit): what telemetry delays.
bool Downhole(const std::string& channel) { return channel.rfind("bit_", 0) == 0 || channel.rfind("wob", 0) == 0; }

struct Pipe {
  double length, impedance, wave_speed, density, polar;
};

Pipe PipeOf(const nlohmann::json& doc) {
  const double od = Number(doc, "/model/string/outer_diameter_m", 0.127);
  const double id = Number(doc, "/model/string/inner_diameter_m", 0.1086);
  const double g = Number(doc, "/model/string/shear_modulus_Pa", 8.08e10);
  const double rho = Number(doc, "/model/string/density_kg_m3", 7850);
  const double polar = kPi / 32 * (std::pow(od, 4) - std::pow(id, 4));
  return {Number(doc, "/model/string/length_m", 2000), polar * std::sqrt(g * rho), std::sqrt(g / rho), rho, polar};
}

// What the effects' ranges and first values are read from: the pipe, the rock's friction, the lumped BHA, the drive.
struct StringFacts {
  Pipe pipe;
  double mu, bit_mass, bit_inertia;
  double first_mode;  // rad/s: the first torsional mode of a pipe clamped at the top with a heavy bit, a quarter wave
  double drive_kp, drive_ki;  // the case's PI gains (NaN where the case has a motor behind them: another law)
  double top_inertia;         // the top drive's, kg m^2 (NaN if the case gives none)
};

// A recorded drive law this many times less stiff than the case's is another drive: the cross-spectral estimate is
// biased low by at most 1 - coherence (10 %) where it is identified, and the stiff drives of ../shared read within
// 0.84-1.21 times their case's |H| (kp 1e5, ki 2e5) on every sticking recording.
constexpr double kSofterDrive = 2;
// Evidence is capped here: a difference of that many standard deviations is certain, and the cap keeps the
// proposals' order finite where the coherence is 1 to rounding.
constexpr double kMostEvidence = 100;

// The case's PI stiffness over the recorded law's at the law's frequency (drive_law.hpp), where the law is identified
// and the case's drive is a plain PI; NaN otherwise.
double CaseOverRecordedStiffness(const StringFacts& s, const DriveLaw& law) {
  if (!law.Identified() || !std::isfinite(s.drive_kp) || !std::isfinite(s.drive_ki)) return std::nan("");
  const double w = 2 * kPi * law.frequency_hz;
  return std::hypot(s.drive_kp, s.drive_ki / w) / law.Stiffness();
}

// How much softer the recorded drive law is than the case's PI, in standard deviations of the estimate's ln |H|, where
// it is identified and at least kSofterDrive times softer; 0 otherwise.
double SofterDriveEvidence(const StringFacts& s, const DriveLaw& law) {
  const double ratio = CaseOverRecordedStiffness(s, law);
  if (!(ratio >= kSofterDrive)) return 0;
  return std::min(kMostEvidence, std::log(ratio) / law.LogStiffnessStd());
}

// soft_topdrive: the top speed moves more than the stiff drive lets it. The first values are the SoftSpeed tuning
// (Kyllingstad & Nessjoen 2009, as a soft_torque top's tuning_period_s sets it): a drive that absorbs torsional waves
// matches the pipe's impedance (kp = Z), and its integral gain makes the top inertia resonate with the integral's
// spring at the string's first mode (ki = J_td w1^2), where stick-slip oscillates.
Effect ProposeSoftTopdrive(const StringFacts& s, const FeatureSet& m, const FeatureSet& r) {
  const Pipe& pipe = s.pipe;
  const double first_mode = s.first_mode;
  const double ki_lower = 0.01 * pipe.impedance * first_mode, ki_upper = 1000 * pipe.impedance * first_mode;
  const double tuned_ki = std::isfinite(s.top_inertia) ? s.top_inertia * first_mode * first_mode
                                                        : 3 * pipe.impedance * first_mode;
  Effect e{"soft_topdrive", "a softer top-drive speed controller (PI gains)", {}, nullptr, 0, ""};
  e.parameters = {{"kp_Nms_per_rad", "N m s/rad", 0.1 * pipe.impedance, 300 * pipe.impedance, true, pipe.impedance},
                  {"ki_Nm_per_rad", "N m/rad", ki_lower, ki_upper, true, std::clamp(tuned_ki, ki_lower, ki_upper)}};
  e.apply = [](nlohmann::json& d, const std::vector<double>& v) {
    d["model"]["top"]["kp_Nms_per_rad"] = v[0];
    d["model"]["top"]["ki_Nm_per_rad"] = v[1];
  };
  // A drive soft enough to let the top speed move also absorbs the torsional waves that make the bit stick: where
  // the top moves more, a smoother bit adds to the evidence (no other effect moves the top).
  const double top_moves = std::max(-Z(m, r, "top_rpm std"), -0.5 * Z(m, r, "top_rpm fast_low_std"));
  const double smoother = top_moves > kWeakEvidence ? BitRunsSmoother(m, r) : 0.0;
  const double z = top_moves + smoother;
  if (z > kWeakEvidence)
    e.strength = z,
    e.evidence = "the top speed moves more than the model's drive lets it: " + Describe(m, r, "top_rpm std") +
                 (smoother > 0 ? "; and the bit runs smoother: " + Describe(m, r, "bit_rpm std") : "");
  // Where the recording's own drive law reads softer than the case's, the fit starts from it (train rec04, rec18:
  // kp 460 and 392 N m s/rad read, 590 and 376 simulated; train rec30 and rec32, where a DC motor adds its K^2/R,
  // named Kelvin-Voigt damping before and their soft drive from it).
  const DriveLaw& law = r.drive;
  if (const double z_law = SofterDriveEvidence(s, law); z_law > 0) {
    for (int k : {0, 1})
      e.parameters[k].start = std::clamp(k == 0 ? law.proportional : law.integral, e.parameters[k].lower,
                                         e.parameters[k].upper);
    const std::string read = "the drive's law read off the recording at " + Fixed(law.frequency_hz, 2) +
                             " Hz (coherence " + Fixed(law.coherence, 3) + "): kp " +
                             Significant(law.proportional, 3) + " N m s/rad, ki " + Significant(law.integral, 3) +
                             " N m/rad, " + Significant(z_law, 3) + " standard deviations softer than the case's";
    e.evidence = e.strength > 0 ? e.evidence + "; " + read : read;
    e.strength = std::max(e.strength, z_law);
  }
  // A law read as the case's own (within kSofterDrive either way) measures the drive: a softer one is refuted, however
  // well it imitates damping (train rec19: a soft drive held out 0.315 against its true Kelvin-Voigt damping's 0.405,
  // the recorded law 0.95 of the case's at coherence 0.97).
  if (const double ratio = CaseOverRecordedStiffness(s, law); ratio < kSofterDrive && ratio > 1 / kSofterDrive)
    e.refuted = "the drive's law read off the recording at " + Fixed(law.frequency_hz, 2) + " Hz (coherence " +
                Fixed(law.coherence, 3) + ": kp " + Significant(law.proportional, 3) + " N m s/rad, ki " +
                Significant(law.integral, 3) + " N m/rad) is the case's within a factor " +
                Significant(kSofterDrive, 2);
  return e;
}

// side_friction: more torque at the top than the model needs to turn the same bit, torque lost along the string.
Effect ProposeSideFriction(const StringFacts& s, const FeatureSet& m, const FeatureSet& r) {
  const Pipe& pipe = s.pipe;
  const double recorded_kNm = r.Value("top_torque_kNm mean");
  const double missing_kNm = recorded_kNm - m.Value("top_torque_kNm mean");
  // The string cannot lose more torque on its way down than the top drive puts in: over a long window the mean
  // top torque is the bit's plus the string's drag and friction, so the friction is at most that mean over the
  // length (a box of that size, not of 10 N m/m, is what the fit's first steps explore).
  const double most = std::isfinite(recorded_kNm) && recorded_kNm > 0 ? 1000 * recorded_kNm / pipe.length : 10.0;
  const double estimate =
      std::min(std::isfinite(missing_kNm) && missing_kNm > 0 ? 1000 * missing_kNm / pipe.length : 0.5, 0.9 * most);
  Effect e{"side_friction", "Coulomb friction torque along the string (per metre)", {}, nullptr, 0, ""};
  e.parameters = {{"torque_per_m_Nm", "N m/m", 0.0, most, false, estimate}};
  e.parameters[0].lower_is_physical = true;
  e.apply = [](nlohmann::json& d, const std::vector<double>& v) {
    d["model"]["string"]["side_friction"] = {{"torque_per_m_Nm", v[0]}, {"from_m", 0.0}};
  };
  const double z = -Z(m, r, "top_torque_kNm mean");
  if (z > kWeakEvidence)
    e.strength = z, e.evidence = "more torque at the top than in the model: " + Describe(m, r, "top_torque_kNm mean") +
                                 ", first estimate " + Fixed(estimate, 2) + " N m/m over the string";
  return e;
}

// stribeck: the bit sticks more, or its speed swings more, than with Coulomb friction: friction that weakens
// with speed.
Effect ProposeStribeck(const StringFacts& s, const FeatureSet& m, const FeatureSet& r) {
  const double mu = s.mu;
  Effect e{"stribeck", "bit friction that weakens with speed (Stribeck)", {}, nullptr, 0, ""};
  e.parameters = {{"static_mu", "-", 1.02 * mu, 3 * mu, false, 1.6 * mu},
                  {"velocity_rad_s", "rad/s", 0.5, 40, true, 5}};
  e.parameters[0].lower_is_physical = true;  // static friction just above kinetic: no weakening
  e.apply = [](nlohmann::json& d, const std::vector<double>& v) {
    d["model"]["rock"]["stribeck"] = {{"static_mu", v[0]}, {"velocity_rad_s", v[1]}};
  };
  const double z = -std::min(Z(m, r, "stick_fraction") - 1, 0.0) - std::min(Z(m, r, "bit_rpm std"), 0.0);
  if (z > kWeakEvidence)
    e.strength = z,
    e.evidence = "the bit sticks or swings more than in the model: " + Describe(m, r, "stick_fraction") + "; " +
                 Describe(m, r, "bit_rpm std");
  return e;
}

// axial_coupling_off: the weight on bit hardly moves while the coupled model's swings.
Effect ProposeAxialCouplingOff(const StringFacts&, const FeatureSet& m, const FeatureSet& r) {
  Effect e{"axial_coupling_off",
           "no axial-torsional coupling: the weight on bit held, the depth of cut following the rock",
           {},
           nullptr,
           0,
           ""};
  e.apply = [](nlohmann::json& d, const std::vector<double>&) { d["model"]["axial_coupling"] = false; };
  const double z = Z(m, r, "wob_kN std");
  const double level = r.Value("wob_kN std") / std::max(m.Value("wob_kN std"), 1e-12);
  if (z > kWeakEvidence && level < 0.5)
    e.strength = z,
    e.evidence = "the weight on bit is steady where the coupled model's swings: " + Describe(m, r, "wob_kN std");
  return e;
}

// bha: the recorded bit runs smoother (less sticking, smaller swings) than the lumped-BHA model's, while the
// weight on bit still moves: a distributed collar section, whose inertia replaces most of the lumped body.
Effect ProposeBha(const StringFacts& s, const FeatureSet& m, const FeatureSet& r) {
  const Pipe& pipe = s.pipe;
  const double bit_mass = s.bit_mass;
  const double bit_inertia = s.bit_inertia;
  const double collar_od = 0.1715, collar_id = 0.0714;  // 6.75 in x 2.8125 in, the common collar
  const double collar_polar = kPi / 32 * (std::pow(collar_od, 4) - std::pow(collar_id, 4));
  const double estimate = std::clamp(bit_inertia / (pipe.density * collar_polar), 30.0, 400.0);
  Effect e{"bha", "a distributed drill-collar section above the bit (6.75 x 2.8125 in)", {}, nullptr, 0, ""};
  e.parameters = {{"length_m", "m", 30, 400, false, estimate}};
  e.apply = [collar_od, collar_id, bit_mass, bit_inertia](nlohmann::json& d, const std::vector<double>& v) {
    d["model"]["string"]["bha"] = {
        {"length_m", v[0]}, {"outer_diameter_m", collar_od}, {"inner_diameter_m", collar_id}};
    // The lumped body keeps the bit and near-bit sub, taken as 5 % of the lumped BHA.
    d["model"]["bit"]["inertia_kgm2"] = 0.05 * bit_inertia;
    d["model"]["bit"]["mass_kg"] = 0.05 * bit_mass;
  };
  const double z = BitRunsSmoother(m, r);
  const bool wob_moves = !(Z(m, r, "wob_kN std") > 3 && r.Value("wob_kN std") < 0.5 * m.Value("wob_kN std"));
  if (z > kWeakEvidence && wob_moves)
    e.strength = z,
    e.evidence = "the recorded bit runs smoother than the model's: " + Describe(m, r, "stick_fraction") + "; " +
                 Describe(m, r, "bit_rpm std");
  return e;
}

// kelvin_voigt: the fast part of the bit speed and of the surface torque (its upper half) is weaker than in the
// model: damping that grows with frequency.
Effect ProposeKelvinVoigt(const StringFacts&, const FeatureSet& m, const FeatureSet& r) {
  Effect e{"kelvin_voigt", "Kelvin-Voigt (strain-rate) damping of the pipe in torsion", {}, nullptr, 0, ""};
  e.parameters = {{"eta_s", "s", 1e-3, 0.2, true, 0.02}};
  e.apply = [](nlohmann::json& d, const std::vector<double>& v) { d["model"]["string"]["kelvin_voigt_s"] = v[0]; };
  const double z = std::max(Z(m, r, "bit_rpm fast_std"), 0.0) + std::max(Z(m, r, "top_torque_kNm fast_high_std"), 0.0);
  if (z > kWeakEvidence)
    e.strength = z, e.evidence = "less fast motion than in the model: " + Describe(m, r, "bit_rpm fast_std") + "; " +
                                 Describe(m, r, "top_torque_kNm fast_high_std");
  return e;
}

// How far the recorded drive law's phase lags the case's PI at the law's frequency (rad), where the law is identified
// and reads as the case's drive (within kSofterDrive of its stiffness: another drive's phase says nothing of a motor
// behind this one); NaN otherwise.
double LagBehindCasePi(const StringFacts& s, const DriveLaw& law) {
  const double ratio = CaseOverRecordedStiffness(s, law);
  if (!(ratio < kSofterDrive && ratio > 1 / kSofterDrive)) return std::nan("");
  const double w = 2 * kPi * law.frequency_hz;
  return std::atan2(-s.drive_ki / w, s.drive_kp) - law.Phase();
}

// dc_motor: the drive's torque follows its speed error with a lag (armature inductance) and an extra damping
// K^2/R: above the lag's corner the top is held by its inertia alone, so the surface torque's fast content moves
// between the halves of the fast band (train rec05, with the KEY's motor: 2-4.5 Hz 0.21 kN m against 0.11 without,
// 4.5-10 Hz 0.04 against 0.09), and its spread differs.
Effect ProposeDcMotor(const StringFacts& s, const FeatureSet& m, const FeatureSet& r) {
  Effect e{"dc_motor", "a DC motor behind the speed controller (armature lag, back-EMF damping)", {}, nullptr, 0, ""};
  e.parameters = {{"electrical_time_constant_s", "s", 0.005, 1.0, true, 0.1},
                  {"back_emf_damping_Nms_per_rad", "N m s/rad", 100, 1e6, true, 1e4}};
  e.parameters[0].lower_is_physical = true;  // 5 ms: no armature lag at the torsional modes' time scales
  e.apply = [](nlohmann::json& d, const std::vector<double>& v) {
    constexpr double k = 30;  // N m/A: only K^2/R and La/R shape the torque, so K is fixed and R, La follow
    const double resistance = k * k / v[1];
    d["model"]["top"]["motor"] = {
        {"motor_constant_Nm_per_A", k}, {"resistance_ohm", resistance}, {"inductance_H", v[0] * resistance}};
  };
  const double z =
      std::max(std::abs(Z(m, r, "top_torque_kNm fast_low_std")), std::abs(Z(m, r, "top_torque_kNm fast_high_std"))) +
      0.5 * std::abs(Z(m, r, "top_torque_kNm std"));
  if (z > kWeakEvidence)
    e.strength = z,
    e.evidence = "the surface torque's dynamics differ: " + Describe(m, r, "top_torque_kNm fast_low_std") + "; " +
                 Describe(m, r, "top_torque_kNm fast_high_std") + "; " + Describe(m, r, "top_torque_kNm std");
  // The recorded law read behind the case's PI: an armature of time constant tau lags the controller's output by
  // atan(w tau) (the back-EMF term K^2 / R is small beside the PI's gains and adds no phase). The lag in standard
  // deviations of the estimate's phase is the evidence, and tan(lag) / w the fit's first tau.
  const DriveLaw& law = r.drive;
  double z_lag = 0, tau = 0;
  std::string read;
  const double lag = LagBehindCasePi(s, law);
  if (lag > 0 && lag < kPi / 2) {
    z_lag = std::min(kMostEvidence, lag / law.PhaseStd());
    tau = std::tan(lag) / (2 * kPi * law.frequency_hz);
    read = "the drive's torque read off the recording at " + Fixed(law.frequency_hz, 2) + " Hz (coherence " +
           Fixed(law.coherence, 3) + ") lags the case's PI by " + Fixed(lag * 180 / kPi, 1) + " degrees, " +
           Significant(z_lag, 3) + " standard deviations (an armature time constant of " + Significant(tau, 3) + " s)";
  }
  // A law that is not the case's PI (behind a soft speed loop) has no known PI to lag behind. Where it is read at
  // several frequencies, a PI behind a lag fitted to them (FitLaggedPi) reads the armature whatever the loop's gains
  // (train rec30: 15 bins, tau 0.111 s against the KEY's 0.113, P 20 600 N m s/rad: the soft loop's kp 598 plus
  // K^2 / R 20 209). Where the law is the case's, its lag behind the known PI above is the better-determined reading
  // (one parameter, not three). The evidence is the F-test's p-value as the standard deviations of a one-sided normal
  // test with that p-value; only a strong one is a reading (a stick-slip string's drive is not a linear system, and
  // its soft laws scatter into lags of 0.2-0.5 s at p 0.02-0.05: dev rec05, train rec18), and a lag on the search's
  // upper end is not an estimate.
  const LaggedPi lagged = std::isnan(lag) ? FitLaggedPi(law) : LaggedPi{};
  if (lagged.bins >= 3 && lagged.p_value < 0.5 && lagged.lag_s < 1.0) {
    const boost::math::normal standard;
    const double z = std::min(
        kMostEvidence, boost::math::quantile(boost::math::complement(standard, std::max(lagged.p_value, 1e-300))));
    if (z > kStrongEvidence) {
      z_lag = z, tau = lagged.lag_s;
      read = "the drive's torque read off the recording at " + std::to_string(lagged.bins) +
             " frequencies is a PI (kp " + Significant(lagged.proportional, 3) + " N m s/rad, ki " +
             Significant(lagged.integral, 3) + " N m/rad) behind a lag of " + Significant(tau, 3) + " +- " +
             Significant(lagged.lag_std_s, 2) +
             " s (an armature), against the PI alone F = " + Significant(lagged.f_statistic, 3) +
             ", p = " + Significant(lagged.p_value, 2) + ", " + Significant(z, 3) + " standard deviations";
    }
  }
  if (z_lag > kWeakEvidence) {
    e.parameters[0].start = std::clamp(tau, e.parameters[0].lower, e.parameters[0].upper);
    e.evidence = e.strength > 0 ? e.evidence + "; " + read : read;
    e.strength = std::max(e.strength, z_lag);
  }
  return e;
}

// unbalance: a line at the bit's rotation frequency in the weight on bit or the bit speed, above the model's.
Effect ProposeUnbalance(const StringFacts&, const FeatureSet& m, const FeatureSet& r) {
  const double lateral_mass = 3000;  // kg: the collars between stabilizers that whirl (assumed, not fitted)
  Effect e{"unbalance", "a BHA mass unbalance whirling at the bit (Jeffcott rotor)", {}, nullptr, 0, ""};
  e.parameters = {{"unbalance_kg_m", "kg m", 0.5, 200, true, 10}, {"lateral_frequency_Hz", "Hz", 0.5, 10, true, 2.5}};
  e.apply = [lateral_mass](nlohmann::json& d, const std::vector<double>& v) {
    constexpr double eccentricity = 0.05, damping_ratio = 0.05;
    const double k = lateral_mass * std::pow(2 * kPi * v[1], 2);
    d["model"]["bit"]["unbalance"] = {{"lateral_mass_kg", lateral_mass},
                                      {"lateral_stiffness_N_per_m", k},
                                      {"lateral_damping_Ns_per_m", 2 * damping_ratio * std::sqrt(k * lateral_mass)},
                                      {"unbalance_mass_kg", v[0] / eccentricity},
                                      {"eccentricity_m", eccentricity}};
  };
  // Its signature is a line at the rotation frequency; but the whirl also drains the torsional oscillation (the
  // lateral damping acts on the bit's rotation through the unbalance), so a bit that runs smoother than the
  // model's points to it as well as to a BHA.
  const double line = -std::min({Z(m, r, "wob_kN rotation_amplitude"), Z(m, r, "bit_rpm rotation_amplitude"), 0.0});
  const double smoother = BitRunsSmoother(m, r);
  const double z = std::max(line, smoother);
  if (z > kWeakEvidence)
    e.strength = z,
    e.evidence = line >= smoother
                     ? "a line at the bit's rotation frequency: " + Describe(m, r, "wob_kN rotation_amplitude") + "; " +
                           Describe(m, r, "bit_rpm rotation_amplitude")
                     : "the recorded bit runs smoother than the model's (a whirl drains "
                       "torsional energy): " +
                           Describe(m, r, "stick_fraction") + "; " + Describe(m, r, "bit_rpm std");
  return e;
}

// sensor_delay: the downhole channels arrive through telemetry, later than the surface's. Seen whole in the weight
// on bit's lag behind the hook load (broadband: the model's is the axial travel time, the recording's adds the
// delay), and modulo the bit's period in the bit speed's lag behind the surface torque.
Effect ProposeSensorDelay(const StringFacts&, const FeatureSet& m, const FeatureSet& r) {
  const double period = r.Value("period_s");
  double shift = r.Value("torque_to_bit_lag_s") - m.Value("torque_to_bit_lag_s");
  if (std::isfinite(shift) && std::isfinite(period) && shift < 0) shift += period;  // lags are modulo a period
  const double axial_shift = r.Value("hook_to_wob_lag_s") - m.Value("hook_to_wob_lag_s");
  const double axial_z = -Z(m, r, "hook_to_wob_lag_s");  // > 0: the recorded weight on bit comes later
  const double torsional_z = std::abs(Z(m, r, "torque_to_bit_lag_s"));
  const bool axial = axial_z > kWeakEvidence && !(torsional_z > axial_z);
  const double first = axial ? axial_shift : std::isfinite(shift) ? shift : 1.0;
  Effect e{"sensor_delay", "telemetry delay of the downhole channels (bit speed, weight on bit)", {}, nullptr, 0, ""};
  e.parameters = {{"delay_s", "s", 0.0, kMaxTelemetryDelayS, false, std::clamp(first, 0.0, kMaxTelemetryDelayS)}};
  e.parameters[0].lower_is_physical = true;
  e.apply = [](nlohmann::json& d, const std::vector<double>& v) {
    if (!d.contains("sensors")) return;
    for (auto& [channel, sensor] : d["sensors"]["channels"].items())
      if (Downhole(channel)) sensor["delay_s"] = v[0];
  };
  if (axial)
    e.strength = axial_z, e.evidence = "the weight on bit follows the hook load " + Fixed(axial_shift, 2) +
                                       " s later than in the model: " + Describe(m, r, "hook_to_wob_lag_s");
  else if (torsional_z > kWeakEvidence)
    e.strength = torsional_z, e.evidence = "the bit speed follows the surface torque " + Fixed(shift, 2) +
                                           " s later than in the model: " + Describe(m, r, "torque_to_bit_lag_s");
  // The virtual downhole sensor's reading (features.hpp): the recorded bit speed is its estimate from the surface
  // channels, late by the delay (on the fit window six of the seven telemetry delays of ../shared read to the sample,
  // none where there is none).
  // Where found, it is the first value, and its length in the lags the reading resolves the evidence.
  if (const estimation::TelemetryLag& lag = r.telemetry; lag.found) {
    e.parameters[0].start = std::clamp(lag.lag_s, 0.0, kMaxTelemetryDelayS);
    const std::string read = "the recorded bit speed is the virtual sensor's estimate from the surface channels " +
                             Fixed(lag.lag_s, 2) + " s late (correlation " + Fixed(lag.correlation, 3) +
                             " against " + Fixed(lag.correlation_at_zero, 3) + " without delay)";
    e.evidence = e.strength > 0 ? e.evidence + "; " + read : read;
    e.strength = std::max(e.strength, lag.lag_s / estimation::kMinTelemetryLagS);
  }
  return e;
}

// The base calibrations of a field string: the rock's contact stress, then its strength.
std::vector<Calibration> StringCalibrations(const nlohmann::json& doc) {
  std::vector<Calibration> calibrations;
  // The contact stress sets the friction's share of the bit torque, and so the mean torque (T = a W / (2 zeta) +
  // a^2 sigma l (gamma mu - 1 / zeta) / 2 in steady drilling): the levels read it.
  const double sigma_l = Number(doc, "/model/rock/sigma_l_N_per_m", 450000);
  Effect contact{
      "contact_stress", "the wear-flat contact stress sigma*l of the rock (base calibration)", {}, nullptr, 0, ""};
  contact.parameters = {{"sigma_l_N_per_m", "N/m", 0.8 * sigma_l, 1.2 * sigma_l, false, sigma_l}};
  contact.apply = [](nlohmann::json& d, const std::vector<double>& v) { d["model"]["rock"]["sigma_l_N_per_m"] = v[0]; };
  calibrations.push_back({contact, CalibrationTarget::kLevels});
  // The intrinsic specific energy: the cut's torque and weight keep the ratio a / (2 zeta) whatever eps is, so no
  // level reads it; it sets the depth of cut a weight makes and with it the regenerative gain (n a zeta eps), which
  // decides how strongly steady drilling is unstable: the stick fraction, the spreads, the axial motion read it.
  const double eps = Number(doc, "/model/rock/intrinsic_specific_energy_Pa", 5e7);
  Effect strength{"rock_strength", "the rock's intrinsic specific energy eps (base calibration)", {}, nullptr, 0, ""};
  strength.parameters = {{"intrinsic_specific_energy_Pa", "Pa", 0.8 * eps, 1.2 * eps, false, eps}};
  strength.apply = [](nlohmann::json& d, const std::vector<double>& v) {
    d["model"]["rock"]["intrinsic_specific_energy_Pa"] = v[0];
  };
  calibrations.push_back({strength, CalibrationTarget::kMotion});
  return calibrations;
}

std::vector<Effect> StringEffects(const nlohmann::json& doc, const FeatureSet& m, const FeatureSet& r) {
  StringFacts s;
  s.pipe = PipeOf(doc);
  s.mu = Number(doc, "/model/rock/mu", 0.6);
  s.bit_mass = Number(doc, "/model/bit/mass_kg", 20000);
  s.bit_inertia = Number(doc, "/model/bit/inertia_kgm2", 90);
  s.first_mode = kPi * s.pipe.wave_speed / (2 * s.pipe.length);
  s.top_inertia = Number(doc, "/model/top/inertia_kgm2", std::nan(""));
  const bool motor = doc.contains(nlohmann::json::json_pointer("/model/top/motor"));
  s.drive_kp = motor ? std::nan("") : Number(doc, "/model/top/kp_Nms_per_rad", std::nan(""));
  s.drive_ki = motor ? std::nan("") : Number(doc, "/model/top/ki_Nm_per_rad", std::nan(""));
  // This order stands where the loop's stable sort by evidence finds a tie.
  std::vector<Effect> effects;
  effects.push_back(ProposeSoftTopdrive(s, m, r));
  effects.push_back(ProposeSideFriction(s, m, r));
  effects.push_back(ProposeStribeck(s, m, r));
  effects.push_back(ProposeAxialCouplingOff(s, m, r));
  effects.push_back(ProposeBha(s, m, r));
  effects.push_back(ProposeKelvinVoigt(s, m, r));
  effects.push_back(ProposeDcMotor(s, m, r));
  effects.push_back(ProposeUnbalance(s, m, r));
  effects.push_back(ProposeSensorDelay(s, m, r));
  return effects;
}

}  // namespace

DiagnosableKind StringDiagnosis() { return {"axial_torsional", StringEffects, StringCalibrations}; }

}  // namespace drillwave::diagnosis
