#pragma once
// First look at a recording before any model is fitted (DESIGN.md §5, steps 1 and 3): sensor artefacts flagged and
// masked per channel, the bit's stuck episodes and the stretches where it slips without sticking, the stick-slip
// period, how steady the top speed is, and which channels move together. Every finding is a measured number; the
// sentences in `findings` only restate them.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/diagnosis/recording.hpp"
#include "drillwave/io/svg_plot.hpp"

namespace drillwave::diagnosis {

struct InspectOptions {
  std::string bit_speed = "bit_rpm";  // channel names
  std::string top_speed = "top_rpm";
  bool mask_artefacts = true;           // false for clean signals (a simulation): nothing is flagged
  double hampel_half_window_s = 0.1;    // windows of 2 x 0.1 s around each sample
  double hampel_threshold = 5;          // robust standard deviations that flag a sample
  double hampel_grow_threshold = 2;     // and that extend a flagged run to its flanks
  double hampel_floor_fraction = 0.05;  // and at least this fraction of the channel's median |value|
  // The bit is at rest while |speed| < max(stuck_floor, stuck_fraction * median |speed|) for stuck_min_s or more.
  double stuck_fraction = 0.05;
  double stuck_floor = 2.0;  // in the channel's unit (rpm)
  double stuck_min_s = 0.01;
  double smoothing_s = 0.05;  // centred moving average of the bit speed before regimes and periods are read
  // A stretch without a stuck episode longer than this many median stick-slip periods is reported.
  double slip_stretch_periods = 3;
  double trend_window_s = 5;
  double soft_drive_ratio = 2.5;

  // Channel names given; the Hampel filter's window and thresholds, the periods, trend window and drive ratio finite
  // and > 0; the floor fraction, stuck floor, stuck time and smoothing finite and >= 0; stuck_fraction in [0, 1)
  // (core/validity.hpp).
  bool IsValid(std::string* error) const;
};

struct ChannelArtefacts {
  std::string channel;
  int samples_flagged = 0;
  // More than kMaxArtefactShare of the samples flagged: motion (a bouncing bit's impacts), not glitches; nothing of
  // the channel is masked and `bursts` stays empty.
  bool left_whole = false;
  std::vector<Interval> bursts;  // runs of flagged samples
  int bursts_while_stuck = 0;    // bursts that overlap a stuck episode of the bit
  double raw_min = 0, raw_max = 0, clean_min = 0, clean_max = 0;
};

struct ChannelPair {
  std::string a, b;
  double correlation;  // of the cleaned channels
};

struct Inspection {
  std::string source;
  std::string bit_speed, top_speed;  // the channels read as the speeds (InspectOptions)
  double duration_s = 0, sample_interval_s = 0;
  std::vector<ChannelArtefacts> artefacts;  // one per channel
  double stuck_threshold = 0;               // in the bit channel's unit
  std::vector<Interval> stuck;              // bit at rest
  std::vector<Interval> slip_without_stick;  // long stretches between stuck episodes (and before the first / after the last)
  double stick_fraction = 0;
  double stick_slip_period_s = 0;  // median interval between stick onsets (NaN with fewer than two)
  double bit_speed_mean = 0, bit_speed_max = 0;
  double top_speed_mean = 0, top_speed_std = 0, top_speed_min = 0, top_speed_max = 0;  // cleaned
  // The top speed's fluctuation about its slow trend (running median over trend_window_s), and the sensor noise
  // estimated from successive differences (robust sigma / sqrt 2): their ratio is ~1 for a stiff drive seen
  // through white noise and grows when the drive lets the string's oscillations through.
  double top_speed_fluctuation = 0, top_speed_noise = 0, top_speed_fluctuation_ratio = 0;
  bool top_drive_soft = false;  // fluctuation ratio above InspectOptions::soft_drive_ratio
  double bit_oscillation_period_s = 0;  // median interval between upward crossings of the bit speed's mean
  std::vector<ChannelPair> correlations;  // every pair of channels, strongest first
  std::vector<std::string> findings;
  // The cleaned channels (artefacts masked), for plots and later fits.
  std::vector<std::vector<double>> cleaned;
  std::vector<std::vector<char>> masked;  // per channel, 1 where a sample was masked (replaced in `cleaned`)
};

// Throws InputError if the bit or top speed channel is missing, ParameterError for options that are not valid. Linear
// in the number of channels: with more than 24, correlations are taken with the two speeds only.
Inspection InspectRecording(const Recording& recording, const InspectOptions& options = {});

nlohmann::json InspectionToJson(const Inspection& inspection);

// The figure of plot.svg: the speeds, then the other channels, each as recorded with its masked samples as dots apart
// from the line; the stuck flag; and the bit speed zoomed on the recording's last few stick-slip cycles.
io::Figure InspectionFigure(const Recording& recording, const Inspection& inspection);

// findings.json, report.md, plot.svg (InspectionFigure), all or nothing.
void WriteInspection(const Recording& recording, const Inspection& inspection, const std::string& out_dir);

}  // namespace drillwave::diagnosis
