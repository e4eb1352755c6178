#pragma once
// The diagnosis loop (DESIGN.md §5, issue 13 item 2): name the physics a model leaves out, model it, refit, and
// prove on data the fit did not see that the model got better.
//
//   1. The recording's artefacts (spikes, dropouts) are masked, not modelled (Hampel filter, as the inspection); the
//      model's channels pass the same filter, so that physics as short as a glitch is masked on both sides alike.
//      Artefacts are rare: a channel with more than 2 % of its samples flagged (a bouncing bit's weight on bit) is
//      showing its motion and is left whole on both sides.
//      Its sensor noise is estimated per channel and carried into the model's measured channels (a
//      sensors block), so that model and recording are compared as the recording was made; so is its sampling: each
//      recorded sample the mean over its window (a logger's 100-Hz samples are 10-ms means, which blunt a bouncing
//      bit's impacts), the model's measured channels the same window mean of a finer output.
//   2. The usable recording is split into a fit window and a later held-out window. The baseline's error on each is
//      the feature distance (features.hpp): differences counted in each feature's own variability. The baseline and
//      every fitted candidate run several draws of their random inputs (roughness and noise seeds) and are judged by
//      the median draw, so that a multistable motion's lottery does not decide.
//   3. Rules read the baseline's differences as graded evidence for effects (effects.hpp); the strongest the case
//      can model are fitted alone on the fit window (NLopt, bounded); then pairs (every pair of the three singles
//      that predict the held-out window best, and the best with the fourth), since one missing effect may hide what
//      another explains. A kept set of two or more is checked by backward elimination — each set without one of its
//      effects refitted from the kept values — and, once it survives, extended by each other single fitted alone and
//      by the best of the other effects screened as its extensions (forward selection, up to max_effects). Each effect of
//      a kept set of two or more is contested by the base's calibrations in its place (the rock was calibrated before
//      any effect), and rival sets within chance of the best contest it: only what they share is named.
//   4. A candidate is kept only when its held-out error falls below (1 - margin) of the baseline's, by more than
//      chance moves the error (sqrt(2 / K) over K features: see loop.cpp), and an information criterion on the fit
//      window (AIC over the features) agrees; a set of effects only when it beats every fitted smaller set of its
//      effects the same way (each effect earns its place). The fitted parameters get uncertainties from the
//      objective's curvature.
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/model_kind.hpp"
#include "drillwave/diagnosis/comparison.hpp"
#include "drillwave/diagnosis/effects.hpp"
#include "drillwave/diagnosis/features.hpp"

