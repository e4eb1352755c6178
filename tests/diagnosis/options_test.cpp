// The diagnosis options' IsValid (core/validity.hpp): the defaults pass (the loop's once its windows are set), each
// field out of its range is named with its value; and every entry point refuses them with a ParameterError naming the
// field before it reads the recording or runs a model.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "drillwave/diagnosis/features.hpp"
#include "drillwave/diagnosis/fit.hpp"
#include "drillwave/diagnosis/inspection.hpp"
#include "drillwave/diagnosis/loop.hpp"
#include "drillwave/diagnosis/minimize.hpp"
#include "drillwave/diagnosis/posterior.hpp"
#include "invalid_field.hpp"
#include "noisy_twin.hpp"

namespace drillwave::diagnosis {
namespace {

using testing::InvalidField;
using testing::InvalidFieldWith;
using testing::RefusedParameter;

const double kNaN = std::nan("");

// The message IsValid writes for `options` ("" when valid).
template <class Options>
std::string MessageOf(const Options& options) {
  std::string message;
  InvalidField(options, &message);
  return message;
}

TEST(MinimizeOptions, TheDefaultsAreValidAndEachBadFieldIsNamed) {
  const MinimizeOptions o;
  EXPECT_EQ(InvalidField(o), "");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.max_evaluations = 0; }), "max_evaluations");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.starts = 0; }), "starts");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.threads = 0; }), "threads");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.initial_step = 1.5; }), "initial_step");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.x_tolerance = 0; }), "x_tolerance");
}

TEST(MinimizeOptions, TheMinimizerRefusesThemBeforeItsFirstEvaluation) {
  int calls = 0;
  const UnitObjective counted = [&](const std::vector<double>&) { return ++calls, 1.0; };
  MinimizeOptions o;
  o.starts = 0;
  EXPECT_EQ(RefusedParameter([&] { MinimizeInUnitCube(counted, {0.5}, o); }), "starts");
  EXPECT_EQ(calls, 0);
}

TEST(FitOptions, TheDefaultsAreValidAndEachBadFieldIsNamed) {
  const FitOptions o;
  EXPECT_EQ(InvalidField(o), "");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.window_begin_s = 9, b.window_end_s = 2; }), "window_end_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.features.clear(); }), "features");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.model_time_offset_s = kNaN; }), "model_time_offset_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.max_evaluations = 0; }), "max_evaluations");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.tolerance = 0; }), "tolerance");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.starts = 0; }), "starts");
  FitOptions reversed;
  reversed.window_begin_s = 9, reversed.window_end_s = 2;
  EXPECT_EQ(MessageOf(reversed),
            "window_end_s: the window must end after it begins (window_begin_s 9, window_end_s 2)");
}

TEST(FitOptions, FitFeaturesRefusesThemBeforeAnyRun) {
  FitOptions o;
  o.max_evaluations = 0;
  EXPECT_EQ(RefusedParameter([&] { FitFeatures(nlohmann::json::object(), Recording{}, {{"/x", 0, 1}}, o); }),
            "max_evaluations");
}

TEST(PosteriorOptions, TheDefaultsAreValidAndEachBadFieldIsNamed) {
  const PosteriorOptions o;
  EXPECT_EQ(InvalidField(o), "");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.walkers = 7; }), "walkers");   // odd
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.walkers = 2; }), "walkers");   // fewer than any sampling takes
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.steps = 0; }), "steps");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.burn_in = b.steps; }), "burn_in");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.predictive_draws = -1; }), "predictive_draws");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.stretch = 1; }), "stretch");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.start_spread = 0; }), "start_spread");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.threads = 0; }), "threads");
  PosteriorOptions all_burnt;
  all_burnt.burn_in = 60;
  EXPECT_EQ(MessageOf(all_burnt), "burn_in: expected a whole number in [0, steps - 1 = 59], got 60");
}

