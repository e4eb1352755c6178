#pragma once
// A recording whose truth is known, for the diagnosis tests: the two-mass stick-slip case's own run with white noise
// (a "noisy twin"), and loop options that compare its two speed channels.
#include <random>
#include <string>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/diagnosis/loop.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::testing {

inline nlohmann::json TwoMassCase() {
  nlohmann::json doc = testing::LoadCase("two-mass-stickslip");
  doc["simulation"]["duration_s"] = 200;
  doc["simulation"]["abs_tol"] = doc["simulation"]["rel_tol"] = 1e-7;
  doc["statistics"]["window_s"] = {100, 200};
  return doc;
}

// The case's own run from `from_s` on, as a recording in its own time (0 = from_s of the run), with white noise.
inline diagnosis::Recording NoisyTwin(const nlohmann::json& doc, double noise_rpm, double scale = 1, double from_s = 100) {
  const cases::RunResult run = cases::RunCase(cases::ParseCase(doc)).result;
  diagnosis::Recording r;
  r.source = "twin";
  r.names = {"top_rpm", "bit_rpm"};
  r.channels.resize(2);
  std::mt19937 rng(42);
  std::normal_distribution<double> n(0.0, noise_rpm);
  for (std::size_t i = 0; i < run.time_s.size(); ++i) {
    if (run.time_s[i] < from_s) continue;
    r.time_s.push_back(run.time_s[i] - from_s);
    r.channels[0].push_back(scale * run.channel("top_rpm").values[i] + n(rng));
    r.channels[1].push_back(scale * run.channel("bit_rpm").values[i] + n(rng));
  }
  r.sample_interval_s = r.time_s[1] - r.time_s[0];
  return r;
}

inline diagnosis::LoopOptions Options() {
  diagnosis::LoopOptions o;
  o.maps = {{"top_rpm", "top_rpm", 1}, {"bit_rpm", "bit_rpm", 1}};
  o.model_time_offset_s = 100;
  o.fit_begin_s = 0, o.fit_end_s = 50, o.held_out_begin_s = 50, o.held_out_end_s = 99;
  o.features.top_torque = "";  // the twin has no torque channel
  return o;
}

}  // namespace drillwave::testing
