#pragma once
// Parameter sweeps: one case run again with one parameter, addressed by its JSON pointer, set to each of a list of
// values; the runs are independent (each parses its own document into an immutable model) and go in parallel.
// The result is a brute-force bifurcation diagram: every summary statistic against the parameter.
//
//   SweepSpec spec{"/model/upper_disc/input_voltage_V", {0.1, 0.2, 0.3}, 2};
//   SweepResult r = RunSweep(document, spec, nullptr);
//   WriteSweepOutputs(document, spec, r, "out/sweep");
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace drillwave::cases {

struct Case;

struct SweepSpec {
  std::string pointer;         // e.g. "/model/upper_disc/input_voltage_V"; must exist in the document
  std::vector<double> values;  // finite, at least one
  int jobs = 1;                // runs at once (threads), >= 1
};

// "a:b:n" -> n values evenly spaced from a to b inclusive; "v1,v2,..." -> those values. Throws InputError naming
// `what` (the parameter, named as ParameterError says) for anything else, n < 1, or a non-finite value.
std::vector<double> ParseSweepValues(const std::string& text, const std::string& what);
// One finite number, all of text; ParameterError naming `what` otherwise.
double ParseNumber(const std::string& text, const std::string& what);

struct SweepPoint {
  double value = 0;
  bool ok = false;
  nlohmann::json summary;  // the run's summary (ok) or null
  std::string error;       // the numerical failure (not ok): message with time and state
};

struct SweepResult {
  std::vector<SweepPoint> points;  // in the order of spec.values
  double wall_time_s = 0;
};

// A sweep's work, estimated before anything is parsed or run: the number of runs times the output samples or
// integration steps of the first value's run (whichever are more; a run counts as at least kSweepRunMinimumWork, its
// parse, model and summary), refused above kSweepWorkPerMaxSample x MaxSamples() (1e9 by default; --max-samples and
// the Python module's max_samples raise it) with InputError naming --values and the estimate.
inline constexpr double kSweepRunMinimumWork = 1e4;
inline constexpr double kSweepWorkPerMaxSample = 100;
void CheckSweepWork(const Case& first, std::size_t runs);
// The work of an analysis over many points of one case (a stability map, orbits' grid of steady states), estimated
// the same way before anything else is parsed: each point counted as kSweepRunMinimumWork (its parse, linearization
// and roots, or a steady state), plus its run's output samples or steps where it also runs the case (`runs_each`);
// refused above kSweepWorkPerMaxSample x MaxSamples() with ParameterError naming `option` and the estimate.
void CheckPointsWork(const Case& first, double points, bool runs_each, const std::string& option);

// Checks the work (above) and the spec, and parses every variant of the document before running anything, so bad
// input (an unknown pointer, a value out of the field's range) throws InputError naming the pointer and the value and
// runs nothing.
// A run that fails numerically is recorded in its point (ok = false) and the sweep goes on; any other exception
// stops it and reaches the caller (core/parallel.hpp). `progress`, if given, is called after each run (from one
// thread at a time) with the point, the number done and the total.
using SweepProgress = std::function<void(const SweepPoint& point, int done, int total)>;
SweepResult RunSweep(const nlohmann::json& document, const SweepSpec& spec, const SweepProgress& progress);

// Writes sweep.csv (the parameter, ok, then every numeric summary key), bifurcation.svg (the bit speed's minimum,
// mean and maximum over the statistics window, and the stick fraction, against the parameter), report.md and
// case.json into out_dir, all or nothing.
void WriteSweepOutputs(const nlohmann::json& document, const SweepSpec& spec, const SweepResult& result,
                       const std::string& out_dir);

}  // namespace drillwave::cases
