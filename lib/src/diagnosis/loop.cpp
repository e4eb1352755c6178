#include "drillwave/diagnosis/loop.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/sensors.hpp"
#include "drillwave/cases/sweep.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/parallel.hpp"
#include "drillwave/core/progress.hpp"
#include "drillwave/core/sampled.hpp"
#include "drillwave/core/stopwatch.hpp"
#include "drillwave/core/validity.hpp"
#include "drillwave/diagnosis/minimize.hpp"
#include "drillwave/diagnosis/recording.hpp"
#include "drillwave/io/json_number.hpp"
#include "drillwave/io/json_reader.hpp"
#include "effect_selection.hpp"
#include "model_runs.hpp"
#include "prepared_recording.hpp"
#include "regime_margin.hpp"

namespace drillwave::diagnosis {
namespace {

using loop_internal::Draws;
using loop_internal::Drawn;
using loop_internal::Judged;
using loop_internal::kFailedRun;
using loop_internal::ModelRecording;
using loop_internal::ModelRuns;
using loop_internal::PrepareRecording;
using loop_internal::PreparedRecording;
using loop_internal::Applied;
using loop_internal::EachDraw;
using loop_internal::EffectSelection;
using loop_internal::ErrorChance;
using loop_internal::Joined;
using loop_internal::RegimeOf;
using loop_internal::StartOf;
using loop_internal::kMaxDrawFactor;
// A calibration of the motion: the mean error over this many draws, on a grid of this many points over the prior range.
constexpr int kCalibrationDraws = 2;
constexpr int kCalibrationGrid = 9;
// A calibrated value within this share of its range from either end is on the range's edge.
constexpr double kCalibrationEdge = 0.01;

// The loop's work is estimated before its runs (issue 38: a sidecar's 1-m string made each run of the loop 100 s on
// 1e-5-s steps, and diagnose ran for hours saying "baseline: running 43 s simulated"). What a run costs is measured on
// its first kProbeS s of model time; how many runs the loop makes is bounded from its options (PlannedRuns), counting
// each effect of the vocabulary (at most kMaxEffects) with at most kParametersPerEffect parameters.
constexpr double kProbeS = 1;
constexpr int kMaxEffects = 10;
constexpr int kParametersPerEffect = 2;

// The model runs a loop with options `o` makes at most, estimated for effects of at most kParametersPerEffect
// parameters (rec01: 490 planned, 255 made): the first run; the draws (up to kMaxDrawFactor times
// LoopOptions::draws) of every model judged — the baseline, the base before and after each of its two calibrations,
// every fitted set (the singles, their pairs, and up to max_effects extensions or eliminations of each single), the
// model kept; the calibrations' grids; the screening fits and the full fits with their runs per parameter.
double PlannedRuns(const LoopOptions& o) {
  const double draw_runs = kMaxDrawFactor * o.draws;
  if (o.max_singles <= 0) return 1 + draw_runs;
  const double singles = o.max_singles, pairs = singles * (singles - 1) / 2, larger = o.max_effects * singles;
  const double p = kParametersPerEffect;
  const double fit_runs = singles * (o.evaluations_per_parameter * p + 2) +
                          pairs * (o.evaluations_per_parameter * 2 * p + 2) +
                          larger * (o.evaluations_per_parameter * 3 * p + 2);
  return 1 + draw_runs * (1 + 3 + singles + pairs + larger + 1) + 2 * kCalibrationGrid * kCalibrationDraws +
         kMaxEffects * (o.screening_evaluations_per_parameter * p + 4) + fit_runs;
}

// The loop's work before any of its runs over the whole span: PlannedRuns times one run's output samples or
// integration steps (the steps per second of the base's first kProbeS s, carried over the span; each run counted as at
// least kSweepRunMinimumWork, as sweeps do), refused above kSweepWorkPerMaxSample x --max-samples (1e9 by default)
// with InputError naming --evaluations and the estimate. Returns the planned runs.
double CheckLoopWork(const nlohmann::json& base, const LoopOptions& o, double full_duration) {
  nlohmann::json probe = base;
  const double probe_s = std::min(kProbeS, full_duration);
  probe["simulation"]["duration_s"] = probe_s;
  probe["statistics"] = {{"window_s", {0.0, probe_s}}};
  probe.erase("expect");
  const cases::Case c = cases::ParseCase(probe);
  const nlohmann::json summary = cases::RunCase(c).summary;
  const double steps = (summary.contains("steps") && summary["steps"].is_number() ? summary["steps"].get<double>() : 0) *
                       full_duration / probe_s;
  const double samples = c.settings.output_interval_s > 0 ? full_duration / c.settings.output_interval_s : 0.0;
  const double per_run = std::max({steps, samples, cases::kSweepRunMinimumWork});
  const double runs = PlannedRuns(o), work = runs * per_run;
  const double limit = cases::kSweepWorkPerMaxSample * cases::MaxSamples();
  if (work > limit)
    throw ParameterError("evaluations",
                     "the diagnosis plans up to about " + ReadableNumber(std::round(runs)) + " model runs of " +
                         ReadableNumber(std::round(full_duration)) + " s simulated, each about " +
                         ReadableNumber(std::round(per_run)) + " output samples or integration steps (the steps " +
                         "measured on its first " + ReadableNumber(probe_s) + " s): " + ReadableNumber(work) +
                         " in all, above the limit of " + ReadableNumber(limit) + " (" +
                         ReadableNumber(cases::kSweepWorkPerMaxSample) +
                         " x max_samples); ask for fewer draws or evaluations, a shorter recording, a case "
                         "with longer time steps, or raise max_samples", {"draws", "evaluations", "max_samples"});
  return runs;
}

// The recording and model must be of one scale: a field string against a lab rig differs by orders of magnitude.
void CheckScale(const Recording& rec, const Recording& model, const std::vector<ChannelMap>& maps) {
  auto rms = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x * x;
    return v.empty() ? 0.0 : std::sqrt(s / v.size());
  };
  for (std::size_t j = 0; j < maps.size(); ++j) {
    const double a = rms(rec.Channel(maps[j].recording)), b = rms(model.channels[j]);
    if (a > 0 && b > 0 && (a / b > 10 || b / a > 10))
      throw InputError("case", "the model's " + maps[j].model + " (typical level " + Significant(b, 3) +
                                   " in the recording's unit) and the recording's " + maps[j].recording + " (" +
                                   Significant(a, 3) + ") differ by a factor " + Fixed(std::max(a / b, b / a), 0) +
                                   ": the case does not describe the system recorded (a field string against a lab "
                                   "rig?); start from a case of the recorded system");
  }
}

nlohmann::json ProbabilitiesJson(const std::vector<ModelProbability>& models) {
  nlohmann::json out = nlohmann::json::array();
  for (const ModelProbability& m : models)
    out.push_back({{"effects", m.effects}, {"aic", std::isfinite(m.aic) ? nlohmann::json(m.aic) : nlohmann::json(nullptr)},
                   {"akaike_weight", m.weight}});
  return out;
}

// A finite number, or null (JSON has no NaN or infinity).

// The drive's law read off the recording's fit window (drive_law.hpp), null where it could not be read at all.
nlohmann::json DriveLawJson(const DriveLaw& law) {
  if (law.segments == 0) return nullptr;
  return {{"frequency_Hz", law.frequency_hz}, {"kp_Nms_per_rad", law.proportional},
          {"ki_Nm_per_rad", law.integral},    {"phase_deg", io::FiniteOrNull(law.Phase() * 180 / kPi)},
          {"coherence", law.coherence},       {"segments", law.segments},
          {"identified", law.Identified()}};
}

// The recorded bit speed's lag behind the virtual sensor's estimate (estimation/metrics.hpp), on the fit window.
nlohmann::json TelemetryLagJson(const estimation::TelemetryLag& lag) {
  return {{"lag_s", lag.lag_s},
          {"correlation", io::FiniteOrNull(lag.correlation)},
          {"correlation_at_zero", io::FiniteOrNull(lag.correlation_at_zero)},
          {"found", lag.found}};
}

nlohmann::json InRegimeJson(const std::vector<char>& in_regime) {
  nlohmann::json out = nlohmann::json::array();
  for (char c : in_regime) out.push_back(c != 0);
  return out;
}

// What the loop says as each step ends.
using Say = std::function<void(const std::string&)>;

// The median draw's channels, features and errors, into the loop's fields for a model (baseline or fitted).
void Adopt(const Judged& j, Recording& model, FeatureSet& fit, FeatureSet& held_out, double& fit_error,
           double& held_out_error) {
  model = j.model, fit = j.fit, held_out = j.held_out;
  fit_error = j.fit_error, held_out_error = j.held_out_error;
}

// A calibrated base before effects: the base's uncertain parameters, within their prior ranges, fitted in order, each
// to what it moves (a level: the fit window's means and period; the motion: all its features). `base` and
// loop.baseline_document take each calibration that, judged over draws through both windows, brings the base closer
// on the fit window and leaves the held-out window no worse beyond chance.
void CalibrateBase(const ModelRuns& runner, const LoopOptions& o, const Say& say, nlohmann::json& base,
                   DiagnosisLoop& loop) {
  const double fit_duration = runner.FitDuration();
  FeatureSet levels = loop.recording_fit;
  const auto not_a_level = [](const Feature& f) {
    const std::string mean = " mean";
    const bool is_mean =
        f.name.size() > mean.size() && f.name.compare(f.name.size() - mean.size(), mean.size(), mean) == 0;
    return !(is_mean || f.name == "period_s");
  };
  levels.features.erase(std::remove_if(levels.features.begin(), levels.features.end(), not_a_level),
                        levels.features.end());
  // The motion is chaotic: a calibration that reads it is judged on the mean over draws (one draw's error moves by
  // chance as much as a 5 % change of the rock does).
  const auto fit_window_error = [&](const nlohmann::json& doc, const FeatureSet& target, int draws) {
    double sum = 0;
    for (int d = 0; d < draws; ++d)
      sum += FeatureDistance(runner.FitFeatures(runner.Run(Drawn(doc, d), fit_duration, ModelRuns::Tolerance::kFit)),
                             target);
    return sum / draws;
  };
  const std::vector<Calibration> calibrations = BaseCalibrations(base);
  if (calibrations.empty()) return;
  const auto judge = [&](const nlohmann::json& doc) {
    Draws draws = runner.RunDraws(doc, o.threads);
    loop.model_runs += static_cast<int>(draws.models.size()) + draws.failed;
    return runner.Judge(std::move(draws));
  };
  const double chance = ErrorChance(loop.recording_held_out);
  Judged current = judge(base);
  for (const Calibration& calibration : calibrations) {
    const bool motion = calibration.target == CalibrationTarget::kMotion;
    const int draws = motion ? kCalibrationDraws : 1;
    const FeatureSet& target = motion ? loop.recording_fit : levels;
    const std::vector<const Effect*> calibrated_effects = {&calibration.parameters};
    auto calibrated = [&](const std::vector<double>& u) { return Applied(base, calibrated_effects, u); };
    auto objective = [&](const std::vector<double>& u) {
      try {
        return fit_window_error(calibrated(u), target, draws);
      } catch (const InputError&) {
      } catch (const NumericalError&) {
      }
      return kFailedRun;
    };
    const std::vector<double> start = StartOf(calibrated_effects);
    MinimizeResult best;
    if (motion && start.size() == 1) {
      // One parameter read off a noisy objective: a grid over the prior range, which a local search's first steps
      // would mistake the noise for a slope on.
      best.best = start, best.value = kFailedRun;
      for (int i = 0; i < kCalibrationGrid; ++i) {
        const std::vector<double> u = {static_cast<double>(i) / (kCalibrationGrid - 1)};
        const double value = objective(u);
        best.evaluations += draws;
        if (value < best.value) best.value = value, best.best = u;
      }
    } else {
      MinimizeOptions mo;
      mo.max_evaluations = o.screening_evaluations_per_parameter * static_cast<int>(start.size()) + 3;
      mo.starts = 1;
      mo.seed = o.seed;
      best = MinimizeInUnitCube(objective, start, mo);
      best.evaluations *= draws;
    }
    loop.model_runs += best.evaluations;
    // The calibration stands only if, judged as every model is (its draws through both windows), it brings the base
    // closer on the fit window as a whole and leaves the held-out window no worse beyond chance: levels fixed at the
    // cost of the motion point to an effect (side friction raising the mean torque, not a softer rock; dev rec01:
    // sigma*l to its -20 % bound, the fit window's error 84 -> 99), and a rock that matches the fit window's transient
    // may leave the recording's regime later (train rec13: eps -10 %, the fit window 16.8 -> 0.44, held out 0.41 -> 20).
    std::optional<Judged> after;
    try {
      after = judge(calibrated(best.best));
    } catch (const NumericalError&) {
    }
    // A value on its box's edge is not an estimate of the rock: the box is wider than the formation's own spread
    // (BASELINE.md: eps +-15 %, sigma l +-10 %; the box +-20 %), so a fit that leans on its wall is absorbing what the
    // base cannot make with any rock — an effect's work (dev rec07: side friction missing, eps to +20 % and sigma l
    // to -20 %, the KEY's rock +13 % and -7 %; the side friction fitted on that base predicted the held-out half 2.2
    // off, the same friction calibrated with (eps -10 %) 0.34).
    const bool on_edge = std::any_of(best.best.begin(), best.best.end(),
                                     [](double u) { return u < kCalibrationEdge || u > 1 - kCalibrationEdge; });
    const bool kept = after && !on_edge && after->fit_error < current.fit_error &&
                      after->held_out_error < current.held_out_error + chance;
    std::size_t k = 0;
    std::string moved;
    for (const EffectParameter& p : calibration.parameters.parameters) {
      const double value = FromUnit(p, best.best[k++]);
      loop.calibration.push_back({calibration.parameters.name, p.name, p.unit, value, p.start, p.lower, p.upper, kept});
      moved += (moved.empty() ? "" : ", ") + p.name + " " + Significant(p.start, 4) + " -> " + Significant(value, 4) +
               " (" + Fixed(100 * (value / p.start - 1), 1) + " %)";
    }
    say("base calibration on the fit window's " + std::string(motion ? "motion (every feature" : "levels (means, period") +
        (draws > 1 ? ", " + std::to_string(draws) + " draws)" : ")") + ": " + moved + "; judged over " +
        std::to_string(o.draws) + " draws: fit window's error " + Significant(current.fit_error, 3) + " -> " +
        (after ? Significant(after->fit_error, 3) + ", held out " + Significant(current.held_out_error, 3) + " -> " +
                     Significant(after->held_out_error, 3)
                : std::string("a failed run")) +
        (kept      ? ": kept"
         : on_edge ? ": not kept, on the edge of its range (an effect's work, not the rock's); the case's value stands"
                   : ": not kept, the case's value stands"));
    if (kept) {
      base = calibrated(best.best);
      loop.baseline_document = base;
      loop.calibration_kept = true;
      current = std::move(*after);
    }
  }
}

// The baseline judged over its draws through both windows, into the loop's baseline fields; the candidates' work budget
// set from it. Says how many draws are in the recording's regime and the baseline's errors.
Judged JudgeBaseline(ModelRuns& runner, const nlohmann::json& base, const LoopOptions& o, const Say& say,
                     DiagnosisLoop& loop) {
  Draws baseline_draws = runner.RunDraws(base, o.threads);
  // The candidates' work budget: the costliest of the baseline's draws (one that bounces costs more than one that
  // drills).
  runner.SetWorkBudget();
  loop.model_runs += static_cast<int>(baseline_draws.models.size());
  const Judged baseline = runner.Judge(std::move(baseline_draws));
  Adopt(baseline, loop.baseline_model, loop.baseline_fit, loop.baseline_held_out, loop.baseline_fit_error,
        loop.baseline_held_out_error);
  loop.baseline_held_out_draw_errors = baseline.held_out_draw_errors;
  loop.baseline_held_out_mean = baseline.held_out_mean;
  loop.baseline_draw_in_regime = baseline.draw_in_regime;
  loop.baseline_draw_seeds = baseline.draw_seeds;
  const auto first_in_regime = static_cast<std::size_t>(
      std::find(baseline.draw_in_regime.begin(), baseline.draw_in_regime.end(), 1) - baseline.draw_in_regime.begin());
  loop.fit_draw = first_in_regime < baseline.draw_seeds.size() ? baseline.draw_seeds[first_in_regime] : 0;
  const double k_features = FeatureCount(loop.recording_fit);
  loop.baseline_aic = k_features * std::log(loop.baseline_fit_error);
  const int baseline_in_regime = static_cast<int>(
      std::count(loop.baseline_draw_in_regime.begin(), loop.baseline_draw_in_regime.end(), 1));
  if (baseline_in_regime < static_cast<int>(loop.baseline_draw_in_regime.size()))
    say("baseline: " + std::to_string(baseline_in_regime) + " of " +
        std::to_string(loop.baseline_draw_in_regime.size()) + " draws in the recording's regime (" +
        (loop.recording_bounces ? "the bit bounces" : "the bit stays on the bottom") + ", off the bottom " +
        Fixed(100 * loop.recorded_off_bottom_share, 1) + " % of the time): the model has both regimes here, and " +
        (baseline_in_regime ? "is judged on those draws; the fits run draw " + std::to_string(loop.fit_draw)
                            : std::string("none is in the recording's: judged on all")));
  say("baseline: error " + Significant(loop.baseline_fit_error, 3) + " on the fit window, " +
      Significant(loop.baseline_held_out_error, 3) + " held out" +
      (loop.baseline_held_out_draw_errors.size() > 1
           ? " (draws alone: " + EachDraw(loop.baseline_held_out_draw_errors, loop.baseline_draw_in_regime) + ")"
           : ""));
  return baseline;
}

// The model that stands, judged over its draws: the kept candidate's effects applied to the base, or the base itself.
// Writes loop.fitted_document; a kept fit whose held-out motion is not the recording's is rejected here.
Judged JudgeStandingModel(ModelRuns& runner, const nlohmann::json& base, const Judged& baseline, const LoopOptions& o,
                          const Say& say, DiagnosisLoop& loop) {
  loop.fitted_document = base;
  Judged fitted = baseline;
  if (loop.kept >= 0) {
    const Candidate& c = loop.candidates[loop.kept];
    std::size_t k = 0;
    for (const std::string& name : c.effects)
      for (const Effect& e : loop.proposals)
        if (e.name == name) {
          std::vector<double> values;
          for (std::size_t j = 0; j < e.parameters.size(); ++j) values.push_back(c.parameters[k++].value);
          e.apply(loop.fitted_document, values);
        }
    Draws models = runner.RunDraws(loop.fitted_document, o.threads);
    loop.model_runs += static_cast<int>(models.models.size());
    fitted = runner.Judge(std::move(models));
    // A fit whose motion over the held-out window is not the recording's (stick-slip against smooth, bouncing against
    // on the bottom: its judged draw) where the baseline's is, is rejected, however its features compare: it explains
    // the recording with another motion (issue 32 item 4).
    const bool bounces = runner.RecordingBounces();
    const bool fitted_bounces = runner.InRegime(fitted.model) ? bounces : !bounces;
    const std::string recorded = RegimeOf(loop.recording_held_out, bounces);
    const std::string model = RegimeOf(fitted.held_out, fitted_bounces);
    const Feature* stuck = loop.recording_held_out.Find("stick_fraction");
    if (stuck && loop_internal::RejectedForRegime(
                     loop_internal::MotionOf(loop.recording_held_out, bounces),
                     loop_internal::MotionOf(fitted.held_out, fitted_bounces),
                     loop_internal::MotionOf(baseline.held_out, runner.InRegime(baseline.model) ? bounces : !bounces),
                     stuck->scale)) {
      Candidate& rejected = loop.candidates[loop.kept];
      rejected.kept = false;
      rejected.verdict = "rejected: held out " + model + " where the recording is " + recorded +
                         " (and the baseline); it qualified: " + rejected.verdict;
      say("rejected " + Joined(rejected.effects) + ": its held-out window is " + model + ", the recording's " +
          recorded + " (the baseline's too)");
      loop.regime_rejected = rejected.effects;
      loop.kept = -1;
      loop.fitted_document = base;
      fitted = baseline;
    }
  }
  return fitted;
}

// What the standing model leaves unexplained on the held-out window: features more than 3 scales off, or present on one
// side only.
std::vector<std::string> Unexplained(const FeatureSet& model, const FeatureSet& recorded) {
  std::vector<std::string> out;
  // The envelopes' correlogram is one feature read at several lags: one entry, where it counts.
  const CorrelogramDifference correlogram = CompareCorrelograms(model, recorded);
  if (correlogram.rms_scales > 3)
    out.push_back("hook load and weight on bit envelopes' correlogram: " + Fixed(correlogram.rms_scales, 1) +
                  " scales rms over its lags, most at " + Fixed(correlogram.largest_at_lag_s, 1) + " s");
  for (const Feature& f : recorded.features) {
    if (f.name.rfind(kEnvelopeCorrelation, 0) == 0) continue;
    const double m = model.Value(f.name);
    if (std::isfinite(f.value) && std::isfinite(m) && std::abs(m - f.value) > 3 * f.scale)
      out.push_back(f.name + ": model " + Significant(m, 4) + " against " + Significant(f.value, 4) + " recorded (" +
                    Fixed((m - f.value) / f.scale, 1) + " scales)");
    else if (std::isfinite(f.value) != std::isfinite(m))
      out.push_back(f.name + ": " + (std::isfinite(m) ? "only the model has it" : "only the recording has it"));
  }
  return out;
}

// The windows in order and finite: the fit window, then the held-out window from its end on.
bool WindowsAreValid(const LoopOptions& o, std::string* error) {
  return FiniteField(error, "fit_begin_s", o.fit_begin_s) &&
         OrderedFields(error, "fit_begin_s", o.fit_begin_s, "fit_end_s", o.fit_end_s,
                       "the fit window must end after it begins") &&
         OrderedFields(error, "fit_end_s", o.fit_end_s, "held_out_begin_s", o.held_out_begin_s,
                       "the held-out window must not begin before the fit window ends", true) &&
         OrderedFields(error, "held_out_begin_s", o.held_out_begin_s, "held_out_end_s", o.held_out_end_s,
                       "the held-out window must end after it begins") &&
         FiniteField(error, "held_out_end_s", o.held_out_end_s);
}

}  // namespace

