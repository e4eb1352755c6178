#pragma once
// Simulation against recording (DESIGN.md §5, "locate the mismatch"): the model's channels are mapped onto the
// recording's, both are inspected the same way, and the report puts their features side by side (periods, stick
// fraction, speed levels, top-drive stiffness, ...) with the point-by-point residuals over a common window. In
// stick-slip the point-by-point residual is dominated by phase drift, so the features are what locate a mismatch.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/model_kind.hpp"
#include "drillwave/diagnosis/inspection.hpp"
#include "drillwave/io/svg_plot.hpp"

namespace drillwave::diagnosis {

struct ChannelMap {
  std::string recording;  // the recording's channel name, e.g. "tob_Nm"
  std::string model;      // the model's channel name, e.g. "bit_torque_Nm"
  double scale = 1;       // model value times scale is in the recording's unit
};

// "rec=model" or "rec=model*scale"; throws InputError naming the option for anything else.
ChannelMap ParseChannelMap(const std::string& text);

// The model's channels, from a run of a few output samples: which channels a kind writes does not depend on the
// duration, and checking the channel maps against them must not wait for the whole run.
std::vector<cases::Channel> ProbeChannels(const cases::Case& c);

// The explicit maps ("rec=model[*scale]"), each checked against the recording and the model's channels (InputError
// naming --map and listing the channels there are), then every recording channel not mapped paired with the model
// channel of the same name, or of the same quantity in base units (a recording's x_kNm / x_kN against x_Nm / x_N).
std::vector<ChannelMap> ResolveChannelMaps(const std::vector<std::string>& texts, const Recording& recording,
                                           const std::vector<cases::Channel>& model);

// The names of the features Compare reports for these maps (for checking --feature before anything runs).
std::vector<std::string> FeatureNames(const std::vector<ChannelMap>& maps);

// Throws ParameterError("window", ...) unless the window, the recording and the model's time span [model_begin_s,
// model_end_s] overlap in at least 10 recorded samples. Compare checks it too; callers check it before running.
void CheckWindow(const Recording& recording, double model_begin_s, double model_end_s, double window_begin_s,
                 double window_end_s);

struct ChannelResidual {
  std::string channel;       // recording name
  double rms = 0;            // of (model - recording) over the window, the model interpolated to the recording's times
  double bias = 0;           // mean of (model - recording)
  double recording_std = 0;  // scale of the recording channel over the window
};

struct FeatureDifference {
  std::string feature;
  double recording = 0, model = 0;
  double relative = 0;  // (model - recording) / |recording| (NaN where the recording's value is 0 or undefined)
};

struct Comparison {
  double window_begin_s = 0, window_end_s = 0;
  Inspection recording, model;
  std::vector<ChannelResidual> residuals;
  std::vector<FeatureDifference> features;  // largest relative difference first
  std::vector<std::string> findings;
};

// The model's sampled channels (scaled and renamed by `maps`) become a recording over the same window; both are
// inspected with `options`. Throws InputError for a channel missing on either side or a window without samples,
// ParameterError for options that are not valid.
Comparison Compare(const Recording& recording, const cases::RunResult& model, const std::vector<ChannelMap>& maps,
                   double window_begin_s, double window_end_s, const InspectOptions& options = {});

nlohmann::json ComparisonToJson(const Comparison& c);

// The figure of a comparison: each mapped channel, the recording (artefacts masked) against the model.
io::Figure ComparisonFigure(const Recording& recording, const std::vector<ChannelMap>& maps, const Comparison& c);

// comparison.json, report.md, plot.svg (each mapped channel: recording, artefacts masked, against the model).
void WriteComparison(const Recording& recording, const cases::RunResult& model, const std::vector<ChannelMap>& maps,
                     const Comparison& c, const std::string& out_dir);

}  // namespace drillwave::diagnosis
