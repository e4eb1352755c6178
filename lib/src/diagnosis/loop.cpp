#include "drillwave/diagnosis/loop.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/sensors.hpp"
#include "drillwave/io/json_reader.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/parallel.hpp"
#include "drillwave/core/sampled.hpp"
#include "drillwave/diagnosis/minimize.hpp"
#include "drillwave/diagnosis/signals.hpp"
#include "model_runs.hpp"
#include "prepared_recording.hpp"

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
// At most this many of the singles fitted in full are chosen by the rules' evidence, the others by screening.
constexpr int kRuleSingles = 2;
// A fit's run that lands in the other regime is drawn again, at most this many times in all.
constexpr int kFitDraws = 3;
// A calibration of the motion: the mean error over this many draws, on a grid of this many points over the prior range.
constexpr int kCalibrationDraws = 2;
constexpr int kCalibrationGrid = 9;

std::string Joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : " + ") + n;
  return s.empty() ? "baseline" : s;
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

// How much a feature distance e over K features moves by chance from one window to the next. Each difference in
// scales is z = b + s n (a bias b the model keeps, noise n of unit variance, s <= 1 where the scale's floor is above
// the feature's own spread), e = mean(z^2) = B + s^2 and var(e) = (4 s^2 B + 2 s^4) / K. Not knowing the split, s^2 is
// taken as large as e allows: a model within its features' noise (e < 1) moves by e sqrt(2 / K), one off by a bias
// by sqrt((2 + 4 (e - 1)) / K) — far less than e sqrt(2 / K) once e is large (rec04 of synthetic-train: a BHA's 6.5
// against axial decoupling's 9.2 is 1.6 standard deviations apart, not 0.8).
double ErrorSpread(double e, double k_features) {
  const double s2 = std::clamp(e, 0.0, 1.0);
  return std::sqrt((2 * s2 * s2 + 4 * s2 * std::max(e - 1, 0.0)) / std::max(1.0, k_features));
}

// `doc` with each effect switched on at its parameters' values u (in their unit cubes, one after the other).
nlohmann::json Applied(nlohmann::json doc, const std::vector<const Effect*>& effects, const std::vector<double>& u) {
  std::size_t k = 0;
  for (const Effect* e : effects) {
    std::vector<double> values;
    for (const EffectParameter& p : e->parameters) values.push_back(FromUnit(p, u[k++]));
    e->apply(doc, values);
  }
  return doc;
}

// The effects' first values, in their unit cubes.
std::vector<double> StartOf(const std::vector<const Effect*>& effects) {
  std::vector<double> u;
  for (const Effect* e : effects)
    for (const EffectParameter& p : e->parameters) u.push_back(ToUnit(p, p.start));
  return u;
}

nlohmann::json InRegimeJson(const std::vector<char>& in_regime) {
  nlohmann::json out = nlohmann::json::array();
  for (char c : in_regime) out.push_back(c != 0);
  return out;
}

// "648, 4.4 (another regime), 1.1"
std::string EachDraw(const std::vector<double>& errors, const std::vector<char>& in_regime) {
  std::string each;
  for (std::size_t d = 0; d < errors.size(); ++d)
    each += (each.empty() ? "" : ", ") + Significant(errors[d], 3) + (in_regime[d] ? "" : " (another regime)");
  return each;
}

// The median draw's channels, features and errors, into the loop's fields for a model (baseline or fitted).
void Adopt(const Judged& j, Recording& model, FeatureSet& fit, FeatureSet& held_out, double& fit_error,
           double& held_out_error) {
  model = j.model, fit = j.fit, held_out = j.held_out;
  fit_error = j.fit_error, held_out_error = j.held_out_error;
}

// How much a held-out error moves by chance: for a model within its features' noise the error (the mean of K squared
// differences in scales) varies by sqrt(2 / K) from one window to the next.
double ErrorChance(const FeatureSet& held_out) { return std::sqrt(2.0 / std::max(1.0, FeatureCount(held_out))); }

