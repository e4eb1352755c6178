#pragma once
// What a model can be asked to reproduce of a recording (DESIGN.md §5, issue 13 item 3). Stick-slip is chaotic: two
// runs that differ by a rounding error drift out of phase within a few periods, so a point-by-point error cannot be
// fitted. Statistics over a window are reproducible: levels, spreads, the content of each channel between 2 and
// 10 Hz, the time the bit spends stuck, the oscillation period, the lag between the surface torque and the bit speed
// (modulo the period), the lag of the weight on bit behind the hook load (broadband: a telemetry delay shows whole),
// and the correlation of their fast motions' envelopes at fixed lags (the shape that lag is the peak of). Each
// feature carries a scale — how much it varies between the window's parts, with a floor — and a model's difference
// is counted in those scales, so that a model which is the recording's twin scores about 1 whatever the regime.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/diagnosis/drive_law.hpp"
#include "drillwave/diagnosis/recording.hpp"
#include "drillwave/estimation/metrics.hpp"

namespace drillwave::diagnosis {

// "hook_wob_envelope_corr_at_+1.5s": the feature of the envelopes' correlation at a lag (the weight on bit later).
inline constexpr const char* kEnvelopeCorrelation = "hook_wob_envelope_corr_at_";
std::string EnvelopeCorrelationName(double lag_s);
// Below this peak (over the lags, in absolute value) the recording's envelopes share too little (a bit that does not
// bounce, rec01: 0.21; rec04's bounce: 0.68) for their correlogram to be asked of a model: it is then not counted.
inline constexpr double kMinEnvelopeCorrelation = 0.3;

struct Feature {
  std::string name;   // "<channel> mean", "<channel> std", "<channel> fast_std", "stick_fraction", ...
  double value = 0;   // NaN where the window does not define it (no oscillation: no period)
  double scale = 1;   // > 0; the size of a difference that is within the feature's own variability
};

struct FeatureSet {
  double begin_s = 0, end_s = 0;
  std::vector<Feature> features;
  // The top drive's law read off a recording's window where its speed set-point is known (the diagnosis loop's
  // PrepareRecording): evidence for the proposals, not a feature (no distance counts it, no model run measures it).
  DriveLaw drive;
  // How late the recorded bit speed arrives behind the virtual downhole sensor's estimate of it from the surface
  // channels (a telemetry delay), read on the fit window likewise.
  estimation::TelemetryLag telemetry;
  const Feature* Find(const std::string& name) const;  // nullptr if absent
  double Value(const std::string& name) const;         // NaN if absent
};

// With a measured torque on bit (FeatureOptions::bit_torque): the friction's slope, torque on bit per unit of bit
// speed while slipping, and the drive's droop, top speed per unit of torque on bit (units of the recording's channels).
inline constexpr const char* kFrictionSlope = "friction_slope";
inline constexpr const char* kDriveDroop = "drive_droop";
// The suffixes of a channel's fast spreads (FeatureOptions::fast_window_s): the whole fast band, or for the drive's
// channels its two halves.
inline constexpr const char* kFast = " fast_std";
inline constexpr const char* kFastLow = " fast_low_std";
inline constexpr const char* kFastHigh = " fast_high_std";

struct FeatureOptions {
  std::string bit_speed = "bit_rpm";     // the channel read for sticking, period and lag (skipped if absent)
  std::string top_speed = "top_rpm";
  std::string top_torque = "top_torque_kNm";
  // A measured torque on bit (a lab rig's; empty: none). With it two laws are read off the recording as a laboratory
  // would calibrate them: the friction's torque-speed slope while slipping (velocity weakening) and the drive's
  // speed-torque slope (its droop, the torque on bit standing for the shaft's), each a least-squares line.
  std::string bit_torque;
  std::string hook_load = "hookload_kN";  // with weight_on_bit: the axial lag (skipped if either is absent)
  std::string weight_on_bit = "wob_kN";
  double min_axial_lag_s = -3, max_axial_lag_s = 8;  // the lags looked at (at most a third of the window)
  // Below this peak correlation the hook load and weight on bit share too little (a bit drilling smoothly, axial
  // coupling off) for the peak to stand out of the chance correlations of ~10^3 lags: no lag (NaN).
  double min_axial_correlation = 0.15;
  // The envelopes' correlation (hook load against weight on bit) read at these lags: the shape of the correlogram,
  // which repeats with the axial round trip, so that its highest peak alone is ambiguous in a steady bounce; read at
  // fixed lags it is not, and a telemetry delay of the weight on bit shifts it whole (rec04: 2.1 s).
  std::vector<double> envelope_lags_s = {-1, -0.5, 0, 0.5, 1, 1.5, 2, 2.5};
  double envelope_window_s = 0.5;  // the rms of the fast part over this window
  double envelope_detrend_s = 4;   // less its moving average over this window
  int parts = 4;                         // the window's parts whose spread sets each feature's scale
  double smoothing_s = 0.05;             // centred moving average before levels and spreads are read
  // "fast": what a moving average over this window removes (the envelopes and the axial lag read it); "fast_std" is
  // the rms of the content between 1 / fast_window_s and 1 / (2 smoothing_s): 2 to 10 Hz. The drive's channels (top
  // speed and torque) are read in the band's two halves of equal log-width instead (split at their geometric mean,
  // 4.5 Hz: "fast_low_std", "fast_high_std"): a drive's dynamics move content between them (a DC motor's armature lag
  // raises the surface torque's 2-4.5 Hz content and lowers its 4.5-10 Hz content: train rec05, where the whole
  // band's rms moved by less than either). The bit's channels keep the whole band: their fast content hangs on
  // bit-rock details (the rock's heterogeneity, an axial resonance) that a base model reproduces only roughly, and
  // read in halves they made damping a false explanation (dev rec01, rec07: Kelvin-Voigt beside side friction).
  double fast_window_s = 0.5;
  double stuck_fraction = 0.05;          // stuck while |bit speed| < max(stuck_floor, fraction * mean |speed|)
  double stuck_floor = 2.0;              // in the bit speed's unit
  double max_period_s = 20;              // longest oscillation period looked for

