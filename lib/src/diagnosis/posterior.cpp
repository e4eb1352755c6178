#include "drillwave/diagnosis/posterior.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "drillwave/cases/sweep.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/parallel.hpp"
#include "drillwave/core/validity.hpp"
#include "drillwave/io/axis_label.hpp"
#include "drillwave/io/csv.hpp"
#include "drillwave/io/json_number.hpp"
#include "drillwave/io/json_reader.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/io/svg_plot.hpp"
#include "model_runs.hpp"
#include "prepared_recording.hpp"

namespace drillwave::diagnosis {
namespace {

using loop_internal::Drawn;
using loop_internal::ModelRuns;
constexpr double kMinusInf = -std::numeric_limits<double>::infinity();
// Noise draws per posterior sample for the predictive band: enough that the band's quantiles are those of the model
// spread plus the feature's own noise, not of a handful of points.
constexpr int kNoisePerDraw = 25;

// The q-quantile of v (linear between order statistics); NaN for none.
double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const double at = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(at));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (at - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

bool IsCorrelogramLag(const std::string& name) { return name.rfind(kEnvelopeCorrelation, 0) == 0; }

// The options alone (IsValid), then what they must be for these parameters.
void CheckOptions(const std::vector<FitParameter>& parameters, const LoopOptions& o, const PosteriorOptions& p) {
  ThrowIfInvalid(o);
  ThrowIfInvalid(p);
  if (parameters.empty()) throw ParameterError("params", "no parameter to sample: give /pointer:lower:upper");
  const int needed = 2 * static_cast<int>(parameters.size()) + 2;
  if (p.walkers < needed)
    throw ParameterError("walkers", "expected an even number in [" + std::to_string(needed) + ", 1000] for " +
                                      std::to_string(parameters.size()) + " parameters, got " +
                                      std::to_string(p.walkers));
}

}  // namespace

namespace {

// The log-likelihood of a point of the parameters' box: the fit window's features of one run of the case with them,
// -inf outside the box or where the case rejects the values or the run fails.
struct Likelihood {
  const std::vector<FitParameter>& parameters;
  const nlohmann::json& base;
  ModelRuns& runner;
  const FeatureSet& fit;
  double k_features;  // the fit window's independent features

