// The posterior of a case's parameters (posterior.hpp) on a recording whose truth is known: a noisy twin of the
// two-mass stick-slip case. The sampler starts away from the truth and must find it, inside a 90 % interval much
// narrower than the prior; the predictive band of the held-out window must hold most of the twin's features; the
// chain must not depend on the number of threads; bad options are refused naming the option.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/diagnosis/posterior.hpp"
#include "drillwave/io/json_reader.hpp"
#include "noisy_twin.hpp"

namespace drillwave::diagnosis {
namespace {

using testing::NoisyTwin;

// The two-mass case to 160 s, its twin the run from 100 s on: 30 s to fit, 29 held out.
nlohmann::json TwoMassCase() {
  nlohmann::json doc = testing::TwoMassCase();
  doc["simulation"]["duration_s"] = 160;
  doc["statistics"]["window_s"] = {100, 160};
  return doc;
}

LoopOptions Options() {
  LoopOptions o = testing::Options();
  o.fit_begin_s = 0, o.fit_end_s = 30, o.held_out_begin_s = 30, o.held_out_end_s = 59;
  return o;
}

constexpr const char* kMuS = "/model/bit/friction/mu_s";

TEST(Posterior, FindsTheTwinsFrictionFromAwayAndItsBandHoldsTheHeldOutFeatures) {
  const nlohmann::json truth = TwoMassCase();
  const Recording twin = NoisyTwin(truth, 0.5);
  nlohmann::json start = truth;
  start["model"]["bit"]["friction"]["mu_s"] = 0.95;  // truth 0.8, prior [0.55, 1.2]
  PosteriorOptions p;
  p.walkers = 8, p.steps = 80, p.burn_in = 40, p.predictive_draws = 12, p.threads = 2;
  const Posterior post = SamplePosterior(start, twin, Options(), {{kMuS, 0.55, 1.2}}, p);
  const ParameterSummary& s = post.summaries.at(0);
  std::printf("[ measured ] mu_s: median %.4f, 90 %% in [%.4f, %.4f] (truth 0.8, prior [0.55, 1.2]); acceptance "
              "%.2f, %d runs (%d failed); held-out coverage %.2f of %zu features\n",
              s.q50, s.q05, s.q95, post.acceptance, post.runs, post.failed_runs, post.coverage, post.predictive.size());
  EXPECT_LE(s.q05, 0.8);
  EXPECT_GE(s.q95, 0.8);
  EXPECT_LT(s.q95 - s.q05, (1.2 - 0.55) / 3);
  EXPECT_GT(post.acceptance, 0.1);
  EXPECT_LT(post.acceptance, 0.95);
  ASSERT_FALSE(post.predictive.empty());
  EXPECT_GE(post.coverage, 0.7);
  // Its best sample is a case that runs.
  EXPECT_NEAR(post.map_document["model"]["bit"]["friction"]["mu_s"].get<double>(), 0.8, 0.05);
}

TEST(Posterior, TheChainIsTheSameOnOneThreadAsOnTwo) {
  const nlohmann::json doc = TwoMassCase();
  const Recording twin = NoisyTwin(doc, 0.5);
  PosteriorOptions p;
  p.walkers = 6, p.steps = 3, p.burn_in = 1, p.predictive_draws = 0;
  p.threads = 1;
  const Posterior one = SamplePosterior(doc, twin, Options(), {{kMuS, 0.55, 1.2}, {"/model/string/damping_Nms_per_rad", 0, 200}}, p);
  p.threads = 2;
  const Posterior two = SamplePosterior(doc, twin, Options(), {{kMuS, 0.55, 1.2}, {"/model/string/damping_Nms_per_rad", 0, 200}}, p);
  EXPECT_EQ(one.chain, two.chain);
  EXPECT_EQ(one.log_likelihood, two.log_likelihood);
}

std::string RefusedOption(const nlohmann::json& doc, const std::vector<FitParameter>& parameters,
                          const PosteriorOptions& p) {
  try {
    LoopOptions o = Options();
    SamplePosterior(doc, Recording{}, o, parameters, p);
  } catch (const InputError& e) {
    return e.json_path();
  }
  return "";
}

TEST(Posterior, BadOptionsAreRefusedNamingTheOptionBeforeAnyRun) {
  const nlohmann::json doc = TwoMassCase();
  const std::vector<FitParameter> mu = {{kMuS, 0.55, 1.2}};
  PosteriorOptions p;
  EXPECT_EQ(RefusedOption(doc, {}, p), "params");
  p.walkers = 7;
  EXPECT_EQ(RefusedOption(doc, mu, p), "walkers");
  p.walkers = 2;  // fewer than 2 p + 2
  EXPECT_EQ(RefusedOption(doc, mu, p), "walkers");
  p = PosteriorOptions{};
  p.burn_in = p.steps;
  EXPECT_EQ(RefusedOption(doc, mu, p), "burn_in");
  p = PosteriorOptions{};
  EXPECT_EQ(RefusedOption(doc, {{"/model/bit/friction/law", 0, 1}}, p), "/model/bit/friction/law");
  EXPECT_EQ(RefusedOption(doc, {{kMuS, 1.2, 0.55}}, p), kMuS);
}

// 1000 walkers for 100000 steps of a 160-s run at 1-ms output: the estimate refused before the first run.
TEST(Posterior, WorkAboveTheLimitIsRefusedBeforeAnyRun) {
  const nlohmann::json doc = TwoMassCase();
  PosteriorOptions p;
  p.walkers = 1000, p.steps = 100000, p.burn_in = 0;
  try {
    SamplePosterior(doc, NoisyTwin(doc, 0.5), Options(), {{kMuS, 0.55, 1.2}}, p);
    FAIL() << "not refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "steps");
    EXPECT_NE(std::string(e.what()).find("max_samples"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace drillwave::diagnosis
