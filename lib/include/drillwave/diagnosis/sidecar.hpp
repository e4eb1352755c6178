#pragma once
// The synthetic recordings' operator sidecar (recNN.json) turned into the case that diagnosis starts from.
#include <string>

#include <nlohmann/json.hpp>

namespace drillwave::diagnosis {

// The synthetic recordings start after this much drilling: a case built from their sidecar runs it first.
constexpr double kSidecarWarmupS = 30;
// and it starts as their simulator did (BASELINE.md, "Recording"): "from the exact steady-drilling state plus a tiny
// bottom-hole roughness". Tiny: 10 um rms, 0.16-1.4 % of a blade's depth of cut at the twelve recordings' points
// (0.7-6.3 mm); at the nominal 60 rpm the bit swings by 10 rpm after 2 s and first sticks at 9 s. One fixed seed, so
// that a recording's case is one run.
constexpr double kSidecarStartRoughnessM = 1e-5;
constexpr int kSidecarStartSeed = 1;

// The operator's sidecar of the synthetic recordings (measured depth, WOB target, rpm set-point schedule in
// recording time) applied to an axial_torsional case: length, weight on bit, the set-point schedule shifted by the
// warm-up that precedes the recording, and the start's bottom-hole roughness (rock/bottom_roughness, kept if the case
// sets one).
// Throws InputError naming `source` (the sidecar's file), the JSON pointer in the sidecar and the value for a missing
// or out-of-range entry: depth in (0, 20000] m, WOB target in (0, 5000] kN, duration in (0, 86400] s, mud density in
// [500, 3000] kg/m3, set-points [t, rpm] with t in [0, duration] not decreasing and rpm in [0, 1000].
nlohmann::json CaseFromSidecar(const nlohmann::json& sidecar, nlohmann::json case_document, double warmup_s,
                               const std::string& source = "sidecar");

}  // namespace drillwave::diagnosis