namespace drillwave::diagnosis {

struct LoopOptions {
  std::vector<ChannelMap> maps;   // recording channel <- model channel (scaled)
  double model_time_offset_s = 0;  // subtracted from the model's time: the warm-up before the recording
  double fit_begin_s = 0, fit_end_s = 0;            // recording time
  double held_out_begin_s = 0, held_out_end_s = 0;  // recording time, after the fit window
  double margin = 0.2;            // a kept effect lowers the held-out error by at least this fraction
  int evaluations_per_parameter = 10;  // fit budget of a candidate: this times its parameters, plus 2
  // Every effect the case can model is screened by a fit of this budget per parameter (one start) and one free run
  // over the whole span; the max_singles best screened are fitted in full, and pairs and extensions come from these.
  int screening_evaluations_per_parameter = 4;
  int max_singles = 4;  // 0: the case's own errors only (no base calibration, screening or fits)
  bool calibrate_base = true;  // the base's uncertain parameters fitted first (effects.hpp: BaseCalibrations)
  bool fit_effects = true;     // false: the (calibrated) base judged, no effect screened or fitted
  bool measure_regime_margin = true;  // the model that stands run with its set-point moved (RegimeMargin)
  int max_effects = 3;            // forward selection stops at this many effects
  // The fits' runs use at most this tolerance's accuracy (rel and abs; 0: the case's); candidates are judged by runs
  // at the case's own tolerance. The features do not move with the tolerance up to 1e-4; at 1e-3 they did for
  // rec10 (tests/diagnosis/tolerance_test.cpp). A set that moves only the sensors is fitted on the baseline's run.
  double fit_tolerance = 1e-4;
  int threads = 1;
  bool carry_noise = true;        // estimated sensor noise added to the model's measured channels
  // Each recorded sample is the mean over this window ending at it (0: point samples); the model's measured channels
  // are the same mean, from an output a fifth of the window apart.
  double sample_window_s = 0;
  unsigned seed = 1;
  // The baseline and every fitted candidate are judged over this many independent draws of the model's random inputs
  // (each seed in the case's model and the sensor noise's; draw 0 is the case as given), by the median draw: the one
  // whose held-out error is the median. One draw of a multistable motion (a bit that bounces in some runs and drills
  // in others) decides by chance which effect "explains" it; the median needs most draws to agree. Only draws in the
  // recording's regime (bouncing or on the bottom) count: more are drawn, up to three times as many, to find them,
  // and the fits run the baseline's first such draw. (A mean of the draws' features counted in their spread was
  // tried: one bouncing draw of three widened every scale so far that any model matched.) Five rather than three:
  // a chaotic motion's error varies from draw to draw by about sqrt(2 / K) of itself, and the median of n draws by
  // about 1.25 / sqrt(n) of that, 0.72 for three, 0.56 for five. At rec12's point (on-bottom draws' fit-window errors
  // 0.55-2.5) three draws let the AIC refuse a DC motor that predicts the held-out half twice as well; the judging
  // runs are a tenth of a diagnosis's.
  int draws = 5;
  FeatureOptions features;

