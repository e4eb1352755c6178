#pragma once
// Fitting a case to a recording by its features (DESIGN.md §5, step 2): the parameters, addressed by JSON pointers
// with bounds, are moved by a bounded derivative-free search (NLopt's Subplex, minimize.hpp) so that the model's features (oscillation period,
// stick fraction, speed levels, ...) match the recording's, as `compare` measures them. Features rather than the
// point-by-point trajectory, because stick-slip is a limit cycle whose phase drifts: its features are what a model
// can be asked to reproduce.
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/diagnosis/comparison.hpp"

namespace drillwave::diagnosis {

struct FitParameter {
  std::string pointer;   // e.g. /model/bit/friction/mu_s; must hold a number in the case
  double lower, upper;   // bounds, lower < upper; the search never leaves them
};

// "/pointer:lower:upper"; throws InputError naming the option for anything else.
FitParameter ParseFitParameter(const std::string& text);

// The case's value at the parameter's pointer; InputError naming the pointer where it is no JSON pointer, holds no
// number in the case, or its bounds are not lower < upper.
double CaseValue(const nlohmann::json& document, const FitParameter& parameter);

struct FitOptions {
  std::vector<ChannelMap> maps;  // as for Compare
  double window_begin_s = -1e300, window_end_s = 1e300;
  // Features to match (names as Comparison::features reports them); each enters as its squared relative difference.
  std::vector<std::string> features = {"bit_oscillation_period_s", "stick_fraction", "bit_speed_mean", "bit_speed_max"};
  double model_time_offset_s = 0;  // subtracted from the model's time before comparing (a warm-up before the recording)
  int max_evaluations = 200;
  double tolerance = 1e-4;  // on the parameters, in units of each parameter's range
  int starts = 1;           // the case's values, then seeded random points within the bounds

  // The window in order, at least one feature, a finite offset, counts >= 1, tolerance in (0, 1]
  // (core/validity.hpp); the maps and feature names are checked against the recording by FitFeatures.
  bool IsValid(std::string* error) const;
};

struct FitResult {
  nlohmann::json document;  // the case with the fitted values
  std::vector<double> start, fitted;
  double objective_start = 0, objective_fitted = 0;
  int evaluations = 0, failed_runs = 0;
  Comparison before, after;
};

using FitProgress = std::function<void(int evaluation, double objective, const std::vector<double>& values)>;

// Throws InputError for a bad pointer, bound or feature name, ParameterError for options that are not valid, before
// anything runs.
FitResult FitFeatures(const nlohmann::json& document, const Recording& recording,
                      const std::vector<FitParameter>& parameters, const FitOptions& options,
                      const FitProgress& progress = nullptr);

// fitted-case.json, fit.json, report.md (before/after features), plot.svg (the fitted model against the recording).
void WriteFit(const Recording& recording, const FitOptions& options, const std::vector<FitParameter>& parameters,
              const FitResult& result, const std::string& out_dir);

}  // namespace drillwave::diagnosis
