#pragma once
// From mismatch to missing physics (DESIGN.md §5, steps 3-4): the model a user believes is compared with the
// recording, and named rules read the feature differences as evidence for effects the model leaves out. Each rule
// states what it measured; none reads any answer key. The rules cover the effects whose signature the features show
// directly; the rest of the mismatch is reported as unexplained.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/diagnosis/comparison.hpp"

namespace drillwave::diagnosis {

struct Hypothesis {
  std::string effect;    // soft_topdrive, side_friction, stribeck, axial_coupling_off
  std::string evidence;  // the measured numbers behind it
  double estimate = 0;   // a first value of the effect's size where the rule gives one (NaN otherwise)
  std::string unit;
};

struct Diagnosis {
  Comparison comparison;
  std::vector<Hypothesis> hypotheses;
  std::vector<std::string> unexplained;  // large feature differences no rule accounts for
};

Diagnosis Diagnose(const Recording& recording, const cases::RunResult& model, const std::vector<ChannelMap>& maps,
                   double window_begin_s, double window_end_s);

nlohmann::json DiagnosisToJson(const Diagnosis& d);

// The synthetic recordings start after this much drilling: a case built from their sidecar runs it first.
constexpr double kSidecarWarmupS = 30;

// The operator's sidecar of the synthetic recordings (measured depth, WOB target, rpm set-point schedule in
// recording time) applied to an axial_torsional case: length, weight on bit, and the set-point schedule shifted by
// the warm-up that precedes the recording (with a 5 % bump in its first seconds to leave the unstable equilibrium).
// Throws InputError naming `source` (the sidecar's file), the JSON pointer in the sidecar and the value for a missing
// or out-of-range entry: depth in (0, 20000] m, WOB target in (0, 5000] kN, duration in (0, 86400] s, mud density in
// [500, 3000] kg/m3, set-points [t, rpm] with t in [0, duration] not decreasing and rpm in [0, 1000].
nlohmann::json CaseFromSidecar(const nlohmann::json& sidecar, nlohmann::json case_document, double warmup_s,
                               const std::string& source = "sidecar");

}  // namespace drillwave::diagnosis