TEST(FeatureOptions, TheDefaultsAreValidAndEachBadFieldIsNamed) {
  const FeatureOptions o;
  EXPECT_EQ(InvalidField(o), "");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.min_axial_lag_s = 9; }), "max_axial_lag_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.min_axial_correlation = 1.5; }), "min_axial_correlation");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.envelope_lags_s.push_back(kNaN); }), "envelope_lags_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.envelope_window_s = 0; }), "envelope_window_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.parts = 0; }), "parts");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.smoothing_s = 0; }), "smoothing_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.fast_window_s = 0.1; }), "fast_window_s");  // no band above 2 x 0.05
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.stuck_fraction = 1; }), "stuck_fraction");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.max_period_s = 0; }), "max_period_s");
}

TEST(FeatureOptions, MeasureFeaturesRefusesThemBeforeTheWindowsSamplesAreCounted) {
  FeatureOptions o;
  o.parts = 0;
  EXPECT_EQ(RefusedParameter([&] { MeasureFeatures(Recording{}, 0, 1, o); }), "parts");
}

TEST(InspectOptions, TheDefaultsAreValidAndEachBadFieldIsNamed) {
  const InspectOptions o;
  EXPECT_EQ(InvalidField(o), "");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.bit_speed.clear(); }), "bit_speed");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.hampel_half_window_s = 0; }), "hampel_half_window_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.hampel_threshold = kNaN; }), "hampel_threshold");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.stuck_fraction = -0.1; }), "stuck_fraction");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.stuck_min_s = -1; }), "stuck_min_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.trend_window_s = 0; }), "trend_window_s");
}

TEST(InspectOptions, TheInspectionRefusesThemBeforeReadingTheRecording) {
  InspectOptions o;
  o.hampel_threshold = 0;
  EXPECT_EQ(RefusedParameter([&] { InspectRecording(Recording{}, o); }), "hampel_threshold");
}

// LoopOptions{} leaves its windows at 0 for DefaultLoopOptions or the caller: not valid until they are set.
TEST(LoopOptions, WithWindowsSetTheDefaultsAreValidAndEachBadFieldIsNamed) {
  EXPECT_EQ(InvalidField(LoopOptions{}), "fit_end_s");
  const LoopOptions o = testing::Options();
  EXPECT_EQ(InvalidField(o), "");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.model_time_offset_s = kNaN; }), "model_time_offset_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.fit_end_s = b.fit_begin_s; }), "fit_end_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.held_out_begin_s = b.fit_end_s - 1; }), "held_out_begin_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.held_out_end_s = b.held_out_begin_s; }), "held_out_end_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.margin = 1; }), "margin");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.evaluations_per_parameter = 0; }), "evaluations_per_parameter");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.max_singles = -1; }), "max_singles");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.max_effects = 0; }), "max_effects");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.fit_tolerance = 0.5; }), "fit_tolerance");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.fit_tolerance = 0; }), "");  // the case's own
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.threads = 0; }), "threads");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.sample_window_s = 61; }), "sample_window_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.draws = 21; }), "draws");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.features.parts = 0; }), "features.parts");
}

TEST(LoopOptions, TheLoopAndThePosteriorRefuseThemBeforeReadingTheRecording) {
  LoopOptions o = testing::Options();
  o.fit_begin_s = 20, o.fit_end_s = 2;
  try {
    RunDiagnosisLoop(nlohmann::json::object(), Recording{}, o);
    FAIL() << "not refused";
  } catch (const ParameterError& e) {
    EXPECT_STREQ(e.what(), "fit_end_s: the fit window must end after it begins (fit_begin_s 20, fit_end_s 2)");
  }
  o = testing::Options();
  o.held_out_begin_s = 40;  // inside the fit window [0, 50]
  EXPECT_EQ(RefusedParameter([&] {
              SamplePosterior(nlohmann::json::object(), Recording{}, o, {{"/x", 0, 1}}, PosteriorOptions{});
            }),
            "held_out_begin_s");
}

}  // namespace
}  // namespace drillwave::diagnosis
