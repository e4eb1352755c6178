#pragma once
// The diagnosis loop's simulations of one recording (internal to the loop): a case run to a window's end, its
// channels measured through the case's sensors on the recording's times and masked as the recording was; runs that
// differ only in their sensors share one simulation (a cache); a model run in draws of its random inputs until enough
// are in the recording's regime, and judged by the median draw.
#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/diagnosis/features.hpp"
#include "drillwave/diagnosis/loop.hpp"

namespace drillwave::diagnosis::loop_internal {

constexpr double kFailedRun = 1e6;  // objective of a run that fails numerically or that the case rejects
constexpr double kWorkFactor = 6;  // a fit's run may cost this many times the baseline's evaluations
// A judging run (a fitted model over the whole span, at the case's tolerance) may cost this many times: the fitted
// values are no corner of the box, but a model with more physics costs more (a distributed BHA of 240 m of collars
// cost more than 6 times the lumped body's at rec04 of synthetic-train, and failed its judging).
constexpr double kJudgingWorkFactor = 30;
// A bit off the bottom for more than this share of the usable span bounces (the synthetic recordings: 0 in eleven,
// 0.36 in rec04's bounce; a bouncing model's runs 0.27-0.51).
constexpr double kBouncingShare = 0.01;
// At most this many times LoopOptions::draws are run to find draws in the recording's regime (rec12's baseline: 4 of
// 9 starts stay on the bottom).
constexpr int kMaxDrawFactor = 3;

// The model's measured channels on the recording's times in [begin, end] (model time less offset_s), named and
// scaled as the recording's.
Recording ModelRecording(const cases::RunResult& run, const std::vector<ChannelMap>& maps, const Recording& rec,
                         double offset_s, double begin_s, double end_s);

// Draw d of a case's random inputs: every seed in its model (bottom roughness, rock heterogeneity) moved by d, the
// sensor noise's by 7919 d (draw 0: the case as given).
nlohmann::json Drawn(nlohmann::json doc, int d);

// A model's draws, each marked in the recording's regime or not.
struct Draws {
  std::vector<Recording> models;
  std::vector<char> in_regime;
  std::vector<int> seeds;  // each model's draw (Drawn): two models' draws of one seed share rock, roughness and noise
  int failed = 0;  // draws whose run failed numerically, left out
};

// A model judged over its draws by the median draw (LoopOptions::draws) of those in the recording's regime: that
// draw's channels and features, its errors, and every draw's held-out error and regime.
struct Judged {
  Recording model;
  FeatureSet fit, held_out;
  FeatureSet held_out_mean;  // each held-out feature's mean over the draws judged (NaN where none defines it)
  double fit_error = 0, held_out_error = 0;
  std::vector<double> held_out_draw_errors;
  std::vector<char> draw_in_regime;
  std::vector<int> draw_seeds;
  int failed_draws = 0;
};

class ModelRuns {
 public:
  // A fit's runs may use a looser tolerance than the case's (features are statistics of the motion, which do not
  // move with it: tests/diagnosis/loop_test.cpp); the runs that decide (whole span, held out) use the case's own.
  enum class Tolerance { kCase, kFit };

  // `recording` is the masked recording (its channels named as o.maps' recording sides), `whole` which of its
  // channels were left unmasked, `features` the options its features were measured with, `fit` and `held_out` those
  // features on the two windows.
  ModelRuns(const LoopOptions& o, const Recording& recording, std::vector<char> whole, const FeatureOptions& features,
            const FeatureSet& fit, const FeatureSet& held_out);

  // The case run for `duration` s of model time, measured as the recording. Safe to call from several threads.
  Recording Run(nlohmann::json doc, double duration, Tolerance tolerance = Tolerance::kCase,
                double work_factor = kWorkFactor) const;
  // Every later run may cost at most its work factor times the costliest run so far per simulated second.
  void SetWorkBudget();

  // LoopOptions::draws draws of the case over the whole span (fit and held-out windows) at the case's tolerance, run
  // until that many are in the recording's regime; a draw that fails numerically is left out and counted (throws
  // NumericalError when every draw fails).
  Draws RunDraws(const nlohmann::json& doc, int threads) const;
  // The median draw of a model's runs in the recording's regime (of all its runs where none is): the one whose
  // held-out error is the median (the lower middle one of an even number); its fit-window error the median of those
  // draws' (an information criterion on the fit window).
  Judged Judge(Draws runs) const;

  bool InRegime(const Recording& model) const;
  double RecordedOffBottomShare() const { return recorded_off_bottom_share_; }
  bool RecordingBounces() const { return recording_bounces_; }
  // A model's features on the fit or held-out window, measured as the recording's.
  FeatureSet FitFeatures(const Recording& model) const;
  FeatureSet HeldOutFeatures(const Recording& model) const;
  // Each run simulated (not those the cache answers) calls `on_run` as it starts with the number started so far, from
  // the thread that runs it: the loop's progress.
  void OnRun(std::function<void(int)> on_run) { on_run_ = std::move(on_run); }
  double FullDuration() const { return full_duration_; }  // model time to the held-out window's end
  double FitDuration() const { return fit_duration_; }    // model time just past the fit window's end

 private:
  const LoopOptions& o_;
  const Recording& recording_;
  std::vector<char> whole_;
  FeatureOptions features_, model_features_;
  const FeatureSet& recording_fit_;
  const FeatureSet& recording_held_out_;
  double full_duration_, fit_duration_;
  double recorded_off_bottom_share_;
  bool recording_bounces_;
  double evaluations_per_second_ = 0;  // the costliest run's so far, once the baseline has run
  mutable std::mutex cache_mutex_;
  mutable std::map<std::string, std::shared_ptr<const cases::RunResult>> simulations_;
  mutable std::atomic<int> runs_simulated_{0};
  std::function<void(int)> on_run_;
};

}  // namespace drillwave::diagnosis::loop_internal