  nlohmann::json With(const std::vector<double>& v) const {
    nlohmann::json doc = base;
    for (std::size_t i = 0; i < parameters.size(); ++i) io::SetByPointer(doc, parameters[i].pointer, v[i]);
    return doc;
  }
  bool Inside(const std::vector<double>& v) const {
    for (std::size_t i = 0; i < parameters.size(); ++i)
      if (!(v[i] >= parameters[i].lower && v[i] <= parameters[i].upper)) return false;
    return true;
  }
  double At(const std::vector<double>& v, int& failed) const {
    if (!Inside(v)) return kMinusInf;
    try {
      const double d =
          FeatureDistance(runner.FitFeatures(runner.Run(With(v), runner.FitDuration(), ModelRuns::Tolerance::kFit)), fit);
      return std::isfinite(d) ? -0.5 * k_features * d : kMinusInf;
    } catch (const InputError&) {  // a combination the case rejects
    } catch (const NumericalError&) {
    }
    ++failed;
    return kMinusInf;
  }
  // A batch of positions in parallel, their runs counted in the posterior. The random numbers are drawn before, so
  // the chain is the same for any number of threads.
  std::vector<double> Batch(const std::vector<std::vector<double>>& positions, int threads, Posterior& post) const {
    std::vector<int> failed(positions.size(), 0);
    std::vector<double> values =
        ParallelMap(positions.size(), threads, [&](std::size_t w) { return At(positions[w], failed[w]); });
    for (std::size_t w = 0; w < positions.size(); ++w)
      post.runs += Inside(positions[w]) ? 1 : 0, post.failed_runs += failed[w];
    return values;
  }
};

struct Random {
  std::mt19937_64 engine;
  std::uniform_real_distribution<double> unit{0.0, 1.0};
  double Unit() { return unit(engine); }
};

// The walkers' start: uniform within start_spread of each range around the case's value, kept inside the bounds;
// walkers whose run fails start again (up to 10 times). The start is the chain's first step.
void StartWalkers(const Likelihood& likelihood, const std::vector<double>& case_value, const PosteriorOptions& p,
                  Random& random, Posterior& post) {
  const std::vector<FitParameter>& parameters = likelihood.parameters;
  const std::size_t dim = parameters.size(), walkers = static_cast<std::size_t>(p.walkers);
  auto draw_start = [&](std::vector<double>& v) {
    for (std::size_t i = 0; i < dim; ++i) {
      const double range = parameters[i].upper - parameters[i].lower;
      const double centre = std::clamp(case_value[i], parameters[i].lower, parameters[i].upper);
      const double lo = std::max(parameters[i].lower, centre - 0.5 * p.start_spread * range);
      const double hi = std::min(parameters[i].upper, centre + 0.5 * p.start_spread * range);
      v[i] = lo + random.Unit() * (hi - lo);
    }
  };
  std::vector<std::vector<double>> x(walkers, std::vector<double>(dim));
  for (auto& v : x) draw_start(v);
  std::vector<double> logl = likelihood.Batch(x, p.threads, post);
  for (int attempt = 0; attempt < 10; ++attempt) {
    std::vector<std::size_t> bad;
    for (std::size_t w = 0; w < walkers; ++w)
      if (!std::isfinite(logl[w])) bad.push_back(w);
    if (bad.empty()) break;
    std::vector<std::vector<double>> again(bad.size(), std::vector<double>(dim));
    for (auto& v : again) draw_start(v);
    const std::vector<double> values = likelihood.Batch(again, p.threads, post);
    for (std::size_t b = 0; b < bad.size(); ++b) x[bad[b]] = again[b], logl[bad[b]] = values[b];
  }
  if (std::none_of(logl.begin(), logl.end(), [](double l) { return std::isfinite(l); }))
    throw NumericalError("no walker's start runs (every model run near the case's values failed)", 0, case_value);
  post.chain.push_back(std::move(x));
  post.log_likelihood.push_back(std::move(logl));
}

// Goodman and Weare's stretch move, half the walkers at a time: walker k moves along the line through a walker j of
// the other half, to x_j + z (x_k - x_j), z from g(z) ~ 1 / sqrt(z) on [1 / a, a]; accepted with probability
// min(1, z^(d - 1) L(y) / L(x_k)). Each step is appended to the chain.
void Stretch(const Likelihood& likelihood, const PosteriorOptions& p, Random& random, Posterior& post,
             const PosteriorProgress& say) {
  const std::size_t dim = likelihood.parameters.size(), walkers = static_cast<std::size_t>(p.walkers);
  std::vector<std::vector<double>> x = post.chain.back();
  std::vector<double> logl = post.log_likelihood.back();
  long accepted = 0, proposed = 0;
  const double a = p.stretch;
  for (int step = 1; step <= p.steps; ++step) {
    for (std::size_t half = 0; half < 2; ++half) {
      std::vector<std::size_t> movers;
      for (std::size_t w = half; w < walkers; w += 2) movers.push_back(w);
      std::vector<std::vector<double>> proposals(movers.size(), std::vector<double>(dim));
      std::vector<double> z(movers.size()), r(movers.size());
      for (std::size_t m = 0; m < movers.size(); ++m) {
        const auto m_other =
            std::min(walkers / 2 - 1, static_cast<std::size_t>(random.Unit() * static_cast<double>(walkers / 2)));
        const std::size_t j = (1 - half) + 2 * m_other;
        const double root = (a - 1) * random.Unit() + 1;
        z[m] = root * root / a;
        r[m] = random.Unit();
        for (std::size_t i = 0; i < dim; ++i) proposals[m][i] = x[j][i] + z[m] * (x[movers[m]][i] - x[j][i]);
      }
      const std::vector<double> values = likelihood.Batch(proposals, p.threads, post);
      for (std::size_t m = 0; m < movers.size(); ++m) {
        ++proposed;
        const std::size_t k = movers[m];
        const double log_ratio = (static_cast<double>(dim) - 1) * std::log(z[m]) + values[m] - logl[k];
        if (std::isfinite(values[m]) && std::log(r[m]) < log_ratio) x[k] = proposals[m], logl[k] = values[m], ++accepted;
      }
    }
    post.chain.push_back(x);
    post.log_likelihood.push_back(logl);
    if (step % std::max(1, p.steps / 10) == 0 || step == p.steps) {
      const double best = *std::max_element(logl.begin(), logl.end());
      say("step " + std::to_string(step) + " of " + std::to_string(p.steps) + ": acceptance " +
          Fixed(100.0 * static_cast<double>(accepted) / static_cast<double>(std::max(1L, proposed)), 0) +
          " %, best log-likelihood " + Significant(best, 5) + ", " + std::to_string(post.runs) + " runs (" +
          std::to_string(post.failed_runs) + " failed)");
    }
  }
  post.acceptance = static_cast<double>(accepted) / static_cast<double>(std::max(1L, proposed));
}

// One parameter's summary over the kept samples (v runs step by step, every walker of a step together).
ParameterSummary Summary(const FitParameter& parameter, double case_value, const std::vector<double>& v) {
  ParameterSummary s;
  s.pointer = parameter.pointer, s.case_value = case_value;
  s.lower = parameter.lower, s.upper = parameter.upper;
  double sum = 0, sum2 = 0;
  for (double value : v) sum += value;
  s.mean = sum / static_cast<double>(v.size());
  for (double value : v) sum2 += (value - s.mean) * (value - s.mean);
  s.sd = std::sqrt(sum2 / static_cast<double>(std::max<std::size_t>(1, v.size() - 1)));
  s.q05 = Quantile(v, 0.05), s.q50 = Quantile(v, 0.5), s.q95 = Quantile(v, 0.95);
  const std::size_t quarter = v.size() / 4;
  if (quarter > 0 && s.sd > 0) {
    const std::vector<double> first(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(quarter));
    const std::vector<double> last(v.end() - static_cast<std::ptrdiff_t>(quarter), v.end());
    s.drift_sd = (Quantile(last, 0.5) - Quantile(first, 0.5)) / s.sd;
  }
  return s;
}

// The posterior predictive of the held-out window: samples spread evenly over the kept ones, each with its own draw
// of the random inputs, over the whole span at the case's tolerance; each held-out feature's 90 % band, the model's
// spread with the feature's own noise (its scale) added.
void PredictHeldOut(const Likelihood& likelihood, const std::vector<std::vector<double>>& samples,
                    const FeatureSet& recorded_held_out, const PosteriorOptions& p, Posterior& post,
                    const PosteriorProgress& say) {
  ModelRuns& runner = likelihood.runner;
  const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(p.predictive_draws), samples.size());
  say("posterior predictive: " + std::to_string(n) + " samples over " + Fixed(runner.FullDuration(), 0) +
      " s simulated each");
  std::vector<int> failed(n, 0);
  const std::vector<FeatureSet> held_out = ParallelMap(n, p.threads, [&](std::size_t d) {
    const std::size_t pick = d * samples.size() / n;
    try {
      return runner.HeldOutFeatures(runner.Run(Drawn(likelihood.With(samples[pick]), static_cast<int>(d) + 1),
                                               runner.FullDuration(), ModelRuns::Tolerance::kCase,
                                               loop_internal::kJudgingWorkFactor));
    } catch (const InputError&) {
    } catch (const NumericalError&) {
    }
    failed[d] = 1;
    return FeatureSet{};
  });
  post.predictive_runs = static_cast<int>(n);
  for (int f : failed) post.failed_predictive_runs += f;
  std::mt19937_64 noise_rng(p.seed + 7919);
  std::normal_distribution<double> gauss(0.0, 1.0);
  int counted = 0, covered = 0;
  for (const Feature& f : recorded_held_out.features) {
    if (!std::isfinite(f.value) || IsCorrelogramLag(f.name)) continue;
    PredictiveFeature pf;
    pf.name = f.name, pf.recorded = f.value, pf.scale = f.scale;
    std::vector<double> values;
    int undefined = 0, runs = 0;
    for (std::size_t d = 0; d < n; ++d) {
      if (failed[d]) continue;
      ++runs;
      const double model = held_out[d].Value(f.name);
      if (!std::isfinite(model)) {
        ++undefined;
        continue;
      }
      for (int e = 0; e < kNoisePerDraw; ++e) values.push_back(model + f.scale * gauss(noise_rng));
    }
    pf.undefined_share = runs > 0 ? static_cast<double>(undefined) / runs : 1.0;
    pf.q05 = Quantile(values, 0.05), pf.q50 = Quantile(values, 0.5), pf.q95 = Quantile(values, 0.95);
    pf.inside = !values.empty() && f.value >= pf.q05 && f.value <= pf.q95;
    ++counted, covered += pf.inside ? 1 : 0;
    post.predictive.push_back(pf);
  }
  post.coverage = counted > 0 ? static_cast<double>(covered) / counted : std::numeric_limits<double>::quiet_NaN();
  say("held-out features inside their 90 % band: " + std::to_string(covered) + " of " + std::to_string(counted));
}

}  // namespace

