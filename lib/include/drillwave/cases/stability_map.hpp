#pragma once
// Two-parameter stability maps: a case's linear verdict on a grid of two parameters addressed by JSON pointers, and
// optionally (simulate) the regime a run of the case as written (from its own initial state, usually rest) reaches at
// each grid point, so the map shows where linear stability and the motion found from rest part (bistability).
//
//   StabilityMapSpec spec{ParseMapAxis("/model/top/speed_rad_s/knots/1/1=4:16:100", doc),
//                         ParseMapAxis("/model/bit/inertia_kgm2=50:150:100", doc), 2, false};
//   WriteStabilityMap2D(doc, spec, StabilityMap2D(doc, spec), "out");
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/analysis/spectrum.hpp"
#include "drillwave/io/svg_heatmap.hpp"

namespace drillwave::cases {

struct MapAxis {
  std::string pointer;
  std::vector<double> values;
};

// "POINTER=first:last:count" (or "POINTER=v1,v2,..."): the values as ParseSweepValues reads them. Throws
// ParameterError(option, ...) naming the text for anything else, for a pointer the case has no field at, and for a first
// value the field refuses (the case is parsed with it).
MapAxis ParseMapAxis(const std::string& text, const nlohmann::json& document, const std::string& option = "map");

struct StabilityMapSpec {
  MapAxis x, y;
  int jobs = 1;           // threads, >= 1
  bool simulate = false;  // also run the case at every grid point
  // Every point by ComputeSpectrum (the reference). Otherwise (the default) the rows are walked point by point, each
  // point's rightmost roots found again from its neighbour's and certified by the argument principle
  // (AnalyzeStabilityFromNeighbour): the same verdicts and rightmost roots at a fraction of the cost for large systems.
  bool full_spectrum = false;
};

// The simulated regime at a grid point, from the run's summary statistics over the case's statistics window.
enum class Regime { kNotSimulated, kSmooth, kStickSlip, kBitBouncing, kFailed };
const char* RegimeName(Regime r);  // "", "smooth", "stick-slip", "bit bouncing", "failed"
// Bit bouncing: the bit left the bottom (off_bottom_fraction > 0); stick-slip: it stuck (stick_onsets or
// stick_fraction > 0); smooth otherwise.
Regime ClassifyRun(const nlohmann::json& summary);

struct StabilityMapCell {
  double x = 0, y = 0;
  bool analysed = true;   // false: the kind has no linearization (a simulate-only map, e.g. jeffcott)
  int steady_states = 0;  // 0: nothing turns steadily (the verdict columns are NaN)
  // Of the steady state with the best verdict (stable before marginal before unstable; then the smallest rightmost
  // real part): a stable one means a stable steady motion exists at this point.
  double spectral_abscissa = 0, frequency_rad_s = 0, essential_abscissa = 0;
  analysis::Spectrum::Verdict verdict = analysis::Spectrum::Verdict::kUnstable;
  Regime regime = Regime::kNotSimulated;
  double stick_fraction = 0;  // of the run (NaN unless simulated and reported)
  double severity = 0;        // the run's stick_slip_severity (NaN unless simulated and reported)
};

// "stable", "marginal", "unstable", "none" (no steady state) or "n/a" (no linearization).
const char* CellVerdictName(const StabilityMapCell& cell);
// A steady motion exists at the cell and is not unstable (stable or marginal): linearly free of stick-slip.
bool LinearlySteady(const StabilityMapCell& cell);

struct StabilityMapResult {
  std::vector<StabilityMapCell> cells;  // x varies fastest: cells[j * nx + i] is (x[i], y[j])
  double linear_wall_time_s = 0, simulation_wall_time_s = 0;
  // Full spectra computed: every steady state's with spec.full_spectrum; otherwise the first point's and those where
  // the argument principle did not certify the continued roots (the two probes that choose the walking axis included).
  int full_spectra = 0;
  // A map over parameter draws (StabilityMapOverDraws): per cell, the share of the draws whose linear verdict is not
  // steady (no stable or marginal steady state) and, with simulate, whose run from the case's start sticks and slips
  // (NaN without simulate); the cells above are the case's own. Empty for a map of the case alone.
  int draws = 0;
  std::vector<std::string> draw_pointers;
  std::vector<double> p_linearly_unstable, p_stick_slip;
};

// Every grid point's document is built and parsed before any work (InputError naming the pointers and values), and
// the kind's linearization is checked on the first (a kind without one: InputError, unless simulate, which then maps
// the regimes alone); then the analyses (and runs) go in parallel (core/parallel.hpp).
StabilityMapResult StabilityMap2D(const nlohmann::json& document, const StabilityMapSpec& spec,
                                  const analysis::SpectrumOptions& options = {});

// Parameter values to map over, one row a draw (a posterior's samples): `pointers[i]` set to `rows[d][i]`.
struct ParameterDraws {
  std::vector<std::string> pointers;
  std::vector<std::vector<double>> rows;
};

// The draws in a CSV file whose JSON-pointer columns ("/model/...") hold the values (calibrate's
// posterior_samples.csv; other columns are ignored): `count` rows spread evenly over the file (0: every row). Throws
// ParameterError("draws", ...) for a file without such columns or rows, and for a pointer the case has no number at.
ParameterDraws ReadParameterDraws(const std::string& file, const nlohmann::json& document, int count);

// The map for every draw (the document with the draw's values), and the probabilities per cell over them, beside the
// case's own map. progress(done, draws) after each draw's map.
StabilityMapResult StabilityMapOverDraws(const nlohmann::json& document, const StabilityMapSpec& spec,
                                         const ParameterDraws& draws,
                                         const std::function<void(int, int)>& progress = nullptr);

// The map as a heat map (no title): the verdict's colour, shaded by the rightmost real part, the regime as marker.
io::HeatMap StabilityHeatMap(const StabilityMapSpec& spec, const StabilityMapResult& result);

// stability_map.csv (x, y, steady_states, spectral_abscissa_per_s, frequency_rad_s, essential_abscissa_per_s, verdict
// stable, marginal, unstable, none (no steady state) or n/a (no linearization), regime, stick_fraction; over draws also
// p_linearly_unstable and p_stick_slip), stability_map.svg (heat map of the verdict, shaded by the rightmost real part,
// with the simulated regime as markers), over draws p_stick_slip.svg, report.md, case.json.
void WriteStabilityMap2D(const nlohmann::json& document, const StabilityMapSpec& spec,
                         const StabilityMapResult& result, const std::string& out_dir);

}  // namespace drillwave::cases
