#pragma once
// The synthetic recordings' operator sidecar (recNN.json) turned into the case that diagnosis starts from.
#include <string>

#include <nlohmann/json.hpp>

namespace drillwave::diagnosis {

// The operator's sidecar of the synthetic recordings (measured depth, WOB target, rpm set-point schedule in
// recording time) applied to an axial_torsional case: length, weight on bit, and the set-point schedule shifted by
// the warm-up that precedes the recording (with a 5 % bump in its first seconds to leave the unstable equilibrium).
// Throws InputError naming `source` (the sidecar's file), the JSON pointer in the sidecar and the value for a missing
// or out-of-range entry: depth in (0, 20000] m, WOB target in (0, 5000] kN, duration in (0, 86400] s, mud density in
// [500, 3000] kg/m3, set-points [t, rpm] with t in [0, duration] not decreasing and rpm in [0, 1000].
nlohmann::json CaseFromSidecar(const nlohmann::json& sidecar, nlohmann::json case_document, double warmup_s,
                               const std::string& source = "sidecar");

}  // namespace drillwave::diagnosis