// A calibrated base before effects: the base's uncertain parameters, within their prior ranges, fitted in order, each
// to what it moves (a level: the fit window's means and period; the motion: all its features). `base` and
// loop.baseline_document take each calibration that, judged over draws through both windows, brings the base closer
// on the fit window and leaves the held-out window no worse beyond chance.
void CalibrateBase(const ModelRuns& runner, const LoopOptions& o, const std::function<void(const std::string&)>& say,
                   nlohmann::json& base, DiagnosisLoop& loop) {
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
    Draws draws = runner.RunDraws(doc, std::max(1, o.threads));
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
    const bool kept = after && after->fit_error < current.fit_error &&
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
        (kept ? ": kept" : ": not kept, the case's value stands"));
    if (kept) {
      base = calibrated(best.best);
      loop.baseline_document = base;
      loop.calibration_kept = true;
      current = std::move(*after);
    }
  }
}

}  // namespace

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
  auto say = [&](const std::string& s) {
    if (progress) progress(s);
  };
  // 1. The recording made ready: mapped channels, artefacts masked, features, its noise and sampling in the case.
  const PreparedRecording prepared = PrepareRecording(document, raw, o);
  const Recording& rec = prepared.recording;
  DiagnosisLoop loop;
  loop.masked_samples = prepared.masked_samples;
  loop.channels_left_whole = prepared.channels_left_whole;
  loop.noise = prepared.noise;
  loop.recording_fit = prepared.fit;
  loop.recording_held_out = prepared.held_out;
  nlohmann::json base = prepared.base;
  loop.baseline_document = base;

  ModelRuns runner(o, rec, prepared.whole, prepared.features, loop.recording_fit, loop.recording_held_out);
  const double full_duration = runner.FullDuration(), fit_duration = runner.FitDuration();
  using Tolerance = ModelRuns::Tolerance;
  loop.recorded_off_bottom_share = runner.RecordedOffBottomShare();
  loop.recording_bounces = runner.RecordingBounces();
  const int draws = std::max(1, o.draws);

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
  // 2a. A calibrated base before effects (none where only the case's own errors are asked for).
  if (o.max_singles > 0 && o.calibrate_base) CalibrateBase(runner, o, say, base, loop);
  Draws baseline_draws = runner.RunDraws(base, std::max(1, o.threads));
  // The candidates' work budget: the costliest of the baseline's draws (one that bounces costs more than one that
  // drills).
  runner.SetWorkBudget();
  loop.model_runs += static_cast<int>(baseline_draws.models.size());
  const Judged baseline = runner.Judge(std::move(baseline_draws));
  Adopt(baseline, loop.baseline_model, loop.baseline_fit, loop.baseline_held_out, loop.baseline_fit_error,
        loop.baseline_held_out_error);
  loop.baseline_held_out_draw_errors = baseline.held_out_draw_errors;
  loop.baseline_draw_in_regime = baseline.draw_in_regime;
  loop.fit_draw = static_cast<int>(std::find(baseline.draw_in_regime.begin(), baseline.draw_in_regime.end(), 1) -
                                   baseline.draw_in_regime.begin());
  if (loop.fit_draw == static_cast<int>(baseline.draw_in_regime.size())) loop.fit_draw = 0;
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

  // 3. Proposals, strongest first. Those the case can model are fitted alone, then in pairs and larger sets (below:
  //    every effect of a set must earn its place).
  loop.proposals = ProposeEffects(base, loop.baseline_fit, loop.recording_fit);
  std::stable_sort(loop.proposals.begin(), loop.proposals.end(),
                   [](const Effect& a, const Effect& b) { return a.strength > b.strength; });
  for (const Effect& e : loop.proposals)
    if (e.strength > 0)
      say((e.Proposed() ? "proposed " : "indicated ") + e.name + " (evidence " + Fixed(e.strength, 1) + "): " + e.evidence);

  auto effects_of = [&](const std::vector<int>& set) {
    std::vector<const Effect*> effects;
    for (int i : set) effects.push_back(&loop.proposals[i]);
    return effects;
  };
  auto document_at = [&](const std::vector<int>& set, const std::vector<double>& u) {
    return Applied(base, effects_of(set), u);
  };
  auto start_of = [&](const std::vector<int>& set) { return StartOf(effects_of(set)); };
  // Every effect is a candidate: the rules' evidence orders the work (the proposals are sorted by it), never gates it.
  std::vector<int> modelable;
  for (std::size_t i = 0; i < loop.proposals.size(); ++i) {
    try {
      cases::ParseCase(document_at({static_cast<int>(i)}, start_of({static_cast<int>(i)})));
      modelable.push_back(static_cast<int>(i));
    } catch (const InputError& e) {  // the case's kind has no such component
      Candidate c;
      c.effects = {loop.proposals[i].name};
      c.failure = std::string("cannot be modelled with this case: ") + e.what();
      say(loop.proposals[i].name + ": " + c.failure);
      loop.candidates.push_back(c);
    }
  }

  // A set whose parameters move only the sensors (a telemetry delay) leaves the motion as it is: the baseline's run
  // serves its whole fit from the cache, so it is fitted on the very motion it is judged by, at the case's tolerance
  // (rec04: a 2.1-s delay fitted at 1e-4 on a motion of its own came out 2.68 s, at the case's 1e-5 2.08 s).
  auto moves_only_sensors = [&](const std::vector<int>& set) {
    nlohmann::json low = document_at(set, std::vector<double>(start_of(set).size(), 0.25));
    nlohmann::json high = document_at(set, std::vector<double>(start_of(set).size(), 0.75));
    low.erase("sensors"), high.erase("sensors");
    return low == high;
  };

  std::mutex progress_mutex;
  const FeatureSet& target = loop.recording_fit;
  // A screening fit (screening = true) is cheap: one start, a few evaluations per parameter, no curvature, and it is
  // judged on one free run over the whole span (the fit draw) instead of the draws' median.
  auto fit_candidate = [&](const std::vector<int>& set, std::vector<double> start, int threads, bool screening) {
    Candidate c;
    for (int i : set) c.effects.push_back(loop.proposals[i].name);
    const bool sensors_only = moves_only_sensors(set);
    std::mutex count_mutex;  // the fit's starts may run side by side
    auto count = [&](int& counter) {
      const std::lock_guard<std::mutex> lock(count_mutex);
      ++counter;
    };
    auto count_failure = [&](const std::exception& e) {
      const std::lock_guard<std::mutex> lock(count_mutex);
      if (c.failed_runs++ == 0) c.first_failure = e.what();
    };
    auto objective = [&](const std::vector<double>& u) {
      count(c.evaluations);
      try {
        // A run in the other regime is drawn again (at most kFitDraws times): the objective is the error in the
        // recording's regime, not which attractor one start happened to reach.
        const nlohmann::json doc = document_at(set, u);
        Recording m;
        for (int k = 0; k < kFitDraws; ++k) {
          m = sensors_only ? runner.Run(Drawn(doc, loop.fit_draw + k), full_duration)
                           : runner.Run(Drawn(doc, loop.fit_draw + k), fit_duration, Tolerance::kFit);
          if (runner.InRegime(m)) break;
          if (k + 1 < kFitDraws) count(c.redrawn_runs);
        }
        return FeatureDistance(runner.FitFeatures(m), target);
      } catch (const InputError& e) {
        count_failure(e);
      } catch (const NumericalError& e) {
        count_failure(e);
      }
      return kFailedRun;
    };
    MinimizeOptions mo;
    mo.max_evaluations =
        (screening ? o.screening_evaluations_per_parameter : o.evaluations_per_parameter) * static_cast<int>(start.size()) + 1;
    mo.starts = start.empty() || screening ? 1 : 2;
    mo.seed = o.seed + static_cast<unsigned>(set.front()) * 31 + static_cast<unsigned>(set.size());
    mo.threads = threads;
    const MinimizeResult best = MinimizeInUnitCube(objective, start, mo);
    const std::vector<double> sigma_u = screening ? std::vector<double>(best.best.size(), std::nan(""))
                                                  : CurvatureSigma(objective, best.best, best.value, k_features);
    std::size_t k = 0;
    for (int i : set)
      for (const EffectParameter& p : loop.proposals[i].parameters) {
        const double v = FromUnit(p, best.best[k]);
        const double slope = p.log_scale ? v * std::log(p.upper / p.lower) : p.upper - p.lower;  // d value / d unit
        c.parameters.push_back({loop.proposals[i].name, p.name, p.unit, v, slope * sigma_u[k], p.lower, p.upper});
        ++k;
      }
    c.unit_values = best.best;
    c.start_values = start;
    try {
      Draws one;
      if (screening) {
        one.models.push_back(runner.Run(Drawn(document_at(set, best.best), loop.fit_draw), full_duration));
        one.in_regime.push_back(runner.InRegime(one.models.back()));
      }
      const Judged j = runner.Judge(screening ? std::move(one) : runner.RunDraws(document_at(set, best.best), threads));
      c.fit_error = j.fit_error;
      c.held_out_error = j.held_out_error;
      c.held_out_draw_errors = j.held_out_draw_errors;
      c.draw_in_regime = j.draw_in_regime;
      c.failed_draws = j.failed_draws;
    } catch (const NumericalError& e) {
      c.failure = std::string("the fitted model failed on the whole span: ") + e.what();
    } catch (const InputError& e) {
      c.failure = std::string("the fitted model failed on the whole span: ") + e.what();
    }
    c.aic = k_features * std::log(c.fit_error) + 2.0 * start.size();
    const std::lock_guard<std::mutex> lock(progress_mutex);
    say((screening ? "screening " : "") + Joined(c.effects) + ": " + std::to_string(c.evaluations + c.redrawn_runs) +
        " runs" +
        (c.failed_runs ? " (" + std::to_string(c.failed_runs) + " failed: " + c.first_failure + ")" : "") +
        (c.failure.empty() ? ", error " + Significant(c.fit_error, 3) + " fitted, " +
                                 Significant(c.held_out_error, 3) + " held out (baseline " +
                                 Significant(loop.baseline_held_out_error, 3) + ")" +
                                 (std::count(c.draw_in_regime.begin(), c.draw_in_regime.end(), 0)
                                      ? "; draws " + EachDraw(c.held_out_draw_errors, c.draw_in_regime)
                                      : std::string())
                           : ", not judged: " + c.failure));
    return c;
  };
  // 4. The decision: held-out error below (1 - margin) of the reference's, by more than chance moves it, and a lower
  //    AIC on the fit window. Each feature's difference is counted in the spread between two runs of the same
  //    physics, so for a model that matches, the error (the mean of K squared differences) is about 1 and varies by
  //    sqrt(2 / K) from one window to the next: a smaller gain is not evidence, whatever the relative margin says.
  loop.error_chance = ErrorChance(loop.recording_held_out);
  auto qualifies = [&](const Candidate& c, double reference_error, double reference_aic) {
    return c.failure.empty() && c.held_out_error < (1 - o.margin) * reference_error &&
           reference_error - c.held_out_error > loop.error_chance && c.aic < reference_aic;
  };

  auto indices_of = [&](const Candidate& c) {
    std::vector<int> set;
    for (const std::string& name : c.effects)
      for (int i : modelable)
        if (loop.proposals[i].name == name) set.push_back(i);
    std::sort(set.begin(), set.end());
    return set;
  };
  // A set of effects may have been fitted more than once (from different starts): the fit with the lower error on
  // the fit window stands for it — the fit's own objective decides, not the held-out window.
  auto representative = [&](const std::vector<int>& set) {
    int best = -1;
    for (std::size_t i = 0; i < loop.candidates.size(); ++i) {
      const Candidate& c = loop.candidates[i];
      if (c.failure.empty() && indices_of(c) == set && c.effects.size() == set.size() &&
          (best < 0 || c.fit_error < loop.candidates[best].fit_error))
        best = static_cast<int>(i);
    }
    return best;
  };
  // Each effect of a set must earn its place: the set qualifies against the baseline and against the fit standing
  // for every smaller set of its effects that was fitted (a pair against each of its singles, a triple against its
  // pairs and singles).
  auto qualifies_against_subsets = [&](int index) {
    const Candidate& c = loop.candidates[index];
    if (representative(indices_of(c)) != index) return false;
    double reference_error = loop.baseline_held_out_error, reference_aic = loop.baseline_aic;
    const std::vector<int> set = indices_of(c);
    for (std::size_t i = 0; i < loop.candidates.size(); ++i) {
      const std::vector<int> other = indices_of(loop.candidates[i]);
      if (other.size() >= set.size() || representative(other) != static_cast<int>(i) ||
          !std::includes(set.begin(), set.end(), other.begin(), other.end()))
        continue;
      reference_error = std::min(reference_error, loop.candidates[i].held_out_error);
      reference_aic = std::min(reference_aic, loop.candidates[i].aic);
    }
    return qualifies(c, reference_error, reference_aic);
  };
  auto best_qualifying = [&] {
    int best = -1;
    for (std::size_t i = 0; i < loop.candidates.size(); ++i)
      if (qualifies_against_subsets(static_cast<int>(i)) &&
          (best < 0 || loop.candidates[i].held_out_error < loop.candidates[best].held_out_error))
        best = static_cast<int>(i);
    return best;
  };
  auto fit_all = [&](const std::vector<std::vector<int>>& sets,
                     const std::function<std::vector<double>(std::size_t)>& start) {
    // Fewer sets than threads: the threads left over run a fit's starts and its judging draws side by side.
    const int threads = std::max(1, o.threads), per_fit = std::max(1, threads / std::max<int>(1, sets.size()));
    for (Candidate& c : ParallelMap(sets.size(), threads,
                                    [&](std::size_t i) { return fit_candidate(sets[i], start(i), per_fit, false); }))
      loop.candidates.push_back(std::move(c));
  };

  // Screening: every effect the case can model gets a cheap fit, judged on one free run over the whole span (the fit
  // draw), and the effects are ranked by that run's held-out error (ties: the stronger evidence first).
  const int max_singles = o.fit_effects ? o.max_singles : 0;
  const std::size_t screened = max_singles > 0 ? modelable.size() : 0;
  if (screened) say("screening " + std::to_string(screened) + " effect(s), each fitted cheaply and run over the whole span");
  loop.screening = ParallelMap(screened, std::max(1, o.threads), [&](std::size_t i) {
    return fit_candidate({modelable[i]}, start_of({modelable[i]}), 1, true);
  });
  std::vector<std::size_t> screening_order(screened);
  std::iota(screening_order.begin(), screening_order.end(), std::size_t{0});
  auto screened_error = [&](std::size_t i) {
    const Candidate& c = loop.screening[i];
    return c.failure.empty() && std::isfinite(c.held_out_error) ? c.held_out_error : kFailedRun;
  };
  std::stable_sort(screening_order.begin(), screening_order.end(),
                   [&](std::size_t a, std::size_t b) { return screened_error(a) < screened_error(b); });
  // The singles fitted in full: the (at most kRuleSingles) strongest proposals the rules make with strong evidence,
  // which know what a screening run misses (side friction needs the soft drive that lets the top move before it
  // lowers any error), then the best screened, up to max_singles.
  std::vector<int> singles;
  for (int i : modelable)  // the proposals are sorted by their evidence
    if (loop.proposals[i].Proposed() && static_cast<int>(singles.size()) < std::min(kRuleSingles, max_singles))
      singles.push_back(i);
  for (std::size_t i : screening_order)
    if (static_cast<int>(singles.size()) < max_singles &&
        std::find(singles.begin(), singles.end(), modelable[i]) == singles.end())
      singles.push_back(modelable[i]);
  for (const Candidate& c : loop.screening)
    loop.model_runs += c.evaluations + c.redrawn_runs + static_cast<int>(c.held_out_draw_errors.size());
  say(std::to_string(singles.size()) + " effect(s) to fit alone: the strongest proposals, then the best screened");
  std::vector<std::vector<int>> sets;
  for (int i : singles) sets.push_back({i});
  fit_all(sets, [&](std::size_t i) { return start_of(sets[i]); });
  // Pairs, since one missing effect may hide what another explains — neither alone need lower the error (side
  // friction without the soft drive that lets the top move): every pair of the singles fitted in full (dev rec01's
  // side friction and soft drive are its second and fourth singles). Each starts from its effects' own fits, where a
  // fit moved the fit-window error by more than chance (a fit that did not found no value for its effect: then from
  // the effect's first value).
  auto own_fit = [&](int effect) {
    const int single = representative({effect});
    if (single >= 0 && loop.baseline_fit_error - loop.candidates[single].fit_error > loop.error_chance &&
        loop.candidates[single].unit_values.size() == loop.proposals[effect].parameters.size())
      return loop.candidates[single].unit_values;
    return start_of({effect});
  };
  std::vector<int> ranked;  // the singles that could be fitted, best held-out error first
  for (int i : singles)
    if (representative({i}) >= 0) ranked.push_back(i);
  std::stable_sort(ranked.begin(), ranked.end(), [&](int a, int b) {
    return loop.candidates[representative({a})].held_out_error < loop.candidates[representative({b})].held_out_error;
  });
  sets.clear();
  for (std::size_t a = 0; a < ranked.size(); ++a)
    for (std::size_t b = a + 1; b < ranked.size(); ++b)
      sets.push_back({std::min(ranked[a], ranked[b]), std::max(ranked[a], ranked[b])});
  if (!sets.empty()) say(std::to_string(sets.size()) + " pair(s) of them to fit");
  fit_all(sets, [&](std::size_t i) {
    std::vector<double> start = own_fit(sets[i][0]), second = own_fit(sets[i][1]);
    start.insert(start.end(), second.begin(), second.end());
    return start;
  });
  loop.kept = best_qualifying();
  // A kept set's fit had more runs than its parts' and started from their best values, so it may beat them only
  // because the parameters they share were fitted better. So before a set of two or more effects stands, each set
  // without one of its effects is fitted again from the kept values (that fit then stands for its set when it is
  // better on the fit window) and the decision is made again (backward elimination). A set that survives its check
  // is extended by each other fitted single, from its own values (forward selection, up to max_effects), and the
  // decision made again; until the kept set has survived its check and no extension of it qualifies.
  auto values_of = [&](const Candidate& from, const std::vector<int>& set) {  // from's values of the set's effects
    std::vector<double> u;
    std::size_t k = 0;
    for (int effect : indices_of(from)) {
      const std::size_t n = loop.proposals[effect].parameters.size();
      if (std::binary_search(set.begin(), set.end(), effect))
        u.insert(u.end(), from.unit_values.begin() + static_cast<std::ptrdiff_t>(k),
                 from.unit_values.begin() + static_cast<std::ptrdiff_t>(k + n));
      k += n;
    }
    return u;
  };
  // A fit of the set started or ended at u (a refit from there would repeat it or start from its optimum).
  auto fitted_at = [&](const std::vector<int>& set, const std::vector<double>& u) {
    return std::any_of(loop.candidates.begin(), loop.candidates.end(), [&](const Candidate& c) {
      return c.failure.empty() && indices_of(c) == set && c.effects.size() == set.size() &&
             (c.unit_values == u || c.start_values == u);
    });
  };
  std::vector<std::vector<int>> checked;
  while (loop.kept >= 0 && loop.candidates[loop.kept].effects.size() >= 2) {
    const Candidate kept = loop.candidates[loop.kept];
    const std::vector<int> set = indices_of(kept);
    sets.clear();
    if (std::find(checked.begin(), checked.end(), set) == checked.end()) {
      checked.push_back(set);
      for (std::size_t drop = 0; drop < set.size(); ++drop) {
        std::vector<int> subset = set;
        subset.erase(subset.begin() + static_cast<std::ptrdiff_t>(drop));
        if (!fitted_at(subset, values_of(kept, subset))) sets.push_back(subset);  // else the refit is that fit
      }
      say("checking each effect of " + Joined(kept.effects) + " against the set without it, refitted from its values");
      fit_all(sets, [&](std::size_t i) { return values_of(kept, sets[i]); });
      loop.kept = best_qualifying();
      if (loop.kept >= 0 && indices_of(loop.candidates[loop.kept]) != set)
        say(Joined(kept.effects) + " does not beat the sets without one of its effects by the margin");
      continue;
    }
    if (static_cast<int>(set.size()) >= o.max_effects) break;
    for (int i : ranked)
      if (!std::binary_search(set.begin(), set.end(), i)) {
        std::vector<int> larger = set;
        larger.insert(std::upper_bound(larger.begin(), larger.end(), i), i);
        if (representative(larger) < 0) sets.push_back(larger);
      }
    if (!sets.empty()) say(Joined(kept.effects) + " leads; " + std::to_string(sets.size()) + " extension(s) to fit");
    fit_all(sets, [&](std::size_t i) {
      std::vector<double> start;  // the lead's values, the new effect's own
      for (int effect : sets[i]) {
        const std::vector<double> own = std::binary_search(set.begin(), set.end(), effect)
                                            ? values_of(kept, {effect})
                                            : own_fit(effect);
        start.insert(start.end(), own.begin(), own.end());
      }
      return start;
    });
    const int next = best_qualifying();
    if (next == loop.kept) break;
    loop.kept = next;
  }
  // Rival explanations contest the best set: each other set that qualifies as the best did (against the baseline and
  // its own smaller sets), neither containing nor contained in it, whose held-out error is within chance of the
  // best's: one standard deviation of the two errors' difference, hypot(ErrorSpread(e_best), ErrorSpread(e_rival)).
  // Only what every rival shares with the best is named (an honest "cannot tell" for the rest), and only if that set
  // qualifies on its own.
  if (loop.kept >= 0) {
    const int best = loop.kept;
    const std::vector<int> best_set = indices_of(loop.candidates[best]);
    const double k_held_out = FeatureCount(loop.recording_held_out);
    std::vector<int> shared = best_set;
    for (std::size_t i = 0; i < loop.candidates.size(); ++i) {
      const Candidate& c = loop.candidates[i];
      const std::vector<int> set = indices_of(c);
      if (static_cast<int>(i) == best || std::includes(best_set.begin(), best_set.end(), set.begin(), set.end()) ||
          std::includes(set.begin(), set.end(), best_set.begin(), best_set.end()) ||
          !qualifies_against_subsets(static_cast<int>(i)))
        continue;
      const double e_best = loop.candidates[best].held_out_error;
      if (c.held_out_error - e_best > std::hypot(ErrorSpread(e_best, k_held_out), ErrorSpread(c.held_out_error, k_held_out)))
        continue;
      loop.rivals.push_back(c);
      std::vector<int> common;
      std::set_intersection(shared.begin(), shared.end(), set.begin(), set.end(), std::back_inserter(common));
      shared = common;
    }
    if (!loop.rivals.empty()) {
      loop.rivals.insert(loop.rivals.begin(), loop.candidates[best]);
      const int standing = shared.empty() ? -1 : representative(shared);
      loop.kept = standing >= 0 && qualifies(loop.candidates[standing], loop.baseline_held_out_error,
                                             loop.baseline_aic)
                      ? standing
                      : -1;
      std::string each;
      for (const Candidate& c : loop.rivals)
        each += (each.empty() ? "" : ", ") + Joined(c.effects) + " " + Significant(c.held_out_error, 3);
      say("rival explanations within chance of each other (held out: " + each + "): " +
          (loop.kept >= 0 ? "only " + Joined(loop.candidates[loop.kept].effects) + ", which all share, is named"
                          : std::string("none is named")));
    }
  }
  if (loop.kept >= 0) loop.candidates[loop.kept].kept = true;
  for (const Candidate& c : loop.candidates)
    loop.model_runs += c.evaluations + c.redrawn_runs + static_cast<int>(c.held_out_draw_errors.size());

  // 5. The model that stands, on both windows.
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
    Draws models = runner.RunDraws(loop.fitted_document, std::max(1, o.threads));
    loop.model_runs += static_cast<int>(models.models.size());
    fitted = runner.Judge(std::move(models));
  }
  Adopt(fitted, loop.fitted_model, loop.fitted_fit, loop.fitted_held_out, loop.fitted_fit_error,
        loop.fitted_held_out_error);
  // The envelopes' correlogram is one feature read at several lags: one entry, where it counts.
  const CorrelogramDifference correlogram = CompareCorrelograms(loop.fitted_held_out, loop.recording_held_out);
  if (correlogram.rms_scales > 3)
    loop.unexplained.push_back("hook load and weight on bit envelopes' correlogram: " +
                               Fixed(correlogram.rms_scales, 1) + " scales rms over its lags, most at " +
                               Fixed(correlogram.largest_at_lag_s, 1) + " s");
  for (const Feature& f : loop.recording_held_out.features) {
    if (f.name.rfind(kEnvelopeCorrelation, 0) == 0) continue;
    const double m = loop.fitted_held_out.Value(f.name);
    if (std::isfinite(f.value) && std::isfinite(m) && std::abs(m - f.value) > 3 * f.scale)
      loop.unexplained.push_back(f.name + ": model " + Significant(m, 4) + " against " + Significant(f.value, 4) +
                                 " recorded (" + Fixed((m - f.value) / f.scale, 1) + " scales)");
    else if (std::isfinite(f.value) != std::isfinite(m))
      loop.unexplained.push_back(f.name + ": " + (std::isfinite(m) ? "only the model has it" : "only the recording has it"));
  }
  say("kept: " + (loop.kept >= 0 ? Joined(loop.candidates[loop.kept].effects) : std::string("nothing")) +
      "; held-out error " + Significant(loop.baseline_held_out_error, 3) + " -> " +
      Significant(loop.fitted_held_out_error, 3));
  return loop;
}