bool PosteriorOptions::IsValid(std::string* error) const {
  // The fewest walkers any sampling takes: 2 * 1 + 2 for one parameter.
  constexpr int kFewestWalkers = 4;
  return ((walkers % 2 == 0 && walkers >= kFewestWalkers && walkers <= 1000) ||
          Invalid(error, "walkers", "expected an even number in [" + std::to_string(kFewestWalkers) +
                                        ", 1000] (2 * parameters + 2 at least), got " + std::to_string(walkers))) &&
         WholeField(error, "steps", steps, 1, 100000) &&
         ((burn_in >= 0 && burn_in < steps) ||
          Invalid(error, "burn_in", "expected a whole number in [0, steps - 1 = " + std::to_string(steps - 1) +
                                        "], got " + std::to_string(burn_in))) &&
         WholeField(error, "predictive_draws", predictive_draws, 0, 10000) &&
         ((stretch > 1 && stretch <= 10) ||
          Invalid(error, "stretch", "expected a number in (1, 10], got " + ReadableNumber(stretch))) &&
         ((start_spread > 0 && start_spread <= 1) ||
          Invalid(error, "start_spread", "expected a share in (0, 1], got " + ReadableNumber(start_spread))) &&
         WholeField(error, "threads", threads, 1);
}

Posterior SamplePosterior(const nlohmann::json& document, const Recording& raw, const LoopOptions& o,
                          const std::vector<FitParameter>& parameters, const PosteriorOptions& p,
                          const PosteriorProgress& progress) {
  const PosteriorProgress say = [&](const std::string& s) {
    if (progress) progress(s);
  };
  CheckOptions(parameters, o, p);
  const std::size_t dim = parameters.size();
  std::vector<double> case_value(dim);
  for (std::size_t i = 0; i < dim; ++i) case_value[i] = CaseValue(document, parameters[i]);
  const loop_internal::PreparedRecording prepared = loop_internal::PrepareRecording(document, raw, o);
  ModelRuns runner(o, prepared.recording, prepared.whole, prepared.features, prepared.fit, prepared.held_out);
  {  // The work asked, checked before any run: every walker's runs and the predictive draws, each over the whole span.
    nlohmann::json whole = prepared.base;
    whole["simulation"]["duration_s"] = runner.FullDuration();
    whole.erase("statistics");  // its window may lie past the span; the runs keep it inside (ModelRuns::Run)
    const double runs = static_cast<double>(p.walkers) * (p.steps + 1) + p.predictive_draws;
    cases::CheckPointsWork(cases::ParseCase(whole), runs, true, "steps");
  }
  Posterior post;
  post.parameters = parameters;
  post.walkers = p.walkers, post.steps = p.steps, post.burn_in = p.burn_in;
  post.recording_features = FeatureCount(prepared.fit);
  const Likelihood likelihood{parameters, prepared.base, runner, prepared.fit, post.recording_features};

  // The case as given sets the work budget: a corner of the box that makes the model stiff fails as a run.
  say("the case as given: " + Fixed(runner.FitDuration(), 0) + " s simulated for the fit window");
  const double case_distance = FeatureDistance(runner.FitFeatures(runner.Run(prepared.base, runner.FitDuration(),
                                                                             ModelRuns::Tolerance::kFit)),
                                               prepared.fit);
  runner.SetWorkBudget();
  say("  its log-likelihood " + Significant(-0.5 * likelihood.k_features * case_distance, 5) + " over " +
      Significant(likelihood.k_features, 3) + " features");

  Random random{std::mt19937_64(p.seed)};
  say("start: " + std::to_string(p.walkers) + " walkers within " + Fixed(100 * p.start_spread, 0) +
      " % of each range around the case's values");
  StartWalkers(likelihood, case_value, p, random, post);
  Stretch(likelihood, p, random, post, say);

  // Summaries over the samples after burn-in: every walker of every kept step.
  std::vector<std::vector<double>> samples;
  std::vector<double> sample_logl;
  for (int s = p.burn_in + 1; s <= p.steps; ++s)
    for (std::size_t w = 0; w < post.chain[s].size(); ++w)
      samples.push_back(post.chain[s][w]), sample_logl.push_back(post.log_likelihood[s][w]);
  for (std::size_t i = 0; i < dim; ++i) {
    std::vector<double> v;
    for (const auto& sample : samples) v.push_back(sample[i]);
    post.summaries.push_back(Summary(parameters[i], case_value[i], v));
  }
  const std::size_t best = static_cast<std::size_t>(
      std::max_element(sample_logl.begin(), sample_logl.end()) - sample_logl.begin());
  post.map_document = likelihood.With(samples[best]);
  post.map_log_likelihood = sample_logl[best];
  if (p.predictive_draws > 0) PredictHeldOut(likelihood, samples, prepared.held_out, p, post, say);
  return post;
}

