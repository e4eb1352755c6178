#pragma once
// The top drive's speed law read off a recording, as a control engineer identifies a loop in operation: the recorded
// drive torque (the controller's or motor's output, BASELINE.md) against the speed error (set-point less the measured
// top speed), as a transfer function at the frequency where the surface torque oscillates most. A PI law reads
// H(i w) = kp - i ki / w there; a motor behind it adds its back-EMF damping K^2 / R to kp and a lag. The estimate is
// the cross-spectral H1 = S_Te / S_ee over Hann-windowed segments (Bendat & Piersol, Random Data, ch. 9): noise in
// the torque averages out, noise in the speed error biases |H| low by the share (1 - coherence), and the coherence
// says whether the speed error carries the oscillation at all (a stiff drive's top-speed ripple, 0.1-0.3 rpm, lies
// under 1 % speed noise: no law can be read, and none is claimed).
#include <complex>
#include <limits>
#include <vector>

namespace drillwave::diagnosis {

// Below this coherence the speed error is mostly noise at the frequency (signal power under 9 times the noise's): the
// law is not identified.
inline constexpr double kMinDriveCoherence = 0.9;

// The law at one frequency of the band: H1 and the coherence there.
struct DriveLawBin {
  double frequency_hz = 0;
  std::complex<double> h;  // torque per unit speed error, N m s/rad
  double coherence = 0;
};

struct DriveLaw {
  double frequency_hz = 0;  // where the torque's spectrum peaks, within [kDriveBandHz]
  double proportional = 0;  // Re H: torque per unit speed error, N m s/rad (a PI's kp)
  double integral = 0;      // -w Im H: torque per unit integrated speed error, N m/rad (a PI's ki)
  double coherence = 0;     // gamma^2 of torque and speed error at the frequency, in [0, 1]
  int segments = 0;         // the segments averaged
  std::vector<DriveLawBin> coherent;  // every bin of the band with coherence >= kMinDriveCoherence, by frequency
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

// A PI behind a first-order lag, H(i w) = (P - i I / w) / (1 + i w tau), fitted to a law's coherent bins: the law
// of a PI speed loop driving a DC motor, P the controller's kp with the back-EMF damping K^2 / R added and tau the
// armature's La / R (V = R / K u + K W_ref, La I' = V - K w - R I, torque K I: K I (1 + s tau) = u + K^2 / R e). The
// bins are weighted by their own spread (each relative residual over sqrt(1 - gamma^2) / (gamma sqrt(2 segments)));
// P and I are linear for a given tau, which is searched on a 1-ms grid over [0, max_lag_s]. Whether the lag is there
// at all is an F-test of the fit against the PI alone (tau = 0) with 1 and 2 bins - 3 degrees of freedom: the
// residual of the lagged fit, not the coherence, measures the law's scatter (a drive in stick-slip is not a linear
// system, and its bins scatter by far more than the averaging alone explains). A law that leads or that is a PI
// reads a p-value near 1.
struct LaggedPi {
  double proportional = 0;                                     // P, N m s/rad
  double integral = 0;                                         // I, N m/rad
  double lag_s = 0;                                            // tau, s
  double lag_std_s = std::numeric_limits<double>::infinity();  // its standard error (the profile's curvature)
  int bins = 0;  // the coherent bins fitted (3 at least, or nothing is fitted)
  double f_statistic = 0;
  double p_value = 1;  // the chance of an F this large from a law without lag
};
LaggedPi FitLaggedPi(const DriveLaw& law, double max_lag_s = 1.0);

// The band looked in (Hz): torsional stick-slip and the drive's modes of kilometre strings, above a trend.
inline constexpr double kDriveBandLowHz = 0.05, kDriveBandHighHz = 3.0;

// The law over the samples with time in [begin_s, end_s], from segments of segment_s (50 % overlap) of evenly
// sampled series: speed_error_rad_s = set-point less top speed, torque_Nm the drive's output torque. A window shorter
// than two segments, or series of different lengths, give a law with no segments (not identified).
DriveLaw IdentifyDriveLaw(const std::vector<double>& time_s, const std::vector<double>& speed_error_rad_s,
                          const std::vector<double>& torque_Nm, double begin_s, double end_s,
                          double segment_s = 20);

}  // namespace drillwave::diagnosis