bool LoopOptions::IsValid(std::string* error) const {
  return FiniteField(error, "model_time_offset_s", model_time_offset_s) && WindowsAreValid(*this, error) &&
         FractionField(error, "margin", margin) &&
         WholeField(error, "evaluations_per_parameter", evaluations_per_parameter, 1) &&
         WholeField(error, "screening_evaluations_per_parameter", screening_evaluations_per_parameter, 1) &&
         WholeField(error, "max_singles", max_singles, 0) && WholeField(error, "max_effects", max_effects, 1) &&
         (fit_tolerance == 0 || (fit_tolerance >= 1e-14 && fit_tolerance <= 1e-2) ||
          Invalid(error, "fit_tolerance", "expected 0 (the case's) or a tolerance in [1e-14, 1e-2], got " +
                                              ReadableNumber(fit_tolerance))) &&
         WholeField(error, "threads", threads, 1) &&
         ((sample_window_s >= 0 && sample_window_s <= 60) ||
          Invalid(error, "sample_window_s", "expected seconds in [0, 60], got " + ReadableNumber(sample_window_s))) &&
         WholeField(error, "draws", draws, 1, 20) && NestedValid(error, "features", features.IsValid(error));
}

LoopOptions DefaultLoopOptions(const cases::Case& c, const Recording& rec, double offset_s, double settle_s) {
  LoopOptions o;
  o.model_time_offset_s = offset_s;
  const double usable_begin = rec.time_s.front() + (offset_s > 0 ? settle_s : 0);
  const double usable_end = std::min(rec.time_s.back(), c.settings.duration_s - offset_s);
  o.fit_begin_s = usable_begin;
  o.fit_end_s = o.held_out_begin_s = 0.5 * (usable_begin + usable_end);
  o.held_out_end_s = usable_end;
  o.sample_window_s = rec.sample_interval_s;
  return o;
}