void CheckPredictionTime(const LoopOptions& o, double until_s) {
  const double span = o.held_out_end_s - o.fit_begin_s;
  if (!(until_s > o.held_out_end_s && until_s <= o.held_out_end_s + 100 * span))
    throw InputError("--predict-until", "expected a recording time after the held-out window's end, " +
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

nlohmann::json DiagnosisLoopToJson(const DiagnosisLoop& loop) {
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  nlohmann::json hypotheses = nlohmann::json::array(), candidates = nlohmann::json::array(),
                 fitted = nlohmann::json::array(), proposals = nlohmann::json::array(), noise = nlohmann::json::object();
  for (const Effect& e : loop.proposals)
    proposals.push_back({{"effect", e.name}, {"component", e.component}, {"evidence_strength", e.strength},
                         {"evidence", e.evidence}});
  for (const Candidate& c : loop.candidates) {
    nlohmann::json parameters = nlohmann::json::array();
    for (const FittedParameter& p : c.parameters)
      parameters.push_back({{"effect", p.effect}, {"name", p.name}, {"unit", p.unit}, {"value", number(p.value)},
                            {"sigma", number(p.sigma)}, {"bounds", {p.lower, p.upper}}});
    candidates.push_back({{"effects", c.effects}, {"parameters", parameters}, {"fit_error", number(c.fit_error)},
                          {"held_out_error", number(c.held_out_error)},
                          {"held_out_error_each_draw", c.held_out_draw_errors},
                          {"draw_in_regime", InRegimeJson(c.draw_in_regime)}, {"aic", number(c.aic)},
                          {"evaluations", c.evaluations}, {"redrawn_runs", c.redrawn_runs},
                          {"failed_runs", c.failed_runs}, {"failed_draws", c.failed_draws},
                          {"first_failed_run", c.first_failure}, {"kept", c.kept}, {"failure", c.failure}});
  }
  if (loop.kept >= 0) {
    const Candidate& c = loop.candidates[loop.kept];
    fitted = candidates[loop.kept]["parameters"];
    for (const std::string& name : c.effects) {
      double estimate = std::nan("");
      std::string unit;
      for (const FittedParameter& p : c.parameters)
        if (p.effect == name && !std::isfinite(estimate)) estimate = p.value, unit = p.unit;
      std::string evidence;
      for (const Effect& e : loop.proposals)
        if (e.name == name) evidence = e.evidence;
      hypotheses.push_back({{"effect", name}, {"estimate", number(estimate)}, {"unit", unit}, {"evidence", evidence}});
    }
  }
  nlohmann::json screening = nlohmann::json::array(), ambiguous = nlohmann::json::array();
  for (const Candidate& c : loop.screening)
    screening.push_back({{"effects", c.effects}, {"fit_error", number(c.fit_error)},
                         {"held_out_error_one_draw", number(c.held_out_error)}, {"evaluations", c.evaluations},
                         {"failure", c.failure}});
  for (const Candidate& c : loop.rivals)
    ambiguous.push_back({{"effects", c.effects}, {"held_out_error", number(c.held_out_error)},
                         {"fit_error", number(c.fit_error)}});
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
          {"held_out", {{"window_s", {loop.recording_held_out.begin_s, loop.recording_held_out.end_s}},
                        {"error_before", loop.baseline_held_out_error},
                        {"error_before_each_draw", loop.baseline_held_out_draw_errors},
                        {"draw_in_regime", InRegimeJson(loop.baseline_draw_in_regime)},
                        {"draws", loop.baseline_held_out_draw_errors.size()},
                        {"recorded_off_bottom_share", number(loop.recorded_off_bottom_share)},
                        {"recording_bounces", loop.recording_bounces},
                        {"fit_draw", loop.fit_draw},
                        {"error_after", loop.fitted_held_out_error},
                        {"error_chance", loop.error_chance}}},
          {"fit", {{"window_s", {loop.recording_fit.begin_s, loop.recording_fit.end_s}},
                   {"error_before", loop.baseline_fit_error},
                   {"error_after", loop.fitted_fit_error},
                   {"baseline_aic", loop.baseline_aic}}},
          {"ambiguous", ambiguous},
          {"base_calibration", {{"parameters", calibration}, {"kept", loop.calibration_kept}}},
          {"plain_case", {{"fit_error_one_draw", number(loop.plain_fit_error)},
                          {"held_out_error_one_draw", number(loop.plain_held_out_error)}}},
          {"screening", {{"baseline_held_out_error_one_draw",
                          loop.baseline_held_out_draw_errors.empty()
                              ? nlohmann::json(nullptr)
                              : number(loop.baseline_held_out_draw_errors.at(static_cast<std::size_t>(loop.fit_draw)))},
                         {"candidates", screening}}},
          {"fitted_parameters", fitted},
          {"candidates", candidates},
          {"proposals", proposals},
          {"unexplained", loop.unexplained},
          {"noise_std", noise},
          {"artefact_samples_masked", masked},
          {"channels_left_whole", loop.channels_left_whole},
          {"model_runs", loop.model_runs},
          {"features_held_out", FeatureSetToJson(loop.fitted_held_out, loop.recording_held_out)},
          {"features_fit_baseline", FeatureSetToJson(loop.baseline_fit, loop.recording_fit)}};
}

}  // namespace drillwave::diagnosis
