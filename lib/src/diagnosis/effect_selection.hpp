#pragma once
// The diagnosis loop's effect selection (internal to the loop): every effect the case can model screened cheaply,
// the strongest fitted alone, then in pairs; a kept set checked against itself without each of its effects (backward
// elimination) and extended by each other single and the best screened other effect (forward selection); each
// effect of a kept set contested by the base's calibrations in its place; rival sets within chance of the best contest
// it, and only what they share is named; the base parameters offered among the effects last, beside the kept set.
// Each decision: held-out error below (1 - margin) of the reference's, by
// more than chance moves it, and a lower AIC on the fit window; a set against the baseline and every fitted smaller
// set of its effects.
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/diagnosis/loop.hpp"
#include "model_runs.hpp"

namespace drillwave::diagnosis::loop_internal {

// "a + b", or "baseline" for none.
std::string Joined(const std::vector<std::string>& names);
// "648, 4.4 (another regime), 1.1": each draw's error, those out of the recording's regime marked.
std::string EachDraw(const std::vector<double>& errors, const std::vector<char>& in_regime);
// `doc` with each effect switched on at its parameters' values u (in their unit cubes, one after the other).
nlohmann::json Applied(nlohmann::json doc, const std::vector<const Effect*>& effects, const std::vector<double>& u);
// The effects' first values, in their unit cubes.
std::vector<double> StartOf(const std::vector<const Effect*>& effects);
// One judged model's draws: each draw's held-out error, whether it is in the recording's regime, its seed.
struct DrawsOf {
  const std::vector<double>* errors;
  const std::vector<char>* in_regime;
  const std::vector<int>* seeds;
};
// The draws two judged models share, as (mine, theirs) held-out errors: those of one seed (one rock, roughness and
// noise) that are both in the recording's regime, in the order of `mine`. A draw that left the regime is paired with
// nothing (its error measures the other attractor, not the model; train rec01: a baseline draw bouncing at 434 against
// a Stribeck draw at 0.14 made the paired spread 190). Where no seed has both in the regime, every shared seed.
std::vector<std::pair<double, double>> PairedDraws(const DrawsOf& mine, const DrawsOf& theirs);
// How much a held-out error moves by chance: for a model within its features' noise the error (the mean of K squared
// differences in scales) varies by sqrt(2 / K) from one window to the next.
double ErrorChance(const FeatureSet& held_out);

class EffectSelection {
 public:
  using Say = std::function<void(const std::string&)>;
  // `loop` holds the baseline (errors, AIC, fit draw), the proposals sorted by evidence and the recording's features;
  // the selection adds its candidates, screening, rivals, kept index and model runs there. `base` is the calibrated
  // base case the effects are switched on in.
  EffectSelection(const LoopOptions& o, const ModelRuns& runner, const nlohmann::json& base, DiagnosisLoop& loop,
                  Say say);

  // Every proposal the case can model; the others become failed candidates ("cannot be modelled").
  void FindModelable();
  // Screening, singles in full, pairs, then the check and extension of the kept set; rivals last.
  void Select();

 private:
  std::vector<const Effect*> EffectsOf(const std::vector<int>& set) const;
  nlohmann::json DocumentAt(const std::vector<int>& set, const std::vector<double>& u) const;
  std::vector<double> StartOfSet(const std::vector<int>& set) const;
  bool MovesOnlySensors(const std::vector<int>& set) const;
  // A fit of the set from `start`; a screening fit is cheap (one start, a few evaluations per parameter, no curvature)
  // and judged on one free run over the whole span instead of the draws' median.
  Candidate Fit(const std::vector<int>& set, std::vector<double> start, int threads, bool screening);
  void FitAll(const std::vector<std::vector<int>>& sets, const std::function<std::vector<double>(std::size_t)>& start);

  // What a candidate must beat: the baseline or the best smaller set of its effects (its held-out error, its AIC, and
  // its draws, paired with the candidate's by seed: PairedDraws).
  struct Reference {
    double error, aic;
    DrawsOf draws;
    const FeatureSet* held_out;  // its held-out features' means over its draws (a judged model always has them)
    std::string name;            // "the baseline", or its effects
    std::vector<std::string> effects = {};  // none for the baseline
  };
  static DrawsOf DrawsOfCandidate(const Candidate& c) {
    return {&c.held_out_draw_errors, &c.draw_in_regime, &c.draw_seeds};
  }
  static Reference ReferenceOf(const Candidate& c) {
    return {c.held_out_error, c.aic, DrawsOfCandidate(c), &c.held_out_mean, Joined(c.effects), c.effects};
  }
  int ParameterOnEdge(const Candidate& c) const;
  double DifferenceSpread(const Candidate& c, const Reference& reference) const;
  bool Resolved(const Candidate& c, const Reference& reference) const;
  bool PredictsAsWell(const Candidate& c, const Reference& lead) const;
  // The largest difference of the two models' held-out feature means, in the recording's scales.
  double LargestDifference(const Candidate& c, const Reference& reference) const;
  // Whether c qualifies against the reference; `why` (if given) says which test decided, with its numbers.
  bool Qualifies(const Candidate& c, const Reference& reference, std::string* why = nullptr) const;
  // The first effect c adds to the reference that the recording does not indicate (evidence at most kWeakEvidence;
  // the base's own parameters excepted), or "".
  std::string UnindicatedAddition(const Candidate& c, const Reference& reference) const;
  Reference BaselineReference() const;
  std::vector<int> IndicesOf(const Candidate& c) const;
  int Representative(const std::vector<int>& set) const;
  bool QualifiesAgainstSubsets(int index, std::string* why = nullptr) const;
  int BestQualifying() const;
  std::vector<double> OwnFit(int effect) const;
  std::vector<double> ScreenedOrStart(int effect) const;
  std::vector<double> ValuesOf(const Candidate& from, const std::vector<int>& set) const;
  std::vector<double> KeptValuesOrStart(const Candidate& kept, const std::vector<int>& set) const;
  bool FittedAt(const std::vector<int>& set, const std::vector<double>& u) const;

  std::vector<int> Screen();  // the singles to fit in full
  void CheckAndExtend(const std::vector<int>& ranked);
  void ContestWithTheBase();
  int BestScreenedExtension(const Candidate& lead, const std::vector<int>& ranked,
                            const std::function<std::vector<int>(int)>& extended,
                            const std::function<std::vector<double>(const std::vector<int>&)>& start);
  void ContestRivals();
  void CalibrateBesideTheKept();

  const LoopOptions& o_;
  const ModelRuns& runner_;
  const nlohmann::json& base_;
  DiagnosisLoop& loop_;
  Say say_;
  std::vector<int> modelable_;
  double k_features_ = 0;
  std::mutex progress_mutex_;
};

}  // namespace drillwave::diagnosis::loop_internal
