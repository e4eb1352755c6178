#include "model_runs.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

#include "drillwave/cases/sensors.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/parallel.hpp"
#include "drillwave/core/sampled.hpp"
#include "drillwave/diagnosis/recording.hpp"
#include "drillwave/io/json_reader.hpp"

namespace drillwave::diagnosis::loop_internal {

Recording ModelRecording(const cases::RunResult& run, const std::vector<ChannelMap>& maps, const Recording& rec,
                         double offset_s, double begin_s, double end_s) {
  Recording m;
  m.source = "model";
  m.sample_interval_s = rec.sample_interval_s;
  for (double t : rec.time_s)
    if (t >= begin_s && t <= end_s) m.time_s.push_back(t);
  std::vector<double> model_time = run.time_s;
  for (double& t : model_time) t -= offset_s;
  for (const ChannelMap& map : maps) {
    const std::string measured = map.model + "_measured";
    const bool has_measured = std::any_of(run.channels.begin(), run.channels.end(),
                                          [&](const cases::Channel& c) { return c.name == measured; });
    const std::vector<double>& values = run.channel(has_measured ? measured : map.model).values;
    std::vector<double> out(m.time_s.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = map.scale * InterpolateSampled(model_time, values, m.time_s[i]);
    m.names.push_back(map.recording);
    m.channels.push_back(std::move(out));
  }
  return m;
}

nlohmann::json Drawn(nlohmann::json doc, int d) {
  const std::function<void(nlohmann::json&)> move_seeds = [&](nlohmann::json& j) {
    if (!j.is_object()) return;
    for (auto& [key, value] : j.items()) {
      if (key == "seed" && value.is_number_integer())
        value = (value.get<long long>() + d) % 2147483648LL;
      else
        move_seeds(value);
    }
  };
  if (d == 0) return doc;
  if (doc.contains("model")) move_seeds(doc["model"]);
  if (doc.contains("sensors") && doc["sensors"].contains("seed"))
    doc["sensors"]["seed"] = (doc["sensors"]["seed"].get<long long>() + 7919LL * d) % 2147483648LL;
  return doc;
}

ModelRuns::ModelRuns(const LoopOptions& o, const Recording& recording, std::vector<char> whole,
                     const FeatureOptions& features, const FeatureSet& fit, const FeatureSet& held_out)
    : o_(o),
      recording_(recording),
      whole_(std::move(whole)),
      features_(features),
      model_features_(features),
      recording_fit_(fit),
      recording_held_out_(held_out),
      full_duration_(o.model_time_offset_s + o.held_out_end_s),
      fit_duration_(o.model_time_offset_s + o.fit_end_s + 0.5),
      recorded_off_bottom_share_(OffBottomShare(recording, o.fit_begin_s, o.held_out_end_s, features)),
      recording_bounces_(recorded_off_bottom_share_ > kBouncingShare) {
  // A model's features are read against the recording's scales, so its own (the spread between the window's parts)
  // are never used: measured on the whole window only, for a fifth of the cost.
  model_features_.parts = 1;
}

Recording ModelRuns::Run(nlohmann::json doc, double duration, Tolerance tolerance, double work_factor) const {
  doc["simulation"]["duration_s"] = duration;
  if (tolerance == Tolerance::kFit && o_.fit_tolerance > 0)
    for (const char* key : {"rel_tol", "abs_tol"})
      doc["simulation"][key] = std::max(doc["simulation"].value(key, 1e-8), o_.fit_tolerance);
  const auto window = nlohmann::json::json_pointer("/statistics/window_s");
  if (doc.contains(window) && doc.at(window).is_array() && doc.at(window).size() == 2)  // kept inside the run
    doc.at(window) = {std::min(doc.at(window)[0].get<double>(), 0.5 * duration), duration};
  const cases::SensorSet sensors =
      doc.contains("sensors") ? cases::ReadSensors(io::JsonReader(doc["sensors"], "/sensors")) : cases::SensorSet{};
  doc.erase("sensors");
  const std::string key = doc.dump();
  std::shared_ptr<const cases::RunResult> simulated;
  {
    const std::lock_guard<std::mutex> lock(cache_mutex_);
    const auto it = simulations_.find(key);
    if (it != simulations_.end()) simulated = it->second;
  }
  if (!simulated) {
    cases::Case c = cases::ParseCase(doc);
    // A candidate's run may cost at most work_factor times the baseline's work per simulated second: a corner of the
    // parameter box that makes the model stiff fails as a run instead of taking the machine's time and memory.
    if (evaluations_per_second_ > 0)
      c.settings.integrator.max_evaluations = static_cast<long>(work_factor * evaluations_per_second_ * duration);
    const int started = ++runs_simulated_;
    if (on_run_) on_run_(started);
    cases::RunResult result = cases::RunCase(c).result;
    // Only the mapped channels are read: at an output finer than the recording's, the others would fill the cache.
    const auto unmapped = [&](const cases::Channel& ch) {
      return std::none_of(o_.maps.begin(), o_.maps.end(), [&](const ChannelMap& m) { return m.model == ch.name; });
    };
    result.channels.erase(std::remove_if(result.channels.begin(), result.channels.end(), unmapped),
                          result.channels.end());
    simulated = std::make_shared<const cases::RunResult>(std::move(result));
    const std::lock_guard<std::mutex> lock(cache_mutex_);
    if (simulations_.size() >= 64) simulations_.clear();  // a bound on memory; fits revisit recent points
    simulations_.emplace(key, simulated);
  }
  cases::RunResult measured = *simulated;
  cases::ApplySensors(sensors, measured);
  // The model's channels pass the artefact filter the recording passed, each masked or left whole as the recording's
  // was.
  return MaskArtefacts(ModelRecording(measured, o_.maps, recording_, o_.model_time_offset_s, o_.fit_begin_s,
                                      std::min(o_.held_out_end_s, duration - o_.model_time_offset_s)),
                       &whole_)
      .recording;
}

void ModelRuns::SetWorkBudget() {
  const std::lock_guard<std::mutex> lock(cache_mutex_);
  for (const auto& [key, simulated] : simulations_) {
    const auto it = simulated->summary.find("derivative_evaluations");
    if (it != simulated->summary.end() && it->is_number())
      evaluations_per_second_ = std::max(evaluations_per_second_, it->get<double>() / full_duration_);
  }
}

bool ModelRuns::InRegime(const Recording& model) const {
  if (!std::isfinite(recorded_off_bottom_share_)) return true;
  return (OffBottomShare(model, o_.fit_begin_s, o_.held_out_end_s, features_) > kBouncingShare) == recording_bounces_;
}

FeatureSet ModelRuns::FitFeatures(const Recording& model) const {
  return MeasureFeatures(model, o_.fit_begin_s, o_.fit_end_s, model_features_);
}

FeatureSet ModelRuns::HeldOutFeatures(const Recording& model) const {
  return MeasureFeatures(model, o_.held_out_begin_s, o_.held_out_end_s, model_features_);
}

Draws ModelRuns::RunDraws(const nlohmann::json& doc, int threads) const {
  const int draws = o_.draws;
  Draws runs;
  int matched = 0, attempted = 0;
  std::mutex failure_mutex;
  std::string first_failure;
  while (matched < draws && attempted < kMaxDrawFactor * draws) {
    const int first = attempted;
    const int batch = std::min(draws - matched, kMaxDrawFactor * draws - first);
    attempted += batch;
    int seed = first;
    for (std::optional<Recording>& m :
         ParallelMap(static_cast<std::size_t>(batch), threads, [&](std::size_t d) -> std::optional<Recording> {
           try {
             return Run(Drawn(doc, first + static_cast<int>(d)), full_duration_, Tolerance::kCase,
                        kJudgingWorkFactor);
           } catch (const NumericalError& e) {
             const std::lock_guard<std::mutex> lock(failure_mutex);
             if (first_failure.empty()) first_failure = e.what();
             return std::nullopt;
           }
         })) {
      const int this_seed = seed++;
      if (!m) {
        ++runs.failed;
        continue;
      }
      runs.seeds.push_back(this_seed);
      runs.in_regime.push_back(InRegime(*m));
      matched += runs.in_regime.back();
      runs.models.push_back(std::move(*m));
    }
  }
  if (runs.models.empty()) throw NumericalError("every draw failed; the first: " + first_failure, std::nan(""), {});
  return runs;
}

Judged ModelRuns::Judge(Draws runs) const {
  std::vector<Recording>& models = runs.models;
  std::vector<FeatureSet> fit, held_out;
  std::vector<double> fit_errors;
  std::vector<std::size_t> order;
  Judged j;
  j.draw_in_regime = runs.in_regime;
  j.draw_seeds = runs.seeds;
  if (j.draw_seeds.size() != models.size()) {  // draws made by hand: numbered in order
    j.draw_seeds.resize(models.size());
    for (std::size_t d = 0; d < models.size(); ++d) j.draw_seeds[d] = static_cast<int>(d);
  }
  j.failed_draws = runs.failed;
  for (std::size_t d = 0; d < models.size(); ++d) {
    fit.push_back(FitFeatures(models[d]));
    held_out.push_back(HeldOutFeatures(models[d]));
    j.held_out_draw_errors.push_back(FeatureDistance(held_out.back(), recording_held_out_));
    if (j.draw_in_regime[d]) order.push_back(d);
  }
  if (order.empty())
    for (std::size_t d = 0; d < models.size(); ++d) order.push_back(d);
  for (std::size_t d : order) fit_errors.push_back(FeatureDistance(fit[d], recording_fit_));
  std::sort(fit_errors.begin(), fit_errors.end());
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return j.held_out_draw_errors[a] < j.held_out_draw_errors[b]; });
  j.held_out_mean = held_out[order.front()];
  for (Feature& f : j.held_out_mean.features) {
    double sum = 0;
    int defined = 0;
    for (std::size_t d : order) {
      const double v = held_out[d].Value(f.name);
      if (std::isfinite(v)) sum += v, ++defined;
    }
    f.value = defined ? sum / defined : std::nan("");
  }
  const std::size_t median = order[(order.size() - 1) / 2];
  j.model = std::move(models[median]);
  j.fit = fit[median], j.held_out = held_out[median];
  j.fit_error = fit_errors[(fit_errors.size() - 1) / 2];  // the median on the fit window, whichever draw
  j.held_out_error = j.held_out_draw_errors[median];
  return j;
}

}  // namespace drillwave::diagnosis::loop_internal
