#pragma once
// The top drive's speed law read off a recording, as a control engineer identifies a loop in operation: the recorded
// drive torque (the controller's or motor's output, BASELINE.md) against the speed error (set-point less the measured
// top speed), as a transfer function at the frequency where the surface torque oscillates most. A PI law reads
// H(i w) = kp - i ki / w there; a motor behind it adds its back-EMF damping K^2 / R to kp and a lag. The estimate is
// the cross-spectral H1 = S_Te / S_ee over Hann-windowed segments (Bendat & Piersol, Random Data, ch. 9): noise in
// the torque averages out, noise in the speed error biases |H| low by the share (1 - coherence), and the coherence
// says whether the speed error carries the oscillation at all (a stiff drive's top-speed ripple, 0.1-0.3 rpm, lies
// under 1 % speed noise: no law can be read, and none is claimed).
#include <vector>

namespace drillwave::diagnosis {

// Below this coherence the speed error is mostly noise at the frequency (signal power under 9 times the noise's): the
// law is not identified.
inline constexpr double kMinDriveCoherence = 0.9;

struct DriveLaw {
  double frequency_hz = 0;  // where the torque's spectrum peaks, within [kDriveBandHz]
  double proportional = 0;  // Re H: torque per unit speed error, N m s/rad (a PI's kp)
  double integral = 0;      // -w Im H: torque per unit integrated speed error, N m/rad (a PI's ki)
  double coherence = 0;     // gamma^2 of torque and speed error at the frequency, in [0, 1]
  int segments = 0;         // the segments averaged
  bool Identified() const { return segments >= 2 && coherence >= kMinDriveCoherence; }
  // |H|, the drive's dynamic stiffness at the frequency (N m s/rad).
  double Stiffness() const;
  // The standard deviation of ln |H| from the averaging: sqrt(1 - gamma^2) / (gamma sqrt(2 segments)).
  double LogStiffnessStd() const;
  // arg H (rad): a PI's lies in (-pi/2, 0]; a lag behind the controller (a motor's armature) takes it lower.
  double Phase() const;
  // The standard deviation of arg H: for the H1 estimate the same as ln |H|'s (Bendat & Piersol, eq. 9.52 and 9.53).
  double PhaseStd() const { return LogStiffnessStd(); }
};

// The band looked in (Hz): torsional stick-slip and the drive's modes of kilometre strings, above a trend.
inline constexpr double kDriveBandLowHz = 0.05, kDriveBandHighHz = 3.0;

// The law over the samples with time in [begin_s, end_s], from segments of segment_s (50 % overlap) of evenly
// sampled series: speed_error_rad_s = set-point less top speed, torque_Nm the drive's output torque. A window shorter
// than two segments, or series of different lengths, give a law with no segments (not identified).
DriveLaw IdentifyDriveLaw(const std::vector<double>& time_s, const std::vector<double>& speed_error_rad_s,
                          const std::vector<double>& torque_Nm, double begin_s, double end_s,
                          double segment_s = 20);

}  // namespace drillwave::diagnosis