DiagnosisLoop RunDiagnosisLoop(const nlohmann::json& document, const Recording& raw, const LoopOptions& o,
                               const LoopProgress& progress) {
  ThrowIfInvalid(o);
  const Stopwatch clock;
  double mark = 0;  // the clock at the end of the last stage
  auto lap = [&](double& stage) {
    const double now = clock.Seconds();
    stage = now - mark;
    mark = now;
  };
  // What the loop does, said as it happens, and every 5 s on long steps (core/progress.hpp, where a program shows
  // it): the step it is in and the model runs started of those planned.
  Progress long_work("diagnosis");
  std::mutex step_mutex;
  std::string step = "preparing the recording";
  auto say = [&](const std::string& s) {
    {
      const std::lock_guard<std::mutex> lock(step_mutex);
      step = "after " + s.substr(0, s.find(':'));  // the loop says each step as it ends
    }
    if (progress) progress(s);
  };
  // 1. The recording made ready: mapped channels, artefacts masked, features, its noise and sampling in the case.
  const PreparedRecording prepared = PrepareRecording(document, raw, o);
  const Recording& rec = prepared.recording;
  DiagnosisLoop loop;
  loop.masked_samples = prepared.masked_samples;
  loop.channels_left_whole = prepared.channels_left_whole;
  loop.bit_speed = prepared.features.bit_speed;
  loop.noise = prepared.noise;
  loop.recording_fit = prepared.fit;
  loop.recording_held_out = prepared.held_out;
  nlohmann::json base = prepared.base;
  loop.baseline_document = base;

  ModelRuns runner(o, rec, prepared.whole, prepared.features, loop.recording_fit, loop.recording_held_out);
  const double full_duration = runner.FullDuration();
  loop.recorded_off_bottom_share = runner.RecordedOffBottomShare();
  loop.recording_bounces = runner.RecordingBounces();
  const int draws = o.draws;
  const double planned_runs = CheckLoopWork(base, o, full_duration);
  runner.OnRun([&](int started) {
    const std::lock_guard<std::mutex> lock(step_mutex);
    long_work.Count(step + ": model runs started", started, std::round(planned_runs), "planned");
  });
  say("work: up to about " + Fixed(planned_runs, 0) + " model runs of " + Fixed(full_duration, 0) +
      " s simulated");

  for (const std::string& channel : loop.channels_left_whole)
    say(channel + ": too many bursts for artefacts (over " + Fixed(100 * kMaxArtefactShare, 0) +
        " % of the samples): motion, left whole");
  // 2. The baseline on both windows, over the draws.
  say("baseline: running " + Fixed(full_duration, 0) + " s simulated" +
      (draws > 1 ? ", " + std::to_string(draws) + " draws" : std::string()));
  const Recording plain = runner.Run(base, full_duration);  // draw 0 of the case as given, from the cache below
  CheckScale(rec, plain, o.maps);
  runner.SetWorkBudget();
  loop.plain_fit_error = FeatureDistance(runner.FitFeatures(plain), loop.recording_fit);
  loop.plain_held_out_error = FeatureDistance(runner.HeldOutFeatures(plain), loop.recording_held_out);
  lap(loop.wall_seconds.preparing);
  // 2a. A calibrated base before effects (none where only the case's own errors are asked for).
  if (o.max_singles > 0 && o.calibrate_base) CalibrateBase(runner, o, say, base, loop);
  lap(loop.wall_seconds.calibration);
  const Judged baseline = JudgeBaseline(runner, base, o, say, loop);

  // 3. Proposals, strongest first. Those the case can model are fitted alone, then in pairs and larger sets (below:
  //    every effect of a set must earn its place).
  loop.proposals = ProposeEffects(base, loop.baseline_fit, loop.recording_fit);
  std::stable_sort(loop.proposals.begin(), loop.proposals.end(),
                   [](const Effect& a, const Effect& b) { return a.strength > b.strength; });
  for (const Effect& e : loop.proposals)
    if (e.strength > 0)
      say((e.Proposed() ? "proposed " : "indicated ") + e.name + " (evidence " + Fixed(e.strength, 1) + "): " + e.evidence);

  // 4. Every effect the case can model screened, fitted alone, in pairs and larger sets; rivals contest the best.
  lap(loop.wall_seconds.baseline);
  EffectSelection selection(o, runner, base, loop, say);
  selection.FindModelable();
  selection.Select();
  lap(loop.wall_seconds.selection);

  // 5. The model that stands, on both windows.
  const Judged fitted = JudgeStandingModel(runner, base, baseline, o, say, loop);
  Adopt(fitted, loop.fitted_model, loop.fitted_fit, loop.fitted_held_out, loop.fitted_fit_error,
        loop.fitted_held_out_error);
  if (o.measure_regime_margin)
    loop.regime_margin = loop_internal::MeasureRegimeMargin(loop.fitted_document, runner, loop.fit_draw,
                                                            loop.recording_held_out, o.threads);
  loop.model_runs += loop.regime_margin.runs;
  if (loop.regime_margin.measured) say(RegimeMarginText(loop.regime_margin));
  lap(loop.wall_seconds.fitted);
  loop.unexplained = Unexplained(loop.fitted_held_out, loop.recording_held_out);
  say("kept: " + (loop.kept >= 0 ? Joined(loop.candidates[loop.kept].effects) : std::string("nothing")) +
      "; held-out error " + Significant(loop.baseline_held_out_error, 3) + " -> " +
      Significant(loop.fitted_held_out_error, 3));
  loop.wall_seconds.total = clock.Seconds();
  say("time: " + Fixed(loop.wall_seconds.total, 0) + " s on the clock, of which the effects' fits " +
      Fixed(loop.wall_seconds.selection, 0) + " s and the base's calibration " +
      Fixed(loop.wall_seconds.calibration, 0) + " s");
  return loop;
}

