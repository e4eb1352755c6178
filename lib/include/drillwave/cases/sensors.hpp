#pragma once
// Sensors: every output channel as it would be recorded. A simulated channel is exact; a recording is not: surface
// sensors are filtered, downhole sensors reach the surface through telemetry (mud pulse ~6.6 s, acoustic ~2.2 s in
// the chapter seed, sect. 2.7), sampled and held at the telemetry rate, with noise S(t), N(t). A case's "sensors"
// block adds "<channel>_measured" beside each named channel, so a model can be compared with a recording channel by
// channel as the recording was made:
//   "sensors": {"seed": 1, "channels": {"bit_rpm": {"delay_s": 6.6, "hold_s": 1, "noise_std": 2},
//                                       "wob_N": {"delay_s": 6.6, "bits": 12, "range": [0, 3e5],
//                                                 "bit_rate_bps": 2, "downhole_noise_std": 500, "noise_std": 50},
//                                       "top_torque_Nm": {"time_constant_s": 0.05, "window_s": 0.01}}}
// The chain, in the order a measurement passes it: first-order low-pass (time constant), averaging window (each
// reading the mean over the window_s ending at it, as a data logger averages its samples), transport delay,
// sample-and-hold (samples taken every hold_s, each received delay_s later), additive Gaussian noise (one draw per
// held sample, or per output sample without hold), seeded so that a run is reproducible.
// Telemetry as the chapter describes it (sect. 2.7, Fig. 2.4): the downhole sensor's noise S(t) is added before the
// value is coded, the code is `bits` bits over a range [lo, hi] (2^bits levels, the nearest kept, clamped to the
// range), sent at bit_rate_bps (1-2 bit/s mud pulse, ~6 bit/s acoustic: a sample every bits / bit_rate s, taken
// when its frame starts and decoded when the frame ends, delay_s later), and the receiver's noise N(t) (noise_std)
// is added to the decoded value.
// The window mean is the exact integral of the channel's linear interpolant between output samples: an output
// interval of a small fraction of window_s resolves what the window averages (a 10-ms mean of 10-ms point samples is
// only a blend of two neighbours).
#include <string>
#include <vector>

#include "drillwave/cases/model_kind.hpp"
#include "drillwave/io/json_reader.hpp"

namespace drillwave::cases {

struct SensorModel {
  std::string channel;         // the simulated channel it measures
  double time_constant_s = 0;  // first-order low-pass; 0: none
  double window_s = 0;         // each reading the mean over this window ending at it; 0: point samples
  double delay_s = 0;          // transport (telemetry) delay
  double hold_s = 0;           // sample-and-hold period; 0: continuous
  double noise_std = 0;        // in the channel's unit; with coding, the receiver's N(t)
  // Coding (0 bits: none): downhole noise S(t) before it, the value quantized to 2^bits levels over [code_min,
  // code_max], a frame of bits / bit_rate_bps seconds (then hold_s is that frame).
  int bits = 0;
  double code_min = 0, code_max = 0;
  double bit_rate_bps = 0;
  double downhole_noise_std = 0;

  // The hold between samples: bits / bit_rate_bps when coded at a bit rate, else hold_s.
  bool SentInFrames() const { return bits > 0 && bit_rate_bps > 0; }
  double SamplePeriod() const { return SentInFrames() ? bits / bit_rate_bps : hold_s; }
  // The coded value of x: the nearest of the 2^bits levels from code_min to code_max (x itself without coding).
  double Quantized(double x) const;
};

struct SensorSet {
  std::vector<SensorModel> sensors;
  unsigned long long seed = 1;
  bool empty() const { return sensors.empty(); }
};

// Reads a "sensors" block (InputError names the path).
SensorSet ReadSensors(const io::JsonReader& block);

// The measured signal of one sensor for a channel sampled at times t (increasing); noise drawn from seed.
std::vector<double> Measure(const SensorModel& sensor, const std::vector<double>& t, const std::vector<double>& values,
                            unsigned long long seed);

// Appends "<channel>_measured" for every sensor and plots it beside its channel. A sensor of a channel the run does
// not have is an InputError naming /sensors/channels/<name> and the channels there are.
void ApplySensors(const SensorSet& set, RunResult& result);

}  // namespace drillwave::cases