  // A finite offset; the windows finite and in order, the held-out one from the fit window's end on (left at 0 they
  // are not: DefaultLoopOptions or the caller sets them); margin in [0, 1); the budgets and counts >= 1 (max_singles
  // >= 0); fit_tolerance 0 or in [1e-14, 1e-2]; sample_window_s in [0, 60]; draws in [1, 20]; valid features
  // (core/validity.hpp). The maps and windows are checked against the recording by the loop's preparation.
  bool IsValid(std::string* error) const;
};

struct FittedParameter {
  std::string effect, name, unit;
  double value = 0, sigma = 0;  // sigma from the curvature of the fit objective (NaN: not identified)
  double lower = 0, upper = 0;
};

struct CalibratedParameter {  // a base parameter fitted before the effects (effects.hpp: BaseCalibrations)
  std::string calibration, name, unit;
  double value = 0, case_value = 0, lower = 0, upper = 0;
  bool kept = false;  // judged over draws it brought the base closer (the fit window better, the held-out window
                      // no worse beyond chance): the base uses it
};

struct Candidate {
  std::vector<std::string> effects;
  std::vector<FittedParameter> parameters;
  double fit_error = 0, held_out_error = 0;  // medians over the draws judged (LoopOptions::draws)
  std::vector<double> held_out_draw_errors;   // each draw's own held-out error, every draw run
  std::vector<char> draw_in_regime;           // per draw run: in the recording's regime (judged), see DiagnosisLoop
  std::vector<int> draw_seeds;                // per draw run: its seed (draws of one seed are compared pairwise)
  FeatureSet held_out_mean;  // each held-out feature's mean over the draws judged
  double aic = 0;  // K ln(fit_error) + 2 p over the K features of the fit window
  int evaluations = 0;
  int redrawn_runs = 0;       // fit runs drawn again because a start landed in the other regime
  int failed_runs = 0;        // evaluations whose run the case rejected or that failed numerically
  int failed_draws = 0;       // judging draws whose run failed numerically (left out of the median)
  std::string first_failure;  // the first of their messages
  bool kept = false;
  // Its decision against the baseline and its smaller sets' fits, with the numbers (a qualifying set may still be left
  // unnamed by rivals within chance: DiagnosisLoop::ambiguous).
  std::string verdict;
  std::vector<double> unit_values;   // the fitted parameters in the fit's unit cube
  std::vector<double> start_values;  // where the fit started, in the same cube
  std::string failure;  // why it could not be fitted (a run failed, the component is missing), empty otherwise
  double wall_seconds = 0;  // its fit and judging, on the clock (beside the fits the loop runs alongside)
};

// Where a diagnosis spent its time, on the clock [s]: the stages in their order, and the whole.
struct LoopTimes {
  double preparing = 0;    // the recording read, the plain case's run
  double calibration = 0;  // the base's parameters calibrated before any effect
  double baseline = 0;     // the base's draws judged, the proposals read
  double selection = 0;    // every effect screened, fitted alone, in sets; rivals
  double fitted = 0;       // the model that stands run and judged, its regime margin measured
  double total = 0;        // the loop from its start to its report's data
};

// How far the model that stands is from the edge of its motion regime over the held-out window (issue 32 item 4): its
// top set-point (every knot) scaled up and down until the held-out window's regime (stick-slip or smooth, bouncing or
// on the bottom) changes, one draw (the fits' own) a run. A fitted model within a few percent of the edge may leave
// the recording's regime as soon as its operating point drifts (the UFRJ rig's first fit: 0.36 % of set-point).
struct RegimeMargin {
  bool measured = false;           // false: the case has no top set-point /model/top/speed_rad_s to move
  std::string recorded, model;     // the held-out window's regimes: the recording's and the model's at its set-point
  // The set-point changes [%] at which the model's regime first differs, each side within +-kRegimeSearchPercent
  // (NaN: the same regime up to there), to a resolution of about a percent.
  double lower_percent = std::numeric_limits<double>::quiet_NaN();
  double upper_percent = std::numeric_limits<double>::quiet_NaN();
  bool near_edge = false;  // a change within kNearRegimeEdgePercent changes the regime
  int runs = 0;
};
inline constexpr double kRegimeSearchPercent = 20;
inline constexpr double kNearRegimeEdgePercent = 5;
// One sentence: the regimes and where the model's changes ("... near the edge" where it is).
std::string RegimeMarginText(const RegimeMargin& margin);

struct DiagnosisLoop {
  // The effects of a set that qualified and was rejected because its held-out motion regime is not the recording's
  // while the baseline's is (empty: none); nothing is then named.
  std::vector<std::string> regime_rejected;
  nlohmann::json baseline_document, fitted_document;
  std::vector<std::pair<std::string, double>> noise;  // recording channel, estimated noise std (its unit)
  std::vector<std::pair<std::string, int>> masked_samples;  // recording channel, artefact samples masked
  std::vector<std::string> channels_left_whole;  // channels with too many bursts for artefacts (motion), left whole
  std::string bit_speed = "bit_rpm";  // the recording's channel read as the bit speed (FeatureOptions::bit_speed)
  FeatureSet recording_fit, recording_held_out;
  // The models' features: the median draw's (LoopOptions::draws).
  FeatureSet baseline_fit, baseline_held_out, fitted_fit, fitted_held_out;
  std::vector<double> baseline_held_out_draw_errors;  // each draw's own held-out error, every draw run
  FeatureSet baseline_held_out_mean;                  // each held-out feature's mean over the draws judged
  // The recording's regime: its bit's share of time off the bottom (NaN: no weight on bit) and whether that makes it
  // a bouncing bit. A model may have both regimes at one set-point, and which one a run ends on depends on its start:
  // a model is judged on its draws in the recording's regime (more are drawn to find them), on all where none is.
  double recorded_off_bottom_share = 0;
  bool recording_bounces = false;
  std::vector<char> baseline_draw_in_regime;  // per draw run
  std::vector<int> baseline_draw_seeds;       // per draw run
  int fit_draw = 0;  // the draw (seed) the fits run: the baseline's first in the recording's regime
  double baseline_fit_error = 0, baseline_held_out_error = 0, fitted_fit_error = 0, fitted_held_out_error = 0;
  double error_chance = 0;  // how much the held-out error moves by chance for a model that matches (sqrt(2 / K))
  double baseline_aic = 0;
  std::vector<Effect> proposals;  // every effect with its evidence (strength 0: no evidence)
  std::vector<CalibratedParameter> calibration;  // the base's parameters as calibrated (empty: none for this kind)
  bool calibration_kept = false;  // a calibration was kept (CalibratedParameter::kept): the base differs from the case
  double plain_fit_error = 0, plain_held_out_error = 0;  // the case as given, before calibration (draw 0)
  // Every modelable effect's cheap fit (one draw judged), in proposal order; then the kept sets' extensions screened.
  std::vector<Candidate> screening;
  std::vector<Candidate> candidates;
  // Rival explanations: sets that lower the held-out error as the best one does, within chance of it (see loop.cpp).
  // Only the effects every rival shares are named; the rest are reported here, each rival with its held-out error.
  std::vector<Candidate> rivals;
  int kept = -1;  // index into candidates, -1: the baseline stands
  std::vector<std::string> unexplained;  // held-out features still more than 3 scales off after the fit
  Recording baseline_model, fitted_model;  // the median draw's measured channels on the recording's times and names
  RegimeMargin regime_margin;  // of the fitted model (the baseline's where nothing is kept)
  int model_runs = 0;
  LoopTimes wall_seconds;
};

// Options for a case and a recording: the model's time offset (a warm-up before the recording), and the usable
// recording — after `settle_s` when there is a warm-up, up to the end of the recording or of the case's run — split
// in halves, the fit window first; each sample the mean over its sample interval. Everything else at its default;
// the channel maps are left to the caller.
LoopOptions DefaultLoopOptions(const cases::Case& c, const Recording& recording, double model_time_offset_s,
                               double settle_s = 5);

// progress(message) reports each step (candidate started, fit evaluations, held-out errors) as it happens.
using LoopProgress = std::function<void(const std::string&)>;

// `document` is the case to diagnose (its duration must cover the held-out window after the offset). Throws
// ParameterError for options that are not valid (windows overlapping among them), InputError for windows outside the
// recording, an unmapped channel, or a model whose scale is far from the recording's (a channel's typical level
// differing by more than a factor 10).
DiagnosisLoop RunDiagnosisLoop(const nlohmann::json& document, const Recording& recording, const LoopOptions& options,
                               const LoopProgress& progress = nullptr);

// The relative probability of each model the loop fitted, by its AIC on the fit window (Akaike weights,
// exp(-(AIC - AIC_min) / 2) normalised over the baseline and each set of effects, a set fitted more than once by its
// lowest AIC): an approximation of the models' evidence beside the held-out decision, which is the loop's.
struct ModelProbability {
  std::vector<std::string> effects;  // empty: the baseline
  double aic = 0, weight = 0;
};
std::vector<ModelProbability> AkaikeWeights(const DiagnosisLoop& loop);

nlohmann::json DiagnosisLoopToJson(const DiagnosisLoop& loop);

// The fitted model (the baseline where nothing is kept) run freely from its start to `until_s` of recording time: its
// mapped channels named and scaled as the recording's, on the recording's sample interval from the fit window's
// start, without sensor noise — a forecast to hold against what is recorded after the recording's end. Throws
// ParameterError("predict_until") unless until_s lies after the held-out window and within 100 times the span from the fit
// window's start past it (CheckPredictionTime, which a caller runs before the loop).
void CheckPredictionTime(const LoopOptions& options, double until_s);
Recording PredictFitted(const DiagnosisLoop& loop, const LoopOptions& options, const Recording& recording, double until_s);

}  // namespace drillwave::diagnosis