void CheckPredictionTime(const LoopOptions& o, double until_s) {
  const double span = o.held_out_end_s - o.fit_begin_s;
  if (!(until_s > o.held_out_end_s && until_s <= o.held_out_end_s + 100 * span))
    throw ParameterError("predict_until", "expected a recording time after the held-out window's end, " +
                                            ReadableNumber(o.held_out_end_s) + " s, and at most " +
                                            ReadableNumber(o.held_out_end_s + 100 * span) + " s, got " +
                                            ReadableNumber(until_s));
}

Recording PredictFitted(const DiagnosisLoop& loop, const LoopOptions& o, const Recording& rec, double until_s) {
  CheckPredictionTime(o, until_s);
  nlohmann::json doc = loop.fitted_document;
  doc.erase("sensors");
  const double dt = rec.sample_interval_s > 0 ? rec.sample_interval_s : 0.01;
  const double duration = o.model_time_offset_s + until_s + dt;  // the last sample inside, whatever its rounding
  doc["simulation"]["duration_s"] = duration;
  const auto window = nlohmann::json::json_pointer("/statistics/window_s");
  if (doc.contains(window)) doc.at(window) = {std::min(doc.at(window)[0].get<double>(), 0.5 * duration), duration};
  const cases::RunResult run = cases::RunCase(cases::ParseCase(doc)).result;
  Recording grid = rec;  // the recording's sampling carried on past its end
  grid.time_s.clear();
  // (A sample interval read from a CSV carries rounding: 150 s at 0.010000000000002 s is still 15 000 samples.)
  const auto samples = static_cast<long>(std::floor((until_s - o.fit_begin_s) / dt + 1e-6));
  for (long k = 0; k <= samples; ++k) grid.time_s.push_back(o.fit_begin_s + static_cast<double>(k) * dt);
  Recording out = ModelRecording(run, o.maps, grid, o.model_time_offset_s, o.fit_begin_s, until_s + 0.5 * dt);
  out.source = "prediction of the fitted model";
  return out;
}

