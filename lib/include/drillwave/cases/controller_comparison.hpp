#pragma once
// `drillwave compare-controllers` (issue 35): one string under each top-drive law against stick-slip, side by side.
// The laws: the stiff PI as the case gives it; SoftSpeed, a soft_torque top whose PI is tuned to the stick-slip
// period the stiff PI shows (kp = Z, ki = J (2 pi / P)^2); Z-Torque, the stiff PI tracking the set-point less the
// high-passed string torque over the top section's impedance Z; wave cancellation, the top absorbing the arriving
// wave exactly (model::WaveCancellation) with the stiff PI's kp and its slow speed loop's corner at 2 pi / (10 P);
// the same law reading the wave through a low-pass of corner 2.5 times the stick-slip frequency (t_f = P / (5 pi));
// a sliding mode holding Z-Torque's command (model::SlidingMode) inside a thin boundary layer.
// Each law takes over from the stiff PI at the same instant of its stick-slip (model::Handover), so every law starts
// from the same stick-slip state; the stiff PI runs on unchanged. Per law: the linear verdict and rightmost root at
// the operating point, and over the 20-s windows after the handover the median stick-slip severity and the median
// standard deviation of the top torque, its reduction against the stiff PI's, and how long the stick-slip takes to
// die out.
//
//   ControllerComparison c = CompareControllers(document, {});  // handover at the case's statistics window
//   WriteControllerComparison(document, c, "out/controllers");   // controllers.csv, .md, .svg, case.json
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace drillwave::cases {

// A PI top drive that replaces a case's top of another kind (dissipative, prescribed speed): its inertia and gains.
struct StiffPi {
  double inertia_kgm2 = 0, kp_Nms_per_rad = 0, ki_Nm_per_rad = 0;
};

struct ControllerComparisonSpec {
  std::optional<double> handover_s;        // > 0; default: the start of the case's statistics window
  double after_s = 60;                     // >= 20 s (a severity window): the runs end this long after the handover
  std::optional<double> tuning_period_s;   // SoftSpeed's P; default: the stiff PI's stick-slip period after handover
  std::optional<double> sliding_reaching_torque_Nm;  // the sliding mode's J eta; default: 1.5 times the stiff PI's
                                                     // largest torque from 10 s before the handover on
  std::optional<StiffPi> stiff_pi;         // needed for a top that is not a PI top drive (top_drive, soft_torque, ...)
  // The drive every law runs on: its actuator delay [s] and torque limit [N m] (default: the case's top's).
  std::optional<double> actuator_delay_s, torque_limit_Nm;
  // Each law's run stops after this many integration steps and is recorded as failed (0: no limit).
  long max_steps = 0;
};

struct ControllerResult {
  std::string law;  // "stiff PI", "SoftSpeed", "Z-Torque", "wave cancellation", "filtered wave cancellation",
                    // "sliding mode"
  nlohmann::json document;       // the case it ran: the law's /model/top, the comparison's duration and window
  std::string verdict;           // stable | marginal | unstable | no steady state | not run (the sliding mode where
                                 // the stiff PI's run, which sizes it, failed)
  double rightmost_re = 0, rightmost_im = 0;  // the rightmost characteristic root [1/s, rad/s] (NaN: none)
  double severity = 0;           // median over the 20-s windows after the handover (NaN: the bit turned backwards)
  double stick_fraction = 0;     // over the same span
  double period_s = 0;           // of the stick-slip (its onsets) or else of the oscillation over it; NaN: none
  // The median over the windows of the standard deviation of the kind's top_torque_Nm: the torque the top feeds into
  // the string in torsional_wave, the drive's torque (which also turns the top drive's inertia) in axial_torsional.
  double torque_std_Nm = 0;
  double torque_reduction_pct = 0;  // 100 (1 - torque_std / the stiff PI's)
  std::optional<double> suppressed_after_s;  // handover to the end of the last stick; none: the bit still sticks
                                             // in the last 20 s (not suppressed)
  std::vector<double> time_s, bit_rpm, top_torque_Nm;  // the run from 10 s before the handover, for the figure
  std::string run_failure;  // why the run failed numerically (a blow-up); empty: it ran. The measures are then NaN
  long steps = 0;           // the run's accepted integration steps (0: it failed)
};

struct ControllerComparison {
  double handover_s = 0, end_s = 0;
  double tuning_period_s = 0;          // SoftSpeed's P
  double feedback_time_constant_s = 0; // Z-Torque's high-pass filter
  double wave_corner_rad_s = 0;        // the wave cancellation's speed loop corner k
  double wave_filter_time_constant_s = 0;  // the filtered wave cancellation's low-pass t_f = P / (5 pi)
  double sliding_reaching_torque_Nm = 0;   // the sliding mode's J eta: 1.5 times the stiff PI's largest torque
  double sliding_boundary_layer_rad_s = 0;  // its layer phi: J eta / phi = 10 times the stiff PI's kp
  double actuator_delay_s = 0;         // of the drive every law runs on
  std::vector<ControllerResult> laws;  // the stiff PI first
};

// Throws InputError for a top that has no stiff PI to compare with (naming /model/top/type, unless spec.stiff_pi
// gives one), a handover not > 0 or after_s below 20 s (naming the spec's field, handover_s or after_s), and where the
// stiff PI shows no stick-slip period to tune SoftSpeed to (naming tuning_period_s, which gives one); NumericalError
// from the stiff PI's run when SoftSpeed is tuned to it (any other run's blow-up is its result: run_failure).
ControllerComparison CompareControllers(const nlohmann::json& document, const ControllerComparisonSpec& spec);

// The case as the comparison runs it under the stiff PI (its duration, statistics window and drive), which every
// law's case shares but for the top's law: what a map over the laws' cases may address. Throws as CompareControllers
// does before its runs.
nlohmann::json StiffPiCase(const nlohmann::json& document, const ControllerComparisonSpec& spec);

// Every law again at each actuator delay (spec.actuator_delay_s replaced), with SoftSpeed's period, Z-Torque's
// filter, the wave cancellation's corner and the sliding mode's reaching torque held at the nominal comparison's: the
// drive is commissioned once and then lives with its delay. A delay equal to the nominal's reuses it. A delayed run may
// take at most kDelayedWorkFactor times the steps of the costliest nominal run: beyond, it is recorded as failed (a bit
// bouncing off the rock with 28-MN impacts once took 1e-8-s steps, whose wave histories filled 4 GB).
inline constexpr double kDelayedWorkFactor = 10;
std::vector<ControllerComparison> CompareUnderActuatorDelays(const nlohmann::json& document,
                                                             ControllerComparisonSpec spec,
                                                             const ControllerComparison& nominal,
                                                             const std::vector<double>& delays_s);

struct ControllerEnvelopes;  // controller_envelope.hpp

// What compare-controllers may add to the nominal comparison.
struct ControllerStudies {
  const ControllerEnvelopes* envelopes = nullptr;  // none: not mapped
  std::vector<ControllerComparison> delays;        // CompareUnderActuatorDelays' (empty: not studied)
};

// controllers.csv (a row per law), controllers.md (the table and how it was made), controllers.svg (bit speed and
// surface torque of every law around the handover) and case.json into out_dir, all or nothing; with the studies also
// envelopes.csv and envelopes.svg (controller_envelope.hpp) and delays.csv (a row per delay and law), their tables
// in controllers.md.
void WriteControllerComparison(const nlohmann::json& document, const ControllerComparison& comparison,
                               const std::string& out_dir, const ControllerStudies& studies = {});

}  // namespace drillwave::cases