nlohmann::json PosteriorToJson(const Posterior& post, const Recording& recording) {
  nlohmann::json parameters = nlohmann::json::array();
  for (const ParameterSummary& s : post.summaries)
    parameters.push_back({{"pointer", s.pointer}, {"case_value", s.case_value}, {"bounds", {s.lower, s.upper}},
                          {"mean", s.mean}, {"sd", s.sd}, {"q05", s.q05}, {"median", s.q50}, {"q95", s.q95},
                          {"drift_sd", s.drift_sd}});
  nlohmann::json predictive = nlohmann::json::array();
  for (const PredictiveFeature& f : post.predictive)
    predictive.push_back({{"feature", f.name},
                          {"recorded", f.recorded},
                          {"scale", f.scale},
                          {"q05", io::FiniteOrNull(f.q05)},
                          {"median", io::FiniteOrNull(f.q50)},
                          {"q95", io::FiniteOrNull(f.q95)},
                          {"undefined_share", f.undefined_share},
                          {"inside", f.inside}});
  return {{"recording", recording.source},
          {"likelihood",
           "log L = -1/2 sum over the fit window's features of ((model - recorded) / scale)^2; uniform "
           "prior in the bounds"},
          {"fit_window_features", post.recording_features},
          {"walkers", post.walkers},
          {"steps", post.steps},
          {"burn_in", post.burn_in},
          {"acceptance", post.acceptance},
          {"runs", post.runs},
          {"failed_runs", post.failed_runs},
          {"parameters", parameters},
          {"map_log_likelihood", io::FiniteOrNull(post.map_log_likelihood)},
          {"predictive_runs", post.predictive_runs},
          {"failed_predictive_runs", post.failed_predictive_runs},
          {"predictive", predictive},
          {"coverage_90", io::FiniteOrNull(post.coverage)}};
}

