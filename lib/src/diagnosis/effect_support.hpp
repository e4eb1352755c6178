#pragma once
// What string_effects.cpp and rig_effects.cpp share: reading a case document and a feature difference in scales.
#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "drillwave/core/constants.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/diagnosis/effects.hpp"

namespace drillwave::diagnosis::effect_support {

inline const double kNaN = std::nan("");

// The difference model - recording of a feature in its scales (NaN where either side lacks it).
inline double Z(const FeatureSet& model, const FeatureSet& recording, const std::string& name) {
  const Feature* r = recording.Find(name);
  const double m = model.Value(name);
  return r && std::isfinite(r->value) && std::isfinite(m) ? (m - r->value) / r->scale : kNaN;
}

inline double Number(const nlohmann::json& doc, const std::string& pointer, double fallback) {
  const nlohmann::json::json_pointer p(pointer);
  return doc.contains(p) && doc.at(p).is_number() ? doc.at(p).get<double>() : fallback;
}

inline std::string Describe(const FeatureSet& model, const FeatureSet& recording, const std::string& name) {
  return name + " " + Significant(model.Value(name), 4) + " in the model against " +
         Significant(recording.Value(name), 4) + " recorded (" + Fixed(Z(model, recording, name), 1) + " scales)";
}

// How much smoother the recorded bit runs than the model's: less sticking, smaller speed swings (in scales, >= 0).
inline double BitRunsSmoother(const FeatureSet& model, const FeatureSet& recording) {
  return std::max(Z(model, recording, "stick_fraction") - 1, 0.0) + std::max(Z(model, recording, "bit_rpm std"), 0.0);
}

}  // namespace drillwave::diagnosis::effect_support
