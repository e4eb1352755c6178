#pragma once
// The virtual downhole sensor (issue 34): the bit's speed, torque on bit, weight on bit and stuck flag estimated from
// surface signals only, with the model of a case. Two estimators, by the case's kind:
//  - a wave string (kind axial_torsional), top speed and top torque measured: downward continuation of the torsional
//    waves (wave_continuation.hpp) gives the bit's speed exactly, one travel time late; the axial channel likewise
//    from the hook load. No state to converge: an error in the start does not exist, noise is propagated.
//  - a lumped pendulum (kind two_mass), top speed measured: with a drive whose law gives its torque (a droop drive,
//    a torque drive) a hybrid observer, the drive law inverted for the bit with the stick-slip regimes
//    (hybrid_observer.hpp); with a PI drive an extended Kalman filter on the pendulum with its set-valued bit
//    friction, smoothed over a fixed lag (lumped_observer.hpp).
// Downhole channels are never read here: the metrics (metrics.hpp) compare afterwards.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/bitrock/friction.hpp"
#include "drillwave/model/schedule.hpp"

namespace drillwave::estimation {

// Surface measurements in SI units on one uniform time grid. Empty vectors: not measured.
struct SurfaceSignals {
  std::vector<double> time_s;
  std::vector<double> top_speed_rad_s;
  std::vector<double> top_torque_Nm;  // the top drive's output (motor) torque
  std::vector<double> hook_load_N;    // string tension at the hook, block weight tared
};

// The two-mass pendulum of kind two_mass, as the estimator needs it.
struct LumpedModel {
  double top_inertia_kgm2 = 0, top_damping_Nms_per_rad = 0;
  double shaft_stiffness_Nm_per_rad = 0, shaft_damping_Nms_per_rad = 0;
  double bit_inertia_kgm2 = 0, bit_damping_Nms_per_rad = 0;
  enum class Drive { kPrescribedSpeed, kPiSpeed, kTorque } drive = Drive::kPiSpeed;
  double kp = 0, ki = 0;       // PI speed controller (kPiSpeed)
  model::Schedule setpoint;    // speed [rad/s] or torque [N m] (kTorque)
  bitrock::FrictionLaw friction{bitrock::Coulomb{0, 0, 0}};  // already scaled by the weight on bit
  double weight_on_bit_N = 0;  // the case's (constant: the pendulum has no axial motion)
};

// One uniform section of a wave string (top to bottom).
struct WaveSection {
  double length_m = 0;
  double torsional_impedance = 0, torsional_speed_m_s = 0, torsional_damping_per_m = 0;  // N m s/rad, m/s, N m s/(rad m)
  double axial_impedance = 0, axial_speed_m_s = 0, axial_damping_per_m = 0;              // N s/m, m/s, N s/m^2
  int subsections = 1;
};

struct WaveStringModel {
  std::vector<WaveSection> sections;
  double top_inertia_kgm2 = 0;  // between the measured motor torque and the string
  double top_kp = 0;            // the PI drive's proportional gain [N m s/rad] (0: unknown)
  double bit_inertia_kgm2 = 0, bit_mass_kg = 0;
  double hoist_mass_kg = 0;        // the travelling block under constant hook force
  double weight_on_bit_N = 0;      // W0, the steady weight on bit the hook force is set for
  double hook_force_N = 0;         // H, the hook load set-point (0: unknown, the recording's mean is used)
};

struct EstimatorModel {
  std::string kind;  // "two_mass" or "axial_torsional"
  double nominal_speed_rad_s = 0;  // the set-point's mean over the case's run: what "stuck" is measured against
  LumpedModel lumped;              // kind two_mass
  WaveStringModel wave;            // kind axial_torsional
};

// The estimator's model from a case document that ParseCase has accepted (so fields are valid), plus an optional
// synthetic recording's sidecar already applied by CaseFromSidecar; hook_force_N from the sidecar's
// hookload_setpoint_kN when given (> 0). Throws InputError naming /model/kind for kinds without an estimator, and
// /model/... for features the estimator does not model (e.g. a two_mass friction schedule over time).
EstimatorModel EstimatorModelFromCase(const nlohmann::json& case_document, double hook_force_N = 0);

struct EstimateOptions {
  // |bit speed| below this fraction of the nominal speed counts as stuck (the same rule for the measurement).
  double stuck_fraction = 0.05;
  double stuck_threshold_rad_s = -1;  // > 0: this threshold instead (a live estimate holds the one it read first)
  // Lumped observer: the smoother's fixed lag [s]; the estimate for time t is ready at t + lag.
  double smoothing_lag_s = -1;  // < 0: the observer's own, from the model (lumped_observer.hpp)
  // The recording's time where the model's time 0 falls (a sidecar's warm-up: the case's schedules run 30 s earlier).
  double model_time_offset_s = 0;

  // stuck_fraction in [0, 1); the threshold, lag and offset finite (core/validity.hpp).
  bool IsValid(std::string* error) const;
};

struct BitEstimate {
  std::vector<double> time_s;
  // NaN where the estimate is not available (a wave string's first and last travel time).
  std::vector<double> bit_speed_rad_s, bit_speed_band_rad_s;  // band: two standard deviations
  std::vector<double> bit_torque_Nm, bit_torque_band_Nm;
  std::vector<double> wob_N, wob_band_N;
  std::vector<char> stuck;
  double stuck_threshold_rad_s = 0;
  double latency_s = 0;  // the estimate for time t needs the surface signals up to t + latency
  std::string method;
  std::vector<std::string> notes;  // how the noise levels were read, what was not estimated and why
};

// Throws InputError naming the missing signal (e.g. "top torque") when the model's estimator needs it, ParameterError
// for options that are not valid.
BitEstimate EstimateBit(const EstimatorModel& model, const SurfaceSignals& signals, const EstimateOptions& options);

}  // namespace drillwave::estimation
