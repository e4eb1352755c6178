// compare-controllers: the laws' top blocks written from the case's top, their runs and what is measured on them
// (the outputs: controller_comparison_report.cpp).
#include "drillwave/cases/controller_comparison.hpp"

#include <cmath>
#include <limits>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/stability.hpp"
#include "drillwave/cases/statistics.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/median.hpp"
#include "drillwave/core/progress.hpp"
#include "kinds/top_components.hpp"

namespace drillwave::cases {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kFigureLeadS = 10;  // the figure shows the stiff PI's stick-slip this long before the handover
constexpr double kSlidingReachingMargin = 1.5;  // the sliding mode's J eta over the stiff PI's largest torque
constexpr double kSlidingLayerGain = 10;        // its layer's gain J eta / phi over the stiff PI's kp

// The case's top as every law keeps it (inertia, set-point, torque limit, actuator delay, gear, dampers), and the
// stiff PI's gains.
struct StiffTop {
  nlohmann::json drive;
  nlohmann::json kp, ki;
};
StiffTop StiffTopOf(const nlohmann::json& top, const std::optional<StiffPi>& given) {
  const std::string type = top.value("type", std::string("top_drive"));
  if (!IsPiTopDriveType(type) && !given)
    throw InputError("/model/top/type",
                     "compare-controllers compares the laws of a PI top drive (top_drive, "
                     "soft_torque, z_torque, wave_cancellation or sliding_mode), got " +
                         type + ": give the stiff PI that replaces it (inertia, kp, ki)");
  if (!top.contains("speed_rad_s"))
    throw InputError("/model/top/speed_rad_s", "the laws track a speed set-point: expected one in the case's top");
  StiffTop stiff;
  if (IsPiTopDriveType(type)) {
    stiff.drive = top;
    for (const char* law_field :
         {"type", "kp_Nms_per_rad", "ki_Nm_per_rad", "tuning_period_s", "feedback_gain_rad_per_Nms",
          "feedback_time_constant_s", "impedance_Nms_per_rad", "speed_loop_corner_rad_s", "wave_filter_time_constant_s",
          "surface_corner_rad_s", "reaching_rate_rad_s2", "boundary_layer_rad_s", "handover"})
      stiff.drive.erase(law_field);
  } else {  // a top of another kind: only its set-point carries over
    stiff.drive = {{"speed_rad_s", top["speed_rad_s"]}};
  }
  if (given) {
    stiff.drive["inertia_kgm2"] = given->inertia_kgm2;
    stiff.kp = given->kp_Nms_per_rad, stiff.ki = given->ki_Nm_per_rad;
  } else if (top.contains("kp_Nms_per_rad") && top.contains("ki_Nm_per_rad")) {
    stiff.kp = top["kp_Nms_per_rad"], stiff.ki = top["ki_Nm_per_rad"];
  } else {
    throw InputError("/model/top/kp_Nms_per_rad", "the stiff PI's gains: expected kp_Nms_per_rad and ki_Nm_per_rad "
                                                  "in the case's top (not a SoftSpeed tuning), or a stiff PI given");
  }
  return stiff;
}

nlohmann::json WithTop(const nlohmann::json& base, const nlohmann::json& drive, const nlohmann::json& law) {
  nlohmann::json doc = base;
  doc["model"]["top"] = drive;
  doc["model"]["top"].update(law);
  return doc;
}

// The linear verdict at the operating point (the first steady state) and its rightmost root.
void LinearVerdict(const Case& c, ControllerResult& r) {
  r.rightmost_re = r.rightmost_im = kNaN;
  std::vector<OperatingPointStability> points;
  try {
    points = AnalyzeStability(c, {}, ContinuumRoots::kSkipped);
  } catch (const InputError&) {  // a kind or string without a linearization
    r.verdict = "no linearization";
    return;
  }
  if (points.empty()) {
    r.verdict = "no steady state";
    return;
  }
  const analysis::Spectrum& sp = points.front().spectrum;
  r.verdict = analysis::VerdictName(sp.verdict);
  if (!sp.roots.empty()) r.rightmost_re = sp.roots.front().s.real(), r.rightmost_im = sp.roots.front().s.imag();
}

// The median over the severity's windows of the standard deviation of `values` in each.
double MedianWindowStd(const std::vector<double>& t, const std::vector<double>& values, double begin, double end) {
  std::vector<double> stds;
  for (const auto& [a, b] : SeverityWindows(begin, end)) {
    double sum = 0, squares = 0;
    int n = 0;
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t[i] >= a && t[i] <= b) sum += values[i], squares += values[i] * values[i], ++n;
    if (n > 1) stds.push_back(std::sqrt(std::max(0.0, (squares - sum * sum / n) / (n - 1))));
  }
  return Median(stds);
}

