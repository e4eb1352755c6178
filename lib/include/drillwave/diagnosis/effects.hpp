#pragma once
// The effects diagnosis can name (issue 13's vocabulary) and how each is modelled: a component of the case switched
// on, with the parameters a fit may move (bounds, log or linear scale, a first value from the evidence). The rules
// here only propose: each reads a measured difference between the recording and the model (in the features' own
// scales) as evidence for the effects that would produce it, in both directions — an effect may create stick-slip
// or remove it. Whether an effect is kept is decided by fitting it (loop.hpp).
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/diagnosis/features.hpp"

namespace drillwave::diagnosis {

// Evidence is graded in feature scales (a scale is how much two runs of the same physics differ in that feature). An
// effect is proposed on a difference above kStrongEvidence; one above kWeakEvidence is only indicated: a difference
// that large happens by chance, but an effect it points to is still worth a fit when fewer effects are proposed than
// the loop can try. The fit and the held-out window decide either way.
constexpr double kStrongEvidence = 3;
constexpr double kWeakEvidence = 1;

// The longest telemetry delay a sensor_delay effect is fitted to: mud-pulse telemetry's ~6.6 s (chapter sect. 2.7)
// with a margin.
constexpr double kMaxTelemetryDelayS = 8.0;

struct EffectParameter {
  std::string name;   // e.g. "kp_Nms_per_rad"
  std::string unit;
  double lower = 0, upper = 1;
  bool log_scale = false;  // moved on a log scale (spans decades)
  double start = 0;        // first value, inside the bounds
  // Which bounds are limits of the physics itself (a friction or delay of zero, static friction no lower than
  // kinetic): a fit that ends on one has estimated the effect at its limit. The other bounds only span what the effect
  // plausibly is, and a fit that ends on one of those has not estimated it (the loop does not name it).
  bool lower_is_physical = false, upper_is_physical = false;
};

struct Effect {
  std::string name;       // from the vocabulary: bha, stribeck, unbalance, side_friction, kelvin_voigt,
                          // soft_topdrive, axial_coupling_off, dc_motor, sensor_delay
  std::string component;  // what is switched on, in the case's words
  std::vector<EffectParameter> parameters;
  // Switches the component on in a case document with these parameter values (one per parameter).
  std::function<void(nlohmann::json& document, const std::vector<double>& values)> apply;
  double strength = 0;    // how strongly the evidence points to it (in feature scales, see above); 0: none
  std::string evidence;   // the measured numbers behind it
  // A base parameter (BaseCalibrations) re-estimated beside effects as a rival explanation: fitted, never named.
  bool calibration = false;
  // A base parameter offered among the effects (the rig's shaft period and disc inertia, which no base calibration
  // can read before an effect makes the disc stick): fitted and named like one, and beside a kept set judged as the
  // base's calibrations are (EffectSelection::CalibrateBesideTheKept).
  bool base_parameter = false;
  // What the recording measures directly that contradicts the effect (a stiff drive's law read off it, against a soft
  // drive): such an effect is not fitted. Empty: nothing refutes it.
  std::string refuted = {};
  bool Proposed() const { return strength > kStrongEvidence; }
};

// Every effect of the vocabulary for an axial_torsional case document, each with its evidence from the features of
// the recording and of that case's run over the same window. Effects the case's kind has no component for are
// omitted. `downhole` names the model channels measured downhole (they get a sensor delay).
std::vector<Effect> ProposeEffects(const nlohmann::json& document, const FeatureSet& model, const FeatureSet& recording);

// The base model's uncertain parameters, each within its stated prior range, as calibrations (no evidence; their
// apply sets the parameter), fitted in order before any effect so that effects are fitted on a calibrated base rather
// than asked to make up for a wrong one. What a calibration is fitted to follows from what its parameter moves: a
// level (the fit window's means and period) or the motion (every feature of the fit window).
enum class CalibrationTarget { kLevels, kMotion };
struct Calibration {
  Effect parameters;  // name, parameters with their prior ranges, apply
  CalibrationTarget target = CalibrationTarget::kLevels;
};
// axial_torsional: first the wear-flat contact stress sigma*l within +-20 % of the case's (the mean torque reads it),
// then the rock's intrinsic specific energy eps within +-20 % (no level reads it: it sets the regenerative coupling's
// gain and so how unstable steady drilling is). Formations vary by that much between wells. Empty for other kinds
// (the rig's disc inertia is among its effects; DiagnosableKind below).
std::vector<Calibration> BaseCalibrations(const nlohmann::json& document);

// What diagnosis offers for one model kind: its effects with their evidence, and its base's calibrations (none: an
// empty function). A field string (axial_torsional: string_effects.cpp) and a laboratory rig modelled as a
// two-inertia pendulum (two_mass: rig_effects.cpp, whose disc inertia and shaft period are among its effects, fitted
// with the others). ProposeEffects and BaseCalibrations hand a document to its kind's; other kinds have none.
struct DiagnosableKind {
  std::string kind;
  std::function<std::vector<Effect>(const nlohmann::json&, const FeatureSet& model, const FeatureSet& recording)>
      propose;
  std::function<std::vector<Calibration>(const nlohmann::json&)> calibrations;
};
const std::vector<DiagnosableKind>& DiagnosableKinds();
DiagnosableKind StringDiagnosis();
DiagnosableKind RigDiagnosis();

// The vocabulary, for listing and checking names.
const std::vector<std::string>& EffectVocabulary();

// value <-> [0, 1] on the parameter's scale.
double ToUnit(const EffectParameter& p, double value);
double FromUnit(const EffectParameter& p, double unit);

}  // namespace drillwave::diagnosis
