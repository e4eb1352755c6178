#pragma once
// The posterior of a case's uncertain parameters given a recording (issue 37 item 1), with the diagnosis loop's own
// likelihood: the recording's features on the fit window, each difference counted in its feature's scale (how much
// the feature varies between the window's parts) as a Gaussian of that standard deviation,
//
//   log L(theta) = -1/2 sum_k ((model_k(theta) - recorded_k) / scale_k)^2 = -K/2 FeatureDistance,
//
// and a uniform prior within each parameter's bounds. Sampled by the affine-invariant ensemble sampler of Goodman and
// Weare (2010) in its parallel form (two halves of the walkers, each half's stretch moves proposed from the other and
// run in parallel: the move emcee makes), since a model run costs milliseconds to seconds and each walker's run is
// independent. Then the posterior predictive of the held-out window: posterior draws run over the whole span, each
// with its own random inputs, their held-out features plus each feature's scale of noise; the 90 % band of every
// held-out feature and how many of the recorded values fall inside it (calibrated: about 90 %, not all).
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/diagnosis/fit.hpp"
#include "drillwave/diagnosis/loop.hpp"
#include "drillwave/diagnosis/recording.hpp"

namespace drillwave::diagnosis {

struct PosteriorOptions {
  int walkers = 16;          // even, >= 2 * parameters + 2
  int steps = 60;            // ensemble steps after the start (every walker moves once a step)
  int burn_in = 20;          // the first steps left out of the samples
  double stretch = 2.0;      // the stretch move's scale a (Goodman and Weare's, emcee's default)
  double start_spread = 0.05;  // the walkers start uniform within this share of each range around the case's value
  int predictive_draws = 40;   // posterior samples run over the whole span for the predictive band
  unsigned seed = 1;
  int threads = 1;

  // walkers even in [4, 1000] (SamplePosterior asks 2 * parameters + 2 of them), steps in [1, 100000], burn_in below
  // steps, predictive_draws in [0, 10000], stretch in (1, 10], start_spread in (0, 1], threads >= 1
  // (core/validity.hpp).
  bool IsValid(std::string* error) const;
};

struct ParameterSummary {
  std::string pointer;
  double case_value = 0, lower = 0, upper = 0;
  double mean = 0, sd = 0, q05 = 0, q50 = 0, q95 = 0;
  // How far the ensemble still moved while sampled: the median of the kept steps' last quarter less that of their first
  // quarter, in posterior standard deviations. Above kMaxDrift the chain had not settled: run more steps.
  double drift_sd = 0;
};
inline constexpr double kMaxDrift = 0.5;

struct PredictiveFeature {
  std::string name;
  double recorded = 0, scale = 1;
  double q05 = 0, q50 = 0, q95 = 0;  // the posterior predictive's 90 % band and median
  double undefined_share = 0;        // share of the draws in which the model does not define the feature
  bool inside = false;               // the recorded value lies in [q05, q95]
};

struct Posterior {
  std::vector<FitParameter> parameters;
  int walkers = 0, steps = 0, burn_in = 0;
  // Every walker's position (parameter values) and log-likelihood at every step, start included: chain[s][w].
  std::vector<std::vector<std::vector<double>>> chain;
  std::vector<std::vector<double>> log_likelihood;
  double acceptance = 0;  // of the moves after the start
  double recording_features = 0;  // K, the fit window's independent features
  std::vector<ParameterSummary> summaries;  // over the samples after burn-in
  std::vector<PredictiveFeature> predictive;
  double coverage = 0;  // share of the held-out features whose recorded value lies in its 90 % band
  int runs = 0, failed_runs = 0;  // likelihood runs, and those the case rejected or that failed (log L = -inf)
  int predictive_runs = 0, failed_predictive_runs = 0;
  nlohmann::json map_document;  // the case at the sample of highest likelihood
  double map_log_likelihood = 0;
};

using PosteriorProgress = std::function<void(const std::string& line)>;

// Throws ParameterError for options that are not valid (either struct's IsValid) or too few walkers for the
// parameters, InputError for a pointer that does not hold a number in the case, bounds out of order, and (through the
// loop's preparation) windows or channel maps the recording does not have; NumericalError when no walker's start
// runs.
Posterior SamplePosterior(const nlohmann::json& document, const Recording& recording, const LoopOptions& loop_options,
                          const std::vector<FitParameter>& parameters, const PosteriorOptions& options,
                          const PosteriorProgress& progress = nullptr);

// posterior.json's content: the settings, acceptance, runs, each parameter's summary, the predictive bands and their
// coverage.
nlohmann::json PosteriorToJson(const Posterior& posterior, const Recording& recording);

// posterior_samples.csv (step, walker, log_likelihood, one column per pointer: after burn-in; what `stability --map
// --draws` reads), posterior.json, predictive.csv, posterior.svg (each parameter's walkers over the steps), map-case.json
// (the sample of highest likelihood), report.md.
void WritePosterior(const Posterior& posterior, const Recording& recording, const std::string& out_dir);

}  // namespace drillwave::diagnosis
