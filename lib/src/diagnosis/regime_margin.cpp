#include "regime_margin.hpp"

#include <array>
#include <cmath>
#include <optional>

#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/parallel.hpp"

namespace drillwave::diagnosis::loop_internal {
namespace {

constexpr double kStuckShare = 0.01;  // a window whose bit is stuck longer than this share of it sticks and slips
// The coarse steps [%] each side, then this many bisections between the last step in the regime and the first out.
constexpr std::array<double, 4> kStepsPercent = {2.5, 5, 10, kRegimeSearchPercent};
constexpr int kBisections = 2;

const nlohmann::json::json_pointer kSetPoint("/model/top/speed_rad_s");

// Whether the case's top has a set-point this search can move: a number or a schedule of knots.
bool HasSetPoint(const nlohmann::json& doc) {
  if (!doc.contains(kSetPoint)) return false;
  const nlohmann::json& v = doc.at(kSetPoint);
  return v.is_number() || (v.is_object() && v.contains("knots"));
}

// The top's set-point (the number, or every knot of the schedule) times factor.
void ScaleSetPoint(nlohmann::json& doc, double factor) {
  nlohmann::json& v = doc.at(kSetPoint);
  if (v.is_number()) v = v.get<double>() * factor;
  else
    for (nlohmann::json& knot : v["knots"]) knot[1] = knot[1].get<double>() * factor;
}

// The held-out regime of doc with its set-point changed by percent; nullopt where the run fails.
std::optional<std::string> RegimeAt(const nlohmann::json& doc, double percent, const ModelRuns& runner, int draw) {
  nlohmann::json moved = doc;
  ScaleSetPoint(moved, 1 + percent / 100);
  try {
    const Recording model =
        runner.Run(Drawn(moved, draw), runner.FullDuration(), ModelRuns::Tolerance::kCase, kJudgingWorkFactor);
    const bool in_regime = runner.InRegime(model);
    return RegimeOf(runner.HeldOutFeatures(model), in_regime ? runner.RecordingBounces() : !runner.RecordingBounces());
  } catch (const InputError&) {  // a set-point the case refuses
  } catch (const NumericalError&) {
  }
  return std::nullopt;
}

}  // namespace

std::string RegimeOf(const FeatureSet& held_out, bool bounces) {
  const double stuck = held_out.Value("stick_fraction");
  return std::string(bounces ? "bouncing, " : "") + (std::isfinite(stuck) && stuck > kStuckShare ? "stick-slip" : "smooth");
}

HeldOutMotion MotionOf(const FeatureSet& held_out, bool bounces) {
  const double stuck = held_out.Value("stick_fraction");
  return {std::isfinite(stuck) ? stuck : 0.0, bounces};
}

bool ClearlyDifferentRegimes(const HeldOutMotion& a, const HeldOutMotion& b, double scale) {
  const bool a_sticks = a.stuck_share > kStuckShare, b_sticks = b.stuck_share > kStuckShare;
  return a.bounces != b.bounces || (a_sticks != b_sticks && std::abs(a.stuck_share - b.stuck_share) > 3 * scale);
}

bool RejectedForRegime(const HeldOutMotion& recorded, const HeldOutMotion& fitted, const HeldOutMotion& baseline,
                       double scale) {
  return ClearlyDifferentRegimes(fitted, recorded, scale) && !ClearlyDifferentRegimes(baseline, recorded, scale);
}

RegimeMargin MeasureRegimeMargin(const nlohmann::json& doc, const ModelRuns& runner, int draw,
                                 const FeatureSet& recorded_held_out, int threads) {
  RegimeMargin margin;
  if (!HasSetPoint(doc)) return margin;
  margin.recorded = RegimeOf(recorded_held_out, runner.RecordingBounces());
  // The set-point itself and the coarse steps on both sides, side by side.
  std::vector<double> percents = {0};
  for (double step : kStepsPercent) percents.push_back(-step), percents.push_back(step);
  const std::vector<std::optional<std::string>> regimes = ParallelMap(
      percents.size(), threads, [&](std::size_t i) { return RegimeAt(doc, percents[i], runner, draw); });
  margin.runs = static_cast<int>(percents.size());
  if (!regimes[0]) return margin;  // the model itself fails: nothing to measure from
  margin.measured = true;
  margin.model = *regimes[0];
  // Each side: the first coarse step out of the regime, then bisected towards the last one in it.
  const std::array<int, 2> sides = {-1, 1};
  const std::vector<double> edges = ParallelMap(sides.size(), threads, [&](std::size_t s) {
    double inside = 0, outside = std::nan("");
    for (std::size_t k = 0; k < kStepsPercent.size(); ++k) {
      const std::optional<std::string>& r = regimes[1 + 2 * k + s];
      if (r && *r == margin.model) {
        inside = sides[s] * kStepsPercent[k];
      } else {
        if (r) outside = sides[s] * kStepsPercent[k];
        break;  // a failed run ends the search on this side
      }
    }
    if (std::isnan(outside)) return outside;
    for (int b = 0; b < kBisections; ++b) {
      const double middle = 0.5 * (inside + outside);
      const std::optional<std::string> r = RegimeAt(doc, middle, runner, draw);
      (r && *r == margin.model ? inside : outside) = middle;
    }
    return outside;
  });
  margin.runs += kBisections * (std::isfinite(edges[0]) + std::isfinite(edges[1]));
  margin.lower_percent = edges[0], margin.upper_percent = edges[1];
  margin.near_edge = std::abs(margin.lower_percent) <= kNearRegimeEdgePercent ||
                     std::abs(margin.upper_percent) <= kNearRegimeEdgePercent;
  return margin;
}

}  // namespace drillwave::diagnosis::loop_internal

namespace drillwave::diagnosis {

std::string RegimeMarginText(const RegimeMargin& m) {
  if (!m.measured) return "regime margin not measured (no top set-point, or the model's run failed)";
  auto side = [](double percent, const char* direction) {
    return std::isfinite(percent) ? "changes at " + Fixed(percent, 1) + " %"
                                  : std::string("holds to ") + direction + Fixed(kRegimeSearchPercent, 0) + " %";
  };
  return "regime over the held-out window: recorded " + m.recorded + ", model " + m.model +
         (m.recorded == m.model ? "" : " (not the recording's)") + "; with the top set-point moved, the model's " +
         side(m.lower_percent, "-") + " below and " + side(m.upper_percent, "+") + " above" +
         (m.near_edge ? ": near the edge (within " + Fixed(kNearRegimeEdgePercent, 0) + " %)" : std::string());
}

}  // namespace drillwave::diagnosis
