#include "drillwave/diagnosis/effects.hpp"

#include <algorithm>
#include <cmath>

#include "effect_support.hpp"

namespace drillwave::diagnosis {

const std::vector<std::string>& EffectVocabulary() {
  static const std::vector<std::string> names = {"bha",          "stribeck",      "unbalance",          "side_friction",
                                                 "kelvin_voigt", "soft_topdrive", "axial_coupling_off", "dc_motor",
                                                 "sensor_delay"};
  return names;
}

double ToUnit(const EffectParameter& p, double v) {
  const double u =
      p.log_scale ? std::log(v / p.lower) / std::log(p.upper / p.lower) : (v - p.lower) / (p.upper - p.lower);
  return std::clamp(u, 0.0, 1.0);
}

double FromUnit(const EffectParameter& p, double u) {
  u = std::clamp(u, 0.0, 1.0);
  return p.log_scale ? p.lower * std::pow(p.upper / p.lower, u) : p.lower + u * (p.upper - p.lower);
}

const std::vector<DiagnosableKind>& DiagnosableKinds() {
  static const std::vector<DiagnosableKind> kinds{StringDiagnosis(), RigDiagnosis()};
  return kinds;
}

namespace {
const DiagnosableKind* KindOf(const nlohmann::json& doc) {
  const std::string kind = doc.value("/model/kind"_json_pointer, std::string());
  for (const DiagnosableKind& k : DiagnosableKinds())
    if (k.kind == kind) return &k;
  return nullptr;
}
}  // namespace

std::vector<Calibration> BaseCalibrations(const nlohmann::json& doc) {
  const DiagnosableKind* kind = KindOf(doc);
  return kind && kind->calibrations ? kind->calibrations(doc) : std::vector<Calibration>{};
}

std::vector<Effect> ProposeEffects(const nlohmann::json& doc, const FeatureSet& m, const FeatureSet& r) {
  const DiagnosableKind* kind = KindOf(doc);
  return kind ? kind->propose(doc, m, r) : std::vector<Effect>{};
}

}  // namespace drillwave::diagnosis
