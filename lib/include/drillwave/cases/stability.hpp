#pragma once
// Linearized stability of a case (DESIGN.md §4): its steady states at the inputs' final values, the characteristic
// roots of the linearization about each, and stability maps over one parameter addressed by its JSON pointer.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/analysis/spectrum.hpp"
#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/sweep.hpp"

namespace drillwave::cases {

struct OperatingPointStability {
  LinearizedOperatingPoint point;
  analysis::Spectrum spectrum;  // of point.system: the discretized model the simulation integrates
  // Of point.continuum where the kind gives one (a Kelvin-Voigt string): the physics the pieces approximate.
  std::optional<analysis::ContinuumSpectrum> continuum = std::nullopt;
};

// Whether a Kelvin-Voigt string's continuum spectrum is computed beside the discretized one: maps, whose verdicts are
// the discretized model's (the one `--simulate` runs), skip it.
enum class ContinuumRoots { kComputed, kSkipped };

// Every steady state of the case with its spectrum. Throws InputError if the kind has no linearization.
std::vector<OperatingPointStability> AnalyzeStability(const Case& c, const analysis::SpectrumOptions& options = {},
                                                      ContinuumRoots continuum = ContinuumRoots::kComputed);
// As AnalyzeStability, with each steady state's roots found again from the same steady state's rightmost roots at a
// neighbouring parameter value (analysis/rightmost_root.hpp): where the argument principle certifies the rightmost
// root, the spectrum holds the roots found so (the verdict, the spectral and essential abscissae are ComputeSpectrum's;
// roots beyond the rightmost few are not sought); elsewhere, and without a neighbour, the full spectrum, counted in
// full_spectra.
std::vector<OperatingPointStability> AnalyzeStabilityFromNeighbour(const Case& c,
                                                                   const std::vector<OperatingPointStability>& neighbour,
                                                                   const analysis::SpectrumOptions& options,
                                                                   int& full_spectra,
                                                                   ContinuumRoots continuum = ContinuumRoots::kComputed);

// {"operating_points": [{"steady_state", "stable", "spectral_abscissa", "essential_abscissa", "roots": [[re, im,
// residual], ...] (the rightmost max_roots)}]}, each point with a continuum spectrum also "continuum_kelvin_voigt":
// {"stable", "verdict", "spectral_abscissa", "essential_abscissa", "certified", "box", "roots_re_im_residual"}.
nlohmann::json StabilityToJson(const std::vector<OperatingPointStability>& result, int max_roots = 12);

// Beyond the linearization: the case run from its own start (as `run` runs it), and whether that motion and the
// linear verdicts tell of two coexisting attractors.
struct RunFromStart {
  bool ran = false;          // false: the kind reports no stick statistics, or the run failed (see note)
  bool sticks = false;       // the bit stuck in the statistics window
  double stick_fraction = 0;
  std::string note;          // LinearVerdictNote, or why nothing was run; empty when motion and verdict agree
};
RunFromStart CompareWithRunFromStart(const Case& c, const std::vector<OperatingPointStability>& points);

// The sentence that sets a run's motion against the linear verdicts, empty when they agree: stick-slip beside a
// steady state that is not unstable (two attractors: the start decides), or no sticking although every steady state
// is unstable. `run` names the run in the sentence ("this run", "the run from the case's start").
std::string LinearVerdictNote(const std::vector<OperatingPointStability>& points, bool sticks, const std::string& run);

// stability.json, roots.csv (every root found: point, Re, Im, residual), report.md, case.json; all or nothing. With
// from_start, stability.json and the report also give that run's motion and note.
void WriteStabilityOutputs(const Case& c, const std::vector<OperatingPointStability>& result,
                           const std::string& out_dir, const RunFromStart* from_start = nullptr);

// One row per value and steady state (branch 0 = the slowest).
struct StabilityMapRow {
  double value = 0;
  int branch = 0;
  double speed_rad_s = 0;             // the steady bit (last inertia) speed
  double spectral_abscissa = 0;       // rightmost Re s
  double frequency_rad_s = 0;         // Im s of that root
  double essential_abscissa = 0;      // -inf for retarded systems
  bool stable = false;
  analysis::Spectrum::Verdict verdict = analysis::Spectrum::Verdict::kUnstable;  // marginal: see spectrum.hpp
};
// Values are checked first (InputError naming the pointer and value); spec.jobs threads (core/parallel.hpp): an
// analysis that throws stops the map and its exception (the lowest failing value's) reaches the caller.
std::vector<StabilityMapRow> StabilityMap(const nlohmann::json& document, const SweepSpec& spec,
                                          const analysis::SpectrumOptions& options = {});
// stability_map.csv (with verdict: 1 stable, 0 marginal, -1 unstable), stability_map.svg (steady speed and rightmost
// Re s against the parameter), report.md.
void WriteStabilityMap(const nlohmann::json& document, const SweepSpec& spec,
                       const std::vector<StabilityMapRow>& rows, const std::string& out_dir);

// Where the model linearizes, sets summary["linear_verdict"] when the motion a run found (its summary's stick_onsets)
// differs from the linear verdict at the same set-point: stick-slip beside a stable steady state (two attractors: the
// start decides), or no sticking although every steady state is unstable. Otherwise leaves the summary as it is.
// The linearization costs a fraction of a second (larger systems than 64 states are left out); sweeps and fits do not
// ask for it.
void AddLinearVerdict(const Case& c, nlohmann::json& summary);

}  // namespace drillwave::cases