// The time from the handover to the end of the last stick after it (0 without one); none if the bit still sticks
// within the last severity window of the run.
std::optional<double> SuppressedAfter(const std::vector<double>& t, const std::vector<double>& stuck, double handover,
                                      double end) {
  double last = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= handover && stuck[i] > 0.5) last = t[i];
  if (last >= end - kSeverityWindowS) return std::nullopt;
  return last < handover ? 0.0 : last - handover;
}

double NumberOr(const nlohmann::json& summary, const char* key, double otherwise) {
  const auto it = summary.find(key);
  return it != summary.end() && it->is_number() ? it->get<double>() : otherwise;
}

// A run's blow-up is recorded (run_failure) unless the comparison needs the run: the stiff PI's when SoftSpeed is
// tuned to its period.
ControllerResult Evaluate(const std::string& law, const nlohmann::json& doc, double handover, double end,
                          long max_steps, bool needed = false) {
  ControllerResult r;
  r.law = law;
  r.document = doc;
  Case c = ParseCase(doc);
  if (max_steps > 0) c.settings.integrator.max_steps = max_steps;
  LinearVerdict(c, r);
  CaseRun run;
  try {
    run = RunCase(c);
  } catch (const NumericalError& e) {  // a law driven unstable (by a delay, say) grows without bound: a result
    if (needed) throw;
    r.run_failure = e.what();
    r.severity = r.stick_fraction = r.period_s = r.torque_std_Nm = kNaN;
    return r;
  }
  r.steps = static_cast<long>(NumberOr(run.summary, "steps", 0));
  r.severity = NumberOr(run.summary, "stick_slip_severity", kNaN);
  r.stick_fraction = NumberOr(run.summary, "stick_fraction", kNaN);
  r.period_s = NumberOr(run.summary, "stick_slip_period_s", NumberOr(run.summary, "oscillation_period_s", kNaN));
  const std::vector<double>& t = run.result.time_s;
  const std::vector<double>& torque = run.result.channel("top_torque_Nm").values;
  const std::vector<double>& bit = run.result.channel("bit_rpm").values;
  r.torque_std_Nm = MedianWindowStd(t, torque, handover, end);
  r.suppressed_after_s = SuppressedAfter(t, run.result.channel("bit_stuck").values, handover, end);
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= handover - kFigureLeadS)
      r.time_s.push_back(t[i]), r.bit_rpm.push_back(bit[i]), r.top_torque_Nm.push_back(torque[i]);
  return r;
}

// What every law shares: the span of the runs, the case they run (without its expectations, to the end, its
// statistics over the span after the handover) and the drive.
struct Protocol {
  double handover_s = 0, end_s = 0;
  nlohmann::json base;
  StiffTop stiff;
  nlohmann::json stiff_law;  // the stiff PI's type and gains on the drive
};
Protocol ProtocolOf(const nlohmann::json& document, const ControllerComparisonSpec& spec) {
  const Case given = ParseCase(document);
  Protocol p;
  p.handover_s = spec.handover_s.value_or(given.settings.window_begin_s);
  if (!(p.handover_s > 0) || !std::isfinite(p.handover_s))
    throw InputError("handover_s", "the laws take over from the stiff PI's stick-slip at a time > 0, got " +
                                       Significant(p.handover_s, 6) + " s (by default the start of the case's "
                                       "statistics window)");
  if (!(spec.after_s >= kSeverityWindowS) || !std::isfinite(spec.after_s))
    throw InputError("after_s", "the runs go on at least one severity window (" + Significant(kSeverityWindowS, 3) +
                                    " s) after the handover, got " + Significant(spec.after_s, 6) + " s");
  p.end_s = p.handover_s + spec.after_s;
  p.base = document;
  p.base.erase("expect");  // the case's expectations are its own law's
  p.base["simulation"]["duration_s"] = p.end_s;
  p.base["statistics"]["window_s"] = {p.handover_s, p.end_s};
  p.stiff = StiffTopOf(document["model"]["top"], spec.stiff_pi);
  if (spec.actuator_delay_s) p.stiff.drive["actuator_delay_s"] = *spec.actuator_delay_s;
  if (spec.torque_limit_Nm) p.stiff.drive["torque_limit_Nm"] = *spec.torque_limit_Nm;
  p.stiff_law = {{"type", "top_drive"}, {"kp_Nms_per_rad", p.stiff.kp}, {"ki_Nm_per_rad", p.stiff.ki}};
  return p;
}

}  // namespace