  // Finite axial lags in order and a correlation in [0, 1]; finite envelope lags; windows, smoothing and max_period_s
  // > 0 with fast_window_s above 2 smoothing_s (a band of some width); parts >= 1; stuck_fraction in [0, 1) and
  // stuck_floor >= 0 (core/validity.hpp). The channel names are the recording's to have or not.
  bool IsValid(std::string* error) const;
};

// The fast band and where it is split in two (FeatureOptions::fast_window_s), in Hz.
struct FastBands {
  double low_hz, split_hz, high_hz;
};
FastBands FastBandsOf(const FeatureOptions& options);

// Features of every channel of `recording` over [begin_s, end_s] (the samples inside). Throws ParameterError("window")
// for fewer than 8 samples per part, ParameterError for options that are not valid.
FeatureSet MeasureFeatures(const Recording& recording, double begin_s, double end_s, const FeatureOptions& options = {});

// Mean over the recording's defined features of ((model - recording) / scale)^2; a feature the recording defines
// and the model does not (no oscillation at all) counts as 9, three scales off, and so does an axial lag more than
// three scales off (another peak of the correlation). The envelopes' correlogram counts as one feature, the mean of
// its lags' squared differences, where the recording's peaks at kMinEnvelopeCorrelation or more.
double FeatureDistance(const FeatureSet& model, const FeatureSet& recording);

// How far FeatureDistance(a, recording) - FeatureDistance(b, recording) moves with the recording's own noise, as a
// standard deviation, for noise of `noise_variance` squared scales in each feature. Both models are compared with the
// same recording, so its noise n moves each term by the same amount: with z = b - n, z_a^2 - z_b^2 = b_a^2 - b_b^2 -
// 2 n (z_a - z_b), linear in n with a slope twice the models' own difference. Two models that agree where the recording
// is noisy are told apart by far less than either error's own spread. Terms that do not move with the recording (a
// feature one model lacks, an axial lag past its cap) add nothing; the correlogram's lags count as one noise, fully
// correlated (the larger bound).
double DistanceDifferenceStd(const FeatureSet& a, const FeatureSet& b, const FeatureSet& recording,
                             double noise_variance);

// The largest difference between two models over the recording's features, in the recording's scales: a feature one
// model defines and the other does not counts as 3; the envelopes' correlogram as one feature, the rms over its lags.
// Below 1 the two are the same model at the resolution the features claim.
double LargestDifferenceInScales(const FeatureSet& a, const FeatureSet& b, const FeatureSet& recording);

// The envelopes' correlogram as the distance counts it: the rms over its lags of the model's difference in scales,
// and the lag where it is largest; NaN (and lag NaN) where the recording's correlogram does not count (its peak below
// kMinEnvelopeCorrelation) or either set lacks it.
struct CorrelogramDifference {
  double rms_scales = 0, largest_at_lag_s = 0;
};
CorrelogramDifference CompareCorrelograms(const FeatureSet& model, const FeatureSet& recording);

// The number of independent features a recording's set defines (its correlogram's lags counted once, where it counts):
// the K of the distance.
double FeatureCount(const FeatureSet& features);

// The share of [begin_s, end_s] in which the bit is off the bottom: its weight on bit, averaged over smoothing_s,
// below kOffBottomLevel of the window's mean |weight on bit|. NaN without a weight-on-bit channel. Throws
// ParameterError for options that are not valid.
inline constexpr double kOffBottomLevel = 0.05;
double OffBottomShare(const Recording& recording, double begin_s, double end_s, const FeatureOptions& options = {});

// The white measurement noise of a sampled channel, from its second differences (robust: 1.4826 MAD / sqrt 6), so
// that slow physics (ramps, oscillations well below the sampling rate) does not count as noise.
double NoiseStd(const std::vector<double>& samples);

nlohmann::json FeatureSetToJson(const FeatureSet& model, const FeatureSet& recording);

}  // namespace drillwave::diagnosis
