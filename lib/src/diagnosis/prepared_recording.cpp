#include "prepared_recording.hpp"

#include <cmath>

#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/diagnosis/recording.hpp"
#include "drillwave/model/schedule.hpp"

namespace drillwave::diagnosis::loop_internal {
namespace {
// Model outputs per sample window, for the measured window means: a bouncing bit's twin of 10-ms means from 0.5-ms
// outputs reads 0.046 held out at 5 (0.007 at 10, chance 0.535; loop_test.cpp), for about a sixth less CPU than 10.
constexpr double kOutputsPerWindow = 5;

// The drive's law on the fit window (drive_law.hpp), where the case gives the top speed's set-point and the maps give
// the recording's top speed and drive torque; a law with no segments where any is missing.
DriveLaw RecordedDriveLaw(const nlohmann::json& document, const Recording& rec, const LoopOptions& o) {
  const ChannelMap *speed = nullptr, *torque = nullptr;
  for (const ChannelMap& map : o.maps) {
    if (map.model == "top_rpm") speed = &map;
    if (map.model == "top_torque_Nm") torque = &map;
  }
  const nlohmann::json::json_pointer set_point("/model/top/speed_rad_s");
  if (!speed || !torque || speed->scale == 0 || torque->scale == 0 || !document.contains(set_point)) return {};
  model::Schedule schedule;
  try {
    schedule = model::Schedule::FromJson(document.at(set_point), set_point.to_string());
  } catch (const InputError&) {
    return {};  // the case's own checks report it
  }
  const std::vector<double>& rpm = rec.Channel(speed->recording);
  const std::vector<double>& recorded_torque = rec.Channel(torque->recording);
  std::vector<double> error(rec.time_s.size()), torque_Nm(rec.time_s.size());
  for (std::size_t i = 0; i < rec.time_s.size(); ++i) {
    error[i] = schedule.Value(rec.time_s[i] + o.model_time_offset_s) - rpm[i] / speed->scale * kRadPerSecondPerRpm;
    torque_Nm[i] = recorded_torque[i] / torque->scale;
  }
  return IdentifyDriveLaw(rec.time_s, error, torque_Nm, o.fit_begin_s, o.fit_end_s);
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