nlohmann::json StiffPiCase(const nlohmann::json& document, const ControllerComparisonSpec& spec) {
  const Protocol p = ProtocolOf(document, spec);
  return WithTop(p.base, p.stiff.drive, p.stiff_law);
}

ControllerComparison CompareControllers(const nlohmann::json& document, const ControllerComparisonSpec& spec) {
  const Protocol p = ProtocolOf(document, spec);
  const StiffTop& stiff = p.stiff;
  ControllerComparison out;
  out.handover_s = p.handover_s, out.end_s = p.end_s;
  out.actuator_delay_s = stiff.drive.value("actuator_delay_s", 0.0);
  out.laws.push_back(
      Evaluate("stiff PI", WithTop(p.base, stiff.drive, p.stiff_law), out.handover_s, out.end_s, spec.max_steps,
               !spec.tuning_period_s));
  // SoftSpeed is tuned to the stick-slip the stiff PI keeps up (its period over the same span).
  out.tuning_period_s = spec.tuning_period_s.value_or(out.laws.front().period_s);
  if (!(out.tuning_period_s > 0))
    throw InputError("tuning_period_s", "the stiff PI shows no stick-slip period over [" +
                                            Significant(out.handover_s, 6) + ", " + Significant(out.end_s, 6) +
                                            "] s to tune SoftSpeed to: give the period");
  const nlohmann::json& top = document["model"]["top"];
  out.feedback_time_constant_s = top.contains("feedback_time_constant_s") && top["feedback_time_constant_s"].is_number()
                                     ? top["feedback_time_constant_s"].get<double>()
                                     : 2 * out.tuning_period_s;  // passes the stick-slip mode: tau_f w = 4 pi
  const nlohmann::json handover = {
      {"time_s", out.handover_s}, {"kp_Nms_per_rad", stiff.kp}, {"ki_Nm_per_rad", stiff.ki}};
  const nlohmann::json soft_speed = {{"type", "soft_torque"}, {"tuning_period_s", out.tuning_period_s},
                                     {"handover", handover}};
  nlohmann::json z_torque = p.stiff_law;
  z_torque.update({{"type", "z_torque"}, {"feedback_time_constant_s", out.feedback_time_constant_s},
                   {"handover", handover}});
  out.laws.push_back(
      Evaluate("SoftSpeed", WithTop(p.base, stiff.drive, soft_speed), out.handover_s, out.end_s, spec.max_steps));
  out.laws.push_back(
      Evaluate("Z-Torque", WithTop(p.base, stiff.drive, z_torque), out.handover_s, out.end_s, spec.max_steps));
  // The wave cancellation pulls the top onto its law's speed with the stiff PI's kp; its slow speed loop reflects
  // only below a tenth of the stick-slip frequency.
  out.wave_corner_rad_s = 2 * kPi / out.tuning_period_s / 10;
  nlohmann::json wave = {{"type", "wave_cancellation"}, {"kp_Nms_per_rad", stiff.kp},
                         {"speed_loop_corner_rad_s", out.wave_corner_rad_s}, {"handover", handover}};
  out.laws.push_back(Evaluate("wave cancellation", WithTop(p.base, stiff.drive, wave), out.handover_s, out.end_s,
                              spec.max_steps));
  // The same law reading the arriving wave through a low-pass (model::WaveCancellation::filter_time_constant_s):
  // behind an actuator delay the exact law sends down up to twice the wave at every frequency, the filtered one only
  // below its corner. The corner sits at 2.5 times the stick-slip frequency, t_f = P / (5 pi): it absorbs the
  // stick-slip mode (22 degrees of lag there) and reflects the faster waves a delay would amplify.
  out.wave_filter_time_constant_s = out.tuning_period_s / (5 * kPi);
  nlohmann::json filtered = wave;
  filtered["wave_filter_time_constant_s"] = out.wave_filter_time_constant_s;
  out.laws.push_back(Evaluate("filtered wave cancellation", WithTop(p.base, stiff.drive, filtered), out.handover_s,
                              out.end_s, spec.max_steps));
  // The sliding mode holds Z-Torque's command on the surface e + lambda I, lambda the wave cancellation's corner. Its
  // reaching torque J eta is one and a half times the largest torque the stiff PI gave the string (the load it must
  // dominate while stick-slip lasts), and its layer is thin: the gain J eta / phi inside it ten times the stiff PI's
  // kp, a near-discontinuous law (at the stiff PI's gain it would be Z-Torque with a torque limit).
  double largest_torque = 0;
  for (double torque : out.laws.front().top_torque_Nm) largest_torque = std::max(largest_torque, std::abs(torque));
  out.sliding_reaching_torque_Nm = spec.sliding_reaching_torque_Nm.value_or(kSlidingReachingMargin * largest_torque);
  if (spec.sliding_reaching_torque_Nm && !(*spec.sliding_reaching_torque_Nm > 0))
    throw InputError("sliding_reaching_torque_Nm", "the sliding mode's reaching torque: expected > 0 N m, got " +
                                                       Significant(*spec.sliding_reaching_torque_Nm, 6));
  out.sliding_boundary_layer_rad_s = out.sliding_reaching_torque_Nm / (kSlidingLayerGain * stiff.kp.get<double>());
  nlohmann::json sliding = {
      {"type", "sliding_mode"},
      {"feedback_time_constant_s", out.feedback_time_constant_s},
      {"surface_corner_rad_s", out.wave_corner_rad_s},
      {"reaching_rate_rad_s2", out.sliding_reaching_torque_Nm / stiff.drive.at("inertia_kgm2").get<double>()},
      {"boundary_layer_rad_s", out.sliding_boundary_layer_rad_s},
      {"handover", handover}};
  if (out.sliding_reaching_torque_Nm > 0) {
    out.laws.push_back(
        Evaluate("sliding mode", WithTop(p.base, stiff.drive, sliding), out.handover_s, out.end_s, spec.max_steps));
  } else {  // the stiff PI's run failed: no load to size the reaching torque by
    ControllerResult failed;
    failed.law = "sliding mode";
    failed.document = WithTop(p.base, stiff.drive, sliding);
    failed.verdict = "not run";
    failed.rightmost_re = failed.rightmost_im = kNaN;
    failed.severity = failed.stick_fraction = failed.period_s = failed.torque_std_Nm = kNaN;
    failed.run_failure =
        "not run: its reaching torque is sized by the stiff PI's largest torque, and that run "
        "failed (" +
        out.laws.front().run_failure + ")";
    out.laws.push_back(failed);
  }
  const double reference = out.laws.front().torque_std_Nm;
  for (ControllerResult& r : out.laws) r.torque_reduction_pct = 100 * (1 - r.torque_std_Nm / reference);
  return out;
}

std::vector<ControllerComparison> CompareUnderActuatorDelays(const nlohmann::json& document,
                                                             ControllerComparisonSpec spec,
                                                             const ControllerComparison& nominal,
                                                             const std::vector<double>& delays_s) {
  spec.tuning_period_s = nominal.tuning_period_s;
  spec.sliding_reaching_torque_Nm = nominal.sliding_reaching_torque_Nm;
  long costliest = 0;
  for (const ControllerResult& r : nominal.laws) costliest = std::max(costliest, r.steps);
  if (costliest > 0) spec.max_steps = static_cast<long>(kDelayedWorkFactor * static_cast<double>(costliest));
  std::vector<ControllerComparison> out;
  Progress progress("compare-controllers under actuator delays");
  for (double delay : delays_s) {
    progress.Count("every law at " + Significant(delay, 3) + " s delay", out.size(), delays_s.size(), "delays");
    if (delay == nominal.actuator_delay_s) {
      out.push_back(nominal);
      continue;
    }
    spec.actuator_delay_s = delay;
    out.push_back(CompareControllers(document, spec));
  }
  return out;
}

}  // namespace drillwave::cases
