#include "prepared_recording.hpp"

#include <cmath>

#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/diagnosis/recording.hpp"
#include "drillwave/estimation/estimate.hpp"
#include "drillwave/model/schedule.hpp"

namespace drillwave::diagnosis::loop_internal {
namespace {
// Model outputs per sample window, for the measured window means: a bouncing bit's twin of 10-ms means from 0.5-ms
// outputs reads 0.046 held out at 5 (0.007 at 10, chance 0.535; loop_test.cpp), for about a sixth less CPU than 10.
constexpr double kOutputsPerWindow = 5;

// The map that gives the model channel `model`'s recording side, or nullptr (none, or a zero scale).
const ChannelMap* MapOf(const LoopOptions& o, const std::string& model) {
  for (const ChannelMap& map : o.maps)
    if (map.model == model && map.scale != 0) return &map;
  return nullptr;
}

// A mapped recording channel in the model's unit, times `factor` (rpm to rad/s, say).
std::vector<double> InModelUnits(const Recording& rec, const ChannelMap& map, double factor = 1) {
  std::vector<double> x = rec.Channel(map.recording);
  for (double& v : x) v *= factor / map.scale;
  return x;
}

// The drive's law on the fit window (drive_law.hpp), where the case gives the top speed's set-point and the maps give
// the recording's top speed and drive torque; a law with no segments where any is missing.
DriveLaw RecordedDriveLaw(const nlohmann::json& document, const Recording& rec, const LoopOptions& o) {
  const ChannelMap *speed = MapOf(o, "top_rpm"), *torque = MapOf(o, "top_torque_Nm");
  const nlohmann::json::json_pointer set_point("/model/top/speed_rad_s");
  if (!speed || !torque || !document.contains(set_point)) return {};
  model::Schedule schedule;
  try {
    schedule = model::Schedule::FromJson(document.at(set_point), set_point.to_string());
  } catch (const InputError&) {
    return {};  // the case's own checks report it
  }
  std::vector<double> error = InModelUnits(rec, *speed, -kRadPerSecondPerRpm);
  for (std::size_t i = 0; i < rec.time_s.size(); ++i) error[i] += schedule.Value(rec.time_s[i] + o.model_time_offset_s);
  return IdentifyDriveLaw(rec.time_s, error, InModelUnits(rec, *torque), o.fit_begin_s, o.fit_end_s);
}

// How late the recorded bit speed arrives behind the virtual sensor's estimate of it from the surface channels
// (estimation/metrics.hpp: ReadTelemetryLag), on the fit window and up to the longest telemetry delay an effect can
// have; not found where the case's kind has no wave estimator or a channel is not mapped.
estimation::TelemetryLag RecordedTelemetryLag(const nlohmann::json& document, const Recording& rec,
                                              const LoopOptions& o) {
  const ChannelMap *speed = MapOf(o, "top_rpm"), *torque = MapOf(o, "top_torque_Nm"), *bit = MapOf(o, "bit_rpm");
  const ChannelMap* hook = MapOf(o, "hookload_N");
  if (!speed || !torque || !bit || document.value("/model/kind"_json_pointer, std::string()) != "axial_torsional")
    return {};
  estimation::SurfaceSignals surface;
  surface.time_s = rec.time_s;
  surface.top_speed_rad_s = InModelUnits(rec, *speed, kRadPerSecondPerRpm);
  surface.top_torque_Nm = InModelUnits(rec, *torque);
  if (hook) surface.hook_load_N = InModelUnits(rec, *hook);
  estimation::EstimateOptions eo;
  eo.model_time_offset_s = -o.model_time_offset_s;
  try {
    const estimation::BitEstimate e = EstimateBit(estimation::EstimatorModelFromCase(document), surface, eo);
    return estimation::ReadTelemetryLag(rec.time_s, e.bit_speed_rad_s, InModelUnits(rec, *bit, kRadPerSecondPerRpm),
                                        o.fit_begin_s, o.fit_end_s, kMaxTelemetryDelayS);
  } catch (const InputError&) {  // a string the estimator does not model (its messages are the estimate command's)
    return {};
  }
}
}  // namespace

PreparedRecording PrepareRecording(const nlohmann::json& document, const Recording& raw, const LoopOptions& o) {
  if (o.maps.empty()) throw ParameterError("map", "no channels to compare");
  PreparedRecording p;
  // Only the mapped channels take part: a channel the model does not have says nothing about it.
  Recording mapped = raw;
  mapped.names.clear(), mapped.channels.clear();
  for (const ChannelMap& map : o.maps) {
    mapped.names.push_back(map.recording);
    mapped.channels.push_back(raw.Channel(map.recording));
  }
  MaskedRecording masked = MaskArtefacts(mapped);
  p.recording = std::move(masked.recording);
  p.whole = std::move(masked.whole);
  p.masked_samples = std::move(masked.masked);
  for (std::size_t j = 0; j < p.whole.size(); ++j)
    if (p.whole[j]) p.channels_left_whole.push_back(mapped.names[j]);
  const Recording& rec = p.recording;
  // A recording channel that maps the model's torque on bit is read as one (a lab rig's calibration features).
  p.features = o.features;
  for (const ChannelMap& map : o.maps)
    if (p.features.bit_torque.empty() && map.model == "bit_torque_Nm") p.features.bit_torque = map.recording;
  p.fit = MeasureFeatures(rec, o.fit_begin_s, o.fit_end_s, p.features);
  p.held_out = MeasureFeatures(rec, o.held_out_begin_s, o.held_out_end_s, p.features);
  p.fit.drive = RecordedDriveLaw(document, rec, o);
  p.fit.telemetry = RecordedTelemetryLag(document, rec, o);

  // The recording's noise, carried into the model's measured channels.
  p.base = document;
  for (const ChannelMap& map : o.maps) {
    std::vector<double> window;
    const auto& values = rec.Channel(map.recording);
    for (std::size_t i = 0; i < rec.time_s.size(); ++i)
      if (rec.time_s[i] >= o.fit_begin_s && rec.time_s[i] <= o.fit_end_s) window.push_back(values[i]);
    const double noise = NoiseStd(window);
    p.noise.push_back({map.recording, noise});
    if (o.carry_noise) p.base["sensors"]["channels"][map.model]["noise_std"] = noise / std::abs(map.scale);
  }
  if (o.carry_noise) p.base["sensors"]["seed"] = o.seed;
  // The recording's sampling: each sample the mean over its window, the model's from an output finer than it.
  if (o.sample_window_s > 0) {
    for (const ChannelMap& map : o.maps) p.base["sensors"]["channels"][map.model]["window_s"] = o.sample_window_s;
    const double interval = o.sample_window_s / kOutputsPerWindow;
    if (!(p.base["simulation"].value("output_interval_s", 1e-3) <= interval))
      p.base["simulation"]["output_interval_s"] = interval;
  }
  return p;
}

}  // namespace drillwave::diagnosis::loop_internal
