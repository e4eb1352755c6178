#pragma once
// A case file: which model (by kind), how to simulate it, over which window to take statistics, and what to expect.
//   {"name": ..., "description": ..., "references": [...],
//    "model": {"kind": "<kind>", ...kind's fields...},
//    "simulation": {"duration_s", "output_interval_s", "abs_tol", "rel_tol", "max_step_s"},
//    "statistics": {"window_s": [begin, end]},
//    "sensors": {"seed": n,
//                "channels": {"<channel>": {"time_constant_s", "window_s", "delay_s", "hold_s", "noise_std"}}},
//    "expect": {"<summary key>": {"min": a, "max": b} | {"value": v, "rel_tol": r} | null}}
// Every parameter is addressable by its JSON pointer (e.g. /model/bit/inertia_kgm2), so sweeps and fits patch the
// document and parse it again: parsing is cheap and a PreparedModel is immutable.
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/cases/model_kind.hpp"
#include "drillwave/cases/sensors.hpp"

namespace drillwave::cases {

struct Case {
  nlohmann::json document;
  std::string name;
  std::string kind;
  RunSettings settings;
  std::shared_ptr<const PreparedModel> model;
  SensorSet sensors;  // "<channel>_measured" channels (sensors.hpp)
  nlohmann::json expect = nlohmann::json::object();
};

// Validates the whole document (InputError names the JSON path); runs nothing. The expect block is validated too,
// and the work the case asks for is estimated and refused above MaxSamples() (see SetMaxSamples).
Case ParseCase(const nlohmann::json& document);

// The most output samples (duration / output interval) and the fewest integration steps (duration / max_step_s) a
// case may ask for; 1e7 unless set (the command line's --max-samples). Process-wide; InputError if not >= 1.
void SetMaxSamples(double limit);
double MaxSamples();

// The embedded default case (json-cases/saldivar-stickslip.json, compiled in).
const std::string& DefaultCaseText();

struct CaseRun {
  RunResult result;
  nlohmann::json summary;  // the kind's statistics plus steps, events, wall_time_s; never NaN, inf or +-1e300
};
// Throws NumericalError if the run fails or any output sample is not finite (time, channel and values there).
CaseRun RunCase(const Case& c);

struct ExpectationCheck {
  std::string key;
  bool passed;
  std::string detail;  // "stick_fraction = 0.31 in [0.2, 0.4]"
};
std::vector<ExpectationCheck> CheckExpectations(const nlohmann::json& expect, const nlohmann::json& summary);

// Writes trajectory.csv, summary.json, plot.svg and report.md into out_dir, all or nothing.
void WriteCaseOutputs(const Case& c, const CaseRun& run, const std::string& out_dir);

}  // namespace drillwave::cases
