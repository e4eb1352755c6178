#pragma once
// Sensors: every output channel as it would be recorded. A simulated channel is exact; a recording is not: surface
// sensors are filtered, downhole sensors reach the surface through telemetry (mud pulse ~6.6 s, acoustic ~2.2 s in
// the chapter seed, sect. 2.7), sampled and held at the telemetry rate, with noise S(t), N(t). A case's "sensors"
// block adds "<channel>_measured" beside each named channel, so a model can be compared with a recording channel by
// channel as the recording was made:
//   "sensors": {"seed": 1, "channels": {"bit_rpm": {"delay_s": 6.6, "hold_s": 1, "noise_std": 2},
//                                       "top_torque_Nm": {"time_constant_s": 0.05, "window_s": 0.01}}}
// The chain, in the order a measurement passes it: first-order low-pass (time constant), averaging window (each
// reading the mean over the window_s ending at it, as a data logger averages its samples), transport delay,
// sample-and-hold (samples taken every hold_s, each received delay_s later), additive Gaussian noise (one draw per
// held sample, or per output sample without hold), seeded so that a run is reproducible.
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
  double noise_std = 0;        // in the channel's unit
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