void WritePosterior(const Posterior& post, const Recording& recording, const std::string& out_dir) {
  io::OutputDirectory out(out_dir);
  const std::size_t dim = post.parameters.size();
  {
    std::string csv = "step,walker,log_likelihood";
    for (const FitParameter& q : post.parameters) csv += "," + q.pointer;
    csv += "\n";
    for (int s = post.burn_in + 1; s <= post.steps; ++s)
      for (int w = 0; w < post.walkers; ++w) {
        csv += std::to_string(s) + "," + std::to_string(w) + ",";
        io::AppendCsvNumber(csv, post.log_likelihood[s][w]);
        for (double v : post.chain[s][w]) csv += ",", io::AppendCsvNumber(csv, v);
        csv += "\n";
      }
    out.Open("posterior_samples.csv") << csv;
  }
  std::string predictive_csv = "feature,recorded,scale,q05,median,q95,undefined_share,inside\n";
  for (const PredictiveFeature& f : post.predictive) {
    predictive_csv += f.name + ",";
    for (double v : {f.recorded, f.scale, f.q05, f.q50, f.q95, f.undefined_share})
      io::AppendCsvNumber(predictive_csv, v), predictive_csv += ",";
    predictive_csv += f.inside ? "1\n" : "0\n";
  }
  out.Open("predictive.csv") << predictive_csv;
  out.Open("posterior.json") << PosteriorToJson(post, recording).dump(2) << "\n";
  out.Open("map-case.json") << post.map_document.dump(2) << "\n";

  // Each parameter's walkers over the steps: the median and the 5-95 % spread of the ensemble, and the log-likelihood.
  io::Figure figure;
  figure.title = "posterior sampling against " + recording.source;
  figure.x_label = "ensemble step";
  std::vector<double> steps;
  for (int s = 0; s <= post.steps; ++s) steps.push_back(s);
  auto ensemble_panel = [&](const std::string& label, const std::function<double(int, int)>& value) {
    io::Series lo{"5 % of the walkers", steps, {}}, mid{"median", steps, {}}, hi{"95 %", steps, {}};
    for (int s = 0; s <= post.steps; ++s) {
      std::vector<double> v;
      for (int w = 0; w < post.walkers; ++w)
        if (std::isfinite(value(s, w))) v.push_back(value(s, w));
      lo.y.push_back(Quantile(v, 0.05)), mid.y.push_back(Quantile(v, 0.5)), hi.y.push_back(Quantile(v, 0.95));
    }
    figure.panels.push_back({label, {lo, mid, hi}});
  };
  for (std::size_t i = 0; i < dim; ++i)
    ensemble_panel(io::AxisLabel(io::QuantityOfPointer(post.parameters[i].pointer)),
                   [&](int s, int w) { return post.chain[s][w][i]; });
  ensemble_panel("log-likelihood", [&](int s, int w) { return post.log_likelihood[s][w]; });
  figure.spans.push_back({"burn-in", 0, static_cast<double>(post.burn_in)});
  io::WriteSvg(figure, out.Open("posterior.svg"));

  std::ostream& report = out.Open("report.md");
  report << "# Posterior against " << recording.source << "\n\n"
         << "Likelihood: the fit window's " << Significant(post.recording_features, 3)
         << " features, each difference counted in its own scale as a Gaussian of that standard deviation; prior "
            "uniform within the bounds. Affine-invariant ensemble sampler (Goodman and Weare's stretch move): "
         << post.walkers << " walkers, " << post.steps << " steps, the first " << post.burn_in
         << " left out; acceptance " << Fixed(100 * post.acceptance, 1) << " %; " << post.runs << " runs ("
         << post.failed_runs << " failed, taken as zero likelihood).\n\n"
         << "| parameter | case | bounds | mean | sd | 5 % | median | 95 % | drift [sd] |\n"
            "|---|---|---|---|---|---|---|---|---|\n";
  int unsettled = 0;
  for (const ParameterSummary& s : post.summaries) {
    const bool drifting = std::abs(s.drift_sd) > kMaxDrift;
    unsettled += drifting ? 1 : 0;
    report << "| " << s.pointer << " | " << Significant(s.case_value, 5) << " | [" << Significant(s.lower, 4) << ", "
           << Significant(s.upper, 4) << "] | " << Significant(s.mean, 5) << " | " << Significant(s.sd, 3) << " | "
           << Significant(s.q05, 5) << " | " << Significant(s.q50, 5) << " | " << Significant(s.q95, 5) << " | "
           << (drifting ? "**" : "") << Fixed(s.drift_sd, 2) << (drifting ? "**" : "") << " |\n";
  }
  report << "\nDrift: the ensemble median of the kept steps' last quarter less their first quarter's, in posterior "
            "standard deviations; "
         << (unsettled > 0 ? "**" + std::to_string(unsettled) + " parameter(s) still moved by more than " +
                                 Fixed(kMaxDrift, 1) + " sd: the chain had not settled, run more steps**"
                           : "every parameter within " + Fixed(kMaxDrift, 1) + " sd: settled as far as this shows")
         << ".\n";
  if (!post.predictive.empty()) {
    int inside = 0;
    for (const PredictiveFeature& f : post.predictive) inside += f.inside ? 1 : 0;
    report << "\n## Posterior predictive of the held-out window\n\n" << post.predictive_runs
           << " posterior samples run over the whole span, each with its own draw of the random inputs ("
           << post.failed_predictive_runs << " failed); each held-out feature's band is their values plus the "
              "feature's own noise (its scale). Recorded values inside the 90 % band: "
           << inside << " of " << post.predictive.size() << " (" << Fixed(100 * post.coverage, 0)
           << " %; a calibrated band holds about 90 %).\n\n"
           << "| feature | recorded | 5 % | median | 95 % | inside |\n|---|---|---|---|---|---|\n";
    for (const PredictiveFeature& f : post.predictive)
      report << "| " << f.name << " | " << Significant(f.recorded, 5) << " | " << Significant(f.q05, 5) << " | "
             << Significant(f.q50, 5) << " | " << Significant(f.q95, 5) << " | " << (f.inside ? "yes" : "**no**")
             << (f.undefined_share > 0 ? " (undefined in " + Fixed(100 * f.undefined_share, 0) + " % of the draws)"
                                       : std::string())
             << " |\n";
  }
  report << "\nFiles: `posterior_samples.csv` (the samples after burn-in: `drillwave stability CASE --map ... --draws "
            "posterior_samples.csv` maps P(stick-slip) over them), `posterior.json`, `predictive.csv`, "
            "`posterior.svg`, `map-case.json` (the sample of highest likelihood).\n";
  out.Commit();
}

}  // namespace drillwave::diagnosis