std::vector<ModelProbability> AkaikeWeights(const DiagnosisLoop& loop) {
  std::vector<ModelProbability> models = {{{}, loop.baseline_aic, 0}};
  for (const Candidate& c : loop.candidates) {
    if (!c.failure.empty() || !std::isfinite(c.aic)) continue;
    std::vector<std::string> set = c.effects;
    std::sort(set.begin(), set.end());
    auto same = std::find_if(models.begin(), models.end(), [&](const ModelProbability& m) { return m.effects == set; });
    if (same == models.end()) models.push_back({set, c.aic, 0});
    else same->aic = std::min(same->aic, c.aic);
  }
  double best = std::numeric_limits<double>::infinity(), total = 0;
  for (const ModelProbability& m : models)
    if (std::isfinite(m.aic)) best = std::min(best, m.aic);
  for (ModelProbability& m : models) total += m.weight = std::isfinite(m.aic) ? std::exp(-0.5 * (m.aic - best)) : 0.0;
  for (ModelProbability& m : models) m.weight = total > 0 ? m.weight / total : 0.0;
  std::stable_sort(models.begin(), models.end(),
                   [](const ModelProbability& a, const ModelProbability& b) { return a.weight > b.weight; });
  return models;
}

namespace {
nlohmann::json RegimeMarginJson(const RegimeMargin& m) {
  if (!m.measured) return {{"measured", false}, {"runs", m.runs}};
  return {{"measured", true},
          {"parameter", "/model/top/speed_rad_s (every knot scaled)"},
          {"recorded_regime", m.recorded},
          {"model_regime", m.model},
          {"lower_change_percent", io::FiniteOrNull(m.lower_percent)},
          {"upper_change_percent", io::FiniteOrNull(m.upper_percent)},
          {"searched_percent", kRegimeSearchPercent},
          {"near_edge", m.near_edge},
          {"near_edge_percent", kNearRegimeEdgePercent},
          {"runs", m.runs},
          {"text", RegimeMarginText(m)}};
}
// The baseline's held-out error on the fits' draw (the screening's reference), null where that draw failed.
nlohmann::json FitDrawError(const DiagnosisLoop& loop) {
  const auto& seeds = loop.baseline_draw_seeds;
  const auto at = static_cast<std::size_t>(std::find(seeds.begin(), seeds.end(), loop.fit_draw) - seeds.begin());
  if (at >= loop.baseline_held_out_draw_errors.size() || !std::isfinite(loop.baseline_held_out_draw_errors[at]))
    return nullptr;
  return loop.baseline_held_out_draw_errors[at];
}

}  // namespace

