#pragma once
// The diagnosis loop's first part (internal to the loop and the posterior): a recording made ready to compare models
// with. Only the mapped channels, their artefacts masked; the features on the fit and held-out windows; the case with
// the recording's sensor noise and sampling in its sensors block, so that a model's channels are measured as the
// recording's were.
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/diagnosis/features.hpp"
#include "drillwave/diagnosis/loop.hpp"
#include "drillwave/diagnosis/recording.hpp"

namespace drillwave::diagnosis::loop_internal {

struct PreparedRecording {
  Recording recording;                 // the mapped channels (named as the maps' recording sides), artefacts masked
  std::vector<char> whole;             // per channel: its bursts are motion, left whole (not masked)
  FeatureOptions features;             // the options its features are measured with
  FeatureSet fit, held_out;            // the recording's features on the two windows
  nlohmann::json base;                 // the case measured as the recording: its noise and sampling in the sensors
  std::vector<std::pair<std::string, double>> noise;  // recording channel, estimated noise std (its unit)
  std::vector<std::pair<std::string, int>> masked_samples;
  std::vector<std::string> channels_left_whole;
};

// Throws InputError for no channel maps; the options must be valid (LoopOptions::IsValid, which the loop's and the
// posterior's entry points check first).
PreparedRecording PrepareRecording(const nlohmann::json& document, const Recording& raw, const LoopOptions& o);

}  // namespace drillwave::diagnosis::loop_internal
