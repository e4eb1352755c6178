#pragma once
// The margin of a model to the edge of its motion regime over the held-out window (loop.hpp: RegimeMargin), internal
// to the loop.
#include <string>

#include <nlohmann/json.hpp>

#include "drillwave/diagnosis/features.hpp"
#include "drillwave/diagnosis/loop.hpp"
#include "model_runs.hpp"

namespace drillwave::diagnosis::loop_internal {

// A held-out window's regime: "stick-slip" where the bit is stuck for more than 1 % of it, else "smooth", with
// "bouncing, " before it where the bit leaves the bottom.
std::string RegimeOf(const FeatureSet& held_out, bool bounces);
// A held-out window's motion as the regime rejection reads it: the bit's stuck share and whether it bounces.
struct HeldOutMotion {
  double stuck_share = 0;
  bool bounces = false;
};
HeldOutMotion MotionOf(const FeatureSet& held_out, bool bounces);
// Two motions are clearly in different regimes where one bounces and the other not, or where one sticks and slips and
// the other turns smoothly (RegimeOf's 1 % threshold) and their stuck shares differ by more than three of the
// recording's stick-fraction scales (`scale`: how much two runs of the same physics differ in it). A fit that sticks
// 0 % against 5.2 % recorded (dev rec07's side friction, held out 25.3 -> 0.277; scale 0.044) is 1.2 scales off: not
// another regime.
bool ClearlyDifferentRegimes(const HeldOutMotion& a, const HeldOutMotion& b, double scale);
// A fit whose held-out regime is clearly not the recording's is rejected where the baseline's is not clearly different
// (issue 32 item 4): it would explain the recording with another motion. Where the baseline misses the regime too, the
// fit is judged by its features like any other.
bool RejectedForRegime(const HeldOutMotion& recorded, const HeldOutMotion& fitted, const HeldOutMotion& baseline,
                       double scale);

// The set-point of doc's top scaled by f in steps out to +-kRegimeSearchPercent, then bisected where the regime
// changes; each run is draw `draw` over the whole span at the case's tolerance. Not measured where the case's top has
// no speed set-point.
RegimeMargin MeasureRegimeMargin(const nlohmann::json& doc, const ModelRuns& runner, int draw,
                                 const FeatureSet& recorded_held_out, int threads);

}  // namespace drillwave::diagnosis::loop_internal