nlohmann::json DiagnosisLoopToJson(const DiagnosisLoop& loop) {
  nlohmann::json hypotheses = nlohmann::json::array(), candidates = nlohmann::json::array(),
                 fitted = nlohmann::json::array(), proposals = nlohmann::json::array(), noise = nlohmann::json::object();
  for (const Effect& e : loop.proposals)
    proposals.push_back({{"effect", e.name}, {"component", e.component}, {"evidence_strength", e.strength},
                         {"evidence", e.evidence}});
  for (const Candidate& c : loop.candidates) {
    nlohmann::json parameters = nlohmann::json::array();
    for (const FittedParameter& p : c.parameters)
      parameters.push_back({{"effect", p.effect},
                            {"name", p.name},
                            {"unit", p.unit},
                            {"value", io::FiniteOrNull(p.value)},
                            {"sigma", io::FiniteOrNull(p.sigma)},
                            {"bounds", {p.lower, p.upper}}});
    candidates.push_back({{"effects", c.effects},
                          {"parameters", parameters},
                          {"fit_error", io::FiniteOrNull(c.fit_error)},
                          {"held_out_error", io::FiniteOrNull(c.held_out_error)},
                          {"held_out_error_each_draw", c.held_out_draw_errors},
                          {"draw_in_regime", InRegimeJson(c.draw_in_regime)},
                          {"aic", io::FiniteOrNull(c.aic)},
                          {"evaluations", c.evaluations},
                          {"redrawn_runs", c.redrawn_runs},
                          {"failed_runs", c.failed_runs},
                          {"failed_draws", c.failed_draws},
                          {"first_failed_run", c.first_failure},
                          {"kept", c.kept},
                          {"failure", c.failure},
                          {"verdict", c.verdict},
                          {"wall_seconds", c.wall_seconds}});
  }
  if (loop.kept >= 0) {
    const Candidate& c = loop.candidates[loop.kept];
    fitted = candidates[loop.kept]["parameters"];
    for (const std::string& name : c.effects) {
      const bool calibration = std::any_of(loop.proposals.begin(), loop.proposals.end(),
                                           [&](const Effect& e) { return e.name == name && e.calibration; });
      if (calibration) continue;  // a base parameter moved beside the effects, not an effect: fitted_parameters has it
      double estimate = std::nan("");
      std::string unit;
      for (const FittedParameter& p : c.parameters)
        if (p.effect == name && !std::isfinite(estimate)) estimate = p.value, unit = p.unit;
      std::string evidence;
      for (const Effect& e : loop.proposals)
        if (e.name == name) evidence = e.evidence;
      hypotheses.push_back(
          {{"effect", name}, {"estimate", io::FiniteOrNull(estimate)}, {"unit", unit}, {"evidence", evidence}});
    }
  }
  nlohmann::json screening = nlohmann::json::array(), ambiguous = nlohmann::json::array();
  for (const Candidate& c : loop.screening)
    screening.push_back({{"effects", c.effects},
                         {"fit_error", io::FiniteOrNull(c.fit_error)},
                         {"held_out_error_one_draw", io::FiniteOrNull(c.held_out_error)},
                         {"evaluations", c.evaluations},
                         {"failure", c.failure},
                         {"wall_seconds", c.wall_seconds}});
  for (const Candidate& c : loop.rivals)
    ambiguous.push_back({{"effects", c.effects},
                         {"held_out_error", io::FiniteOrNull(c.held_out_error)},
                         {"fit_error", io::FiniteOrNull(c.fit_error)}});
  nlohmann::json calibration = nlohmann::json::array();
  for (const CalibratedParameter& p : loop.calibration)
    calibration.push_back({{"calibration", p.calibration}, {"name", p.name}, {"unit", p.unit},
                           {"case_value", p.case_value}, {"value", p.value},
                           {"moved_percent", 100 * (p.value / p.case_value - 1)}, {"bounds", {p.lower, p.upper}},
                           {"kept", p.kept}});
  for (const auto& [channel, sigma] : loop.noise) noise[channel] = sigma;
  nlohmann::json masked = nlohmann::json::object();
  for (const auto& [channel, count] : loop.masked_samples) masked[channel] = count;
  return {{"hypotheses", hypotheses},
          {"held_out",
           {{"window_s", {loop.recording_held_out.begin_s, loop.recording_held_out.end_s}},
            {"error_before", loop.baseline_held_out_error},
            {"error_before_each_draw", loop.baseline_held_out_draw_errors},
            {"draw_in_regime", InRegimeJson(loop.baseline_draw_in_regime)},
            {"draws", loop.baseline_held_out_draw_errors.size()},
            {"recorded_off_bottom_share", io::FiniteOrNull(loop.recorded_off_bottom_share)},
            {"recording_bounces", loop.recording_bounces},
            {"fit_draw", loop.fit_draw},
            {"error_after", loop.fitted_held_out_error},
            {"error_chance", loop.error_chance}}},
          {"fit",
           {{"window_s", {loop.recording_fit.begin_s, loop.recording_fit.end_s}},
            {"error_before", loop.baseline_fit_error},
            {"error_after", loop.fitted_fit_error},
            {"baseline_aic", loop.baseline_aic}}},
          {"ambiguous", ambiguous},
          {"model_probabilities", ProbabilitiesJson(AkaikeWeights(loop))},
          {"base_calibration", {{"parameters", calibration}, {"kept", loop.calibration_kept}}},
          {"plain_case",
           {{"fit_error_one_draw", io::FiniteOrNull(loop.plain_fit_error)},
            {"held_out_error_one_draw", io::FiniteOrNull(loop.plain_held_out_error)}}},
          {"screening", {{"baseline_held_out_error_one_draw", FitDrawError(loop)}, {"candidates", screening}}},
          {"fitted_parameters", fitted},
          {"candidates", candidates},
          {"proposals", proposals},
          {"unexplained", loop.unexplained},
          {"regime_margin", RegimeMarginJson(loop.regime_margin)},
          {"regime_rejected", loop.regime_rejected},
          {"noise_std", noise},
          {"recorded_drive_law", DriveLawJson(loop.recording_fit.drive)},
          {"recorded_telemetry_lag", TelemetryLagJson(loop.recording_fit.telemetry)},
          {"artefact_samples_masked", masked},
          {"channels_left_whole", loop.channels_left_whole},
          {"model_runs", loop.model_runs},
          {"wall_seconds",
           {{"preparing", loop.wall_seconds.preparing},
            {"calibration", loop.wall_seconds.calibration},
            {"baseline", loop.wall_seconds.baseline},
            {"selection", loop.wall_seconds.selection},
            {"fitted", loop.wall_seconds.fitted},
            {"total", loop.wall_seconds.total}}},
          {"features_held_out", FeatureSetToJson(loop.fitted_held_out, loop.recording_held_out)},
          {"features_fit_baseline", FeatureSetToJson(loop.baseline_fit, loop.recording_fit)}};
}

}  // namespace drillwave::diagnosis
