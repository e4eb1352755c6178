#pragma once
// A model kind: one module that declares, validates and runs one family of models (torsional wave string,
// two-mass pendulum, two-disc set-up, ...). The runner knows kinds only through this interface, so adding a kind
// touches neither the runner, nor the solvers, nor the output writers: only the list in kind_registry.cpp.
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/analysis/kelvin_voigt_continuum.hpp"
#include "drillwave/analysis/periodic_orbits.hpp"
#include "drillwave/analysis/spectrum.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/integration/options.hpp"
#include "drillwave/io/json_reader.hpp"

namespace drillwave::cases {

// Settings every kind receives from the case's "simulation" and "statistics" blocks.
struct RunSettings {
  double duration_s = 10;
  double output_interval_s = 1e-3;
  integration::IntegratorOptions integrator;
  double window_begin_s = 0;  // statistics window
  double window_end_s = 10;
};

// A named output channel; the name carries its unit (e.g. "bit_rpm", "top_torque_Nm").
struct Channel {
  std::string name;
  std::vector<double> values;
};

// What a run of any kind hands to the output writers: sampled channels, a summary and how to plot them.
struct RunResult {
  std::vector<double> time_s;
  std::vector<Channel> channels;
  nlohmann::json summary = nlohmann::json::object();  // the statistics that apply to the kind
  // Plot layout: panels of channel names (each panel shares a y axis and unit).
  std::vector<std::vector<std::string>> plot_panels;

  const Channel& channel(const std::string& name) const;
};

// Angular speeds [rad/s] as revolutions per minute, for the *_rpm channels every kind writes.
inline std::vector<double> ToRpm(const std::vector<double>& rad_s) {
  std::vector<double> rpm(rad_s.size());
  for (std::size_t i = 0; i < rad_s.size(); ++i) rpm[i] = rad_s[i] * (30.0 / kPi);
  return rpm;
}

// A steady state of a model (at the final values of its input schedules) and the linear delay system of small
// perturbations about it, for `drillwave stability`.
struct LinearizedOperatingPoint {
  nlohmann::json steady_state;  // named values with units, e.g. {"bit_speed_rad_s": 6.2, ...}
  std::vector<std::string> state_names;
  analysis::LinearDelaySystem system;
  // A string with Kelvin-Voigt damping as the continuum it discretizes (exact sections), where the kind can close it:
  // `stability` reports its verdict beside the discretized system's.
  std::optional<analysis::KelvinVoigtString> continuum = std::nullopt;
};

// A validated model ready to run; immutable, so one prepared model can be run many times (sweeps, fits).
class PreparedModel {
 public:
  virtual ~PreparedModel() = default;
  virtual RunResult Run(const RunSettings& settings) const = 0;
  // Every steady state at the inputs' final values with its linearization (possibly none: e.g. the bit held by
  // static friction). Throws InputError naming "/model" if this kind or configuration has no linearization.
  virtual std::vector<LinearizedOperatingPoint> Linearize() const;
  // The model at its inputs' final values as an autonomous piecewise-smooth field, for periodic orbits
  // (`drillwave orbits`). Throws InputError naming "/model" if this kind has none.
  virtual std::shared_ptr<const analysis::PiecewiseSmoothField> OrbitField() const;
};

class ModelKind {
 public:
  virtual ~ModelKind() = default;
  virtual std::string name() const = 0;         // the value of "model.kind"
  virtual std::string description() const = 0;  // one line, for `drillwave kinds`
  // Fields with units and allowed ranges, for `drillwave kinds` (a JSON object: field path -> description).
  virtual nlohmann::json FieldSchema() const = 0;
  // Reads and validates the "model" block (InputError names the JSON path), without running anything.
  virtual std::unique_ptr<PreparedModel> Prepare(const io::JsonReader& model) const = 0;
};

// Every registered kind (see kind_registry.cpp).
const std::vector<std::unique_ptr<ModelKind>>& AllKinds();
const ModelKind& FindKind(const std::string& name, const std::string& json_path);

}  // namespace drillwave::cases
