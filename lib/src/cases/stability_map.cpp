#include "drillwave/cases/stability_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/stability.hpp"
#include "drillwave/cases/sweep.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/parallel.hpp"
#include "drillwave/core/stopwatch.hpp"
#include "drillwave/core/validity.hpp"
#include "drillwave/io/json_reader.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/io/axis_label.hpp"
#include "drillwave/io/svg_heatmap.hpp"

namespace drillwave::cases {
namespace {

using Verdict = analysis::Spectrum::Verdict;

int Rank(Verdict v) { return v == Verdict::kStable ? 0 : v == Verdict::kMarginal ? 1 : 2; }

// The cell's linear columns from the steady state with the best verdict.
void TakeBestSteadyState(const std::vector<OperatingPointStability>& points, StabilityMapCell& cell) {
  cell.steady_states = static_cast<int>(points.size());
  const OperatingPointStability* best = nullptr;
  for (const auto& p : points)
    if (!best || Rank(p.spectrum.verdict) < Rank(best->spectrum.verdict) ||
        (Rank(p.spectrum.verdict) == Rank(best->spectrum.verdict) &&
         p.spectrum.spectral_abscissa < best->spectrum.spectral_abscissa))
      best = &p;
  if (!best) {
    cell.spectral_abscissa = cell.frequency_rad_s = cell.essential_abscissa = std::nan("");
    return;
  }
  cell.spectral_abscissa = best->spectrum.spectral_abscissa;
  cell.frequency_rad_s = best->spectrum.roots.empty() ? 0.0 : best->spectrum.roots.front().s.imag();
  cell.essential_abscissa = best->spectrum.essential_abscissa;
  cell.verdict = best->spectrum.verdict;
}

std::string CsvName(const std::string& pointer, const char* fallback) {
  return pointer.find_first_of(",\"\n\r") == std::string::npos ? pointer : fallback;
}

std::string Number(double v) { return std::isnan(v) ? "nan" : Significant(v, 10); }

// Light to dark, by t in [0, 1].
std::string Shade(const int light[3], const int dark[3], double t) {
  t = std::clamp(std::isfinite(t) ? t : 1.0, 0.0, 1.0);
  char b[8];
  std::snprintf(b, sizeof b, "#%02x%02x%02x", static_cast<int>(light[0] + t * (dark[0] - light[0])),
                static_cast<int>(light[1] + t * (dark[1] - light[1])), static_cast<int>(light[2] + t * (dark[2] - light[2])));
  return b;
}

constexpr int kStableLight[3] = {0xc6, 0xdb, 0xef}, kStableDark[3] = {0x08, 0x45, 0x94};
constexpr int kUnstableLight[3] = {0xfc, 0xbb, 0xa1}, kUnstableDark[3] = {0xa5, 0x0f, 0x15};
constexpr const char* kMarginalColour = "#fdd835";
constexpr const char* kNoSteadyStateColour = "#d9d9d9";
constexpr const char* kNotAnalysedColour = "#ffffff";

io::Marker MarkerOf(Regime r) {
  switch (r) {
    case Regime::kNotSimulated: return io::Marker::kNone;
    case Regime::kSmooth: return io::Marker::kOpenCircle;
    case Regime::kStickSlip: return io::Marker::kFilledCircle;
    case Regime::kBitBouncing: return io::Marker::kTriangle;
    case Regime::kFailed: return io::Marker::kCross;
  }
  return io::Marker::kNone;
}

}  // namespace

MapAxis ParseMapAxis(const std::string& text, const nlohmann::json& document, const std::string& option) {
  const auto eq = text.rfind('=');
  if (eq == std::string::npos || eq == 0 || text[0] != '/')
    throw ParameterError(option, "'" + text + "': expected /json/pointer=first:last:count");
  MapAxis axis{text.substr(0, eq), ParseSweepValues(text.substr(eq + 1), option + " " + text.substr(0, eq))};
  for (double v : axis.values)
    if (!std::isfinite(v)) throw ParameterError(option, "'" + text + "': a value is not finite");
  // The pointer must lead to a field the case reads: set the first value and parse (a misspelt optional field is
  // refused by the case's reader as unknown).
  nlohmann::json probe = document;
  try {
    io::SetByPointer(probe, axis.pointer, axis.values.front());
    ParseCase(probe);
  } catch (const InputError& e) {
    throw ParameterError(option, "'" + text + "': " + e.what());  // what() names its path
  }
  return axis;
}

const char* RegimeName(Regime r) {
  switch (r) {
    case Regime::kNotSimulated: return "";
    case Regime::kSmooth: return "smooth";
    case Regime::kStickSlip: return "stick-slip";
    case Regime::kBitBouncing: return "bit bouncing";
    case Regime::kFailed: return "failed";
  }
  return "";
}

Regime ClassifyRun(const nlohmann::json& summary) {
  auto positive = [&](const char* key) {
    return summary.contains(key) && summary.at(key).is_number() && summary.at(key).get<double>() > 0;
  };
  if (positive("off_bottom_fraction")) return Regime::kBitBouncing;
  if (positive("stick_onsets") || positive("stick_fraction")) return Regime::kStickSlip;
  return Regime::kSmooth;
}

const char* CellVerdictName(const StabilityMapCell& cell) {
  return !cell.analysed ? "n/a" : cell.steady_states > 0 ? analysis::VerdictName(cell.verdict) : "none";
}

bool LinearlySteady(const StabilityMapCell& cell) {
  return cell.steady_states > 0 && cell.verdict != Verdict::kUnstable;
}

StabilityMapResult StabilityMap2D(const nlohmann::json& document, const StabilityMapSpec& spec,
                                  const analysis::SpectrumOptions& options) {
  ThrowIfInvalid(options);
  if (spec.jobs < 1) throw ParameterError("jobs", std::to_string(spec.jobs) + " is not >= 1");
  if (spec.x.values.empty() || spec.y.values.empty()) throw ParameterError("map", "no values to map");
  const std::size_t nx = spec.x.values.size(), ny = spec.y.values.size();
  // Every grid point parsed first; the document copies are dropped (a 100 x 100 map would hold 10^4 of them).
  std::vector<Case> cases;
  cases.reserve(nx * ny);
  for (double y : spec.y.values)
    for (double x : spec.x.values) {
      nlohmann::json doc = document;
      io::SetByPointer(doc, spec.x.pointer, x);
      io::SetByPointer(doc, spec.y.pointer, y);
      try {
        cases.push_back(ParseCase(doc));
      } catch (const InputError& e) {
        throw InputError(e.json_path(),
                         e.message() + " (map point " + spec.x.pointer + " = " + Significant(x, 8) + ", " +
                             spec.y.pointer + " = " + Significant(y, 8) + ")",
                         e.mentioned_parameters());
      }
      cases.back().document = nullptr;
      // The work from the first point, before the others are parsed (issue 38: 1000 x 1000 with --simulate ran on).
      if (cases.size() == 1) CheckPointsWork(cases.front(), static_cast<double>(nx) * ny, spec.simulate, "map");
    }
  // A kind without linearization fails here, before the threads start; with simulate, its map holds the regimes only.
  bool linearizable = true;
  try {
    cases.front().model->Linearize();
  } catch (const InputError& e) {
    if (!spec.simulate || e.json_path() != "/model/kind") throw;
    linearizable = false;
  }

  StabilityMapResult result;
  const Stopwatch linear_clock;
  auto blank_cell = [&](std::size_t k) {
    StabilityMapCell cell;
    cell.x = spec.x.values[k % nx];
    cell.y = spec.y.values[k / nx];
    cell.stick_fraction = cell.severity = std::nan("");
    cell.analysed = linearizable;
    if (!linearizable) cell.spectral_abscissa = cell.frequency_rad_s = cell.essential_abscissa = std::nan("");
    return cell;
  };
  if (!linearizable || spec.full_spectrum) {
    result.cells = ParallelMap(cases.size(), spec.jobs, [&](std::size_t k) {
      StabilityMapCell cell = blank_cell(k);
      if (linearizable) {
        const auto points = AnalyzeStability(cases[k], options, ContinuumRoots::kSkipped);
        TakeBestSteadyState(points, cell);
      }
      return cell;
    });
    result.full_spectra = linearizable ? static_cast<int>(nx * ny) : 0;
  } else {
    // Lines of points walked one by one in parallel, each point starting from its neighbour's roots (a point without
    // steady state passes its neighbour's on); the lines' first points along a spine across them. The lines run along
    // the axis on which the rightmost root moves less from the first point (where the roots move far between
    // neighbours, Newton may miss one and the point needs the full spectrum).
    int full_spectra = 0;
    const std::vector<OperatingPointStability> no_neighbour;
    const auto origin =
        AnalyzeStabilityFromNeighbour(cases[0], no_neighbour, options, full_spectra, ContinuumRoots::kSkipped);
    auto rightmost_moves = [&](std::size_t k) {
      const int full_before = full_spectra;
      const auto next =
          AnalyzeStabilityFromNeighbour(cases[k], origin, options, full_spectra, ContinuumRoots::kSkipped);
      if (full_spectra > full_before || next.empty() || origin.empty() || next[0].spectrum.roots.empty() ||
          origin[0].spectrum.roots.empty())
        return std::numeric_limits<double>::infinity();
      return std::abs(next[0].spectrum.roots.front().s - origin[0].spectrum.roots.front().s);
    };
    const bool lines_along_x = nx > 1 && (ny == 1 || rightmost_moves(1) <= rightmost_moves(nx));
    const std::size_t lines = lines_along_x ? ny : nx, length = lines_along_x ? nx : ny;
    auto cell_index = [&](std::size_t line, std::size_t p) { return lines_along_x ? line * nx + p : p * nx + line; };
    std::vector<std::vector<OperatingPointStability>> spine(lines), line_seeds(lines);
    for (std::size_t l = 0; l < lines; ++l) {
      spine[l] = l == 0 ? origin
                        : AnalyzeStabilityFromNeighbour(cases[cell_index(l, 0)], line_seeds[l - 1], options,
                                                        full_spectra, ContinuumRoots::kSkipped);
      line_seeds[l] = !spine[l].empty() || l == 0 ? spine[l] : line_seeds[l - 1];
    }
    const auto walked = ParallelMap(lines, spec.jobs, [&](std::size_t l) {
      std::pair<std::vector<StabilityMapCell>, int> line{{}, 0};
      std::vector<OperatingPointStability> previous = line_seeds[l];
      for (std::size_t p = 0; p < length; ++p) {
        const std::size_t k = cell_index(l, p);
        std::vector<OperatingPointStability> points =
            p == 0 ? spine[l]
                   : AnalyzeStabilityFromNeighbour(cases[k], previous, options, line.second, ContinuumRoots::kSkipped);
        line.first.push_back(blank_cell(k));
        TakeBestSteadyState(points, line.first.back());
        if (!points.empty()) previous = std::move(points);
      }
      return line;
    });
    result.full_spectra = full_spectra;
    result.cells.resize(nx * ny);
    for (std::size_t l = 0; l < lines; ++l) {
      for (std::size_t p = 0; p < length; ++p) result.cells[cell_index(l, p)] = walked[l].first[p];
      result.full_spectra += walked[l].second;
    }
  }
  result.linear_wall_time_s = linear_clock.Seconds();
  if (!spec.simulate) return result;
  const Stopwatch simulation_clock;
  struct Run {
    Regime regime = Regime::kFailed;
    double stick_fraction = std::nan(""), severity = std::nan("");
  };
  const auto runs = ParallelMap(cases.size(), spec.jobs, [&](std::size_t k) {
    Run run;
    auto number = [](const nlohmann::json& summary, const char* key) {
      return summary.contains(key) && summary.at(key).is_number() ? summary.at(key).get<double>() : std::nan("");
    };
    try {
      const nlohmann::json summary = RunCase(cases[k]).summary;
      run.regime = ClassifyRun(summary);
      run.stick_fraction = number(summary, "stick_fraction");
      run.severity = number(summary, "stick_slip_severity");
    } catch (const NumericalError&) {
    }
    return run;
  });
  for (std::size_t k = 0; k < runs.size(); ++k) {
    result.cells[k].regime = runs[k].regime;
    result.cells[k].stick_fraction = runs[k].stick_fraction;
    result.cells[k].severity = runs[k].severity;
  }
  result.simulation_wall_time_s = simulation_clock.Seconds();
  return result;
}

io::HeatMap StabilityHeatMap(const StabilityMapSpec& spec, const StabilityMapResult& result) {
  // Colours: stable blue and unstable red, darker the farther the rightmost root is from the axis (relative to the
  // map's extreme), marginal yellow, no steady state grey.
  double most_stable = 0, most_unstable = 0;
  for (const StabilityMapCell& c : result.cells)
    if (c.steady_states > 0 && std::isfinite(c.spectral_abscissa)) {
      if (c.verdict == Verdict::kStable) most_stable = std::max(most_stable, -c.spectral_abscissa);
      if (c.verdict == Verdict::kUnstable) most_unstable = std::max(most_unstable, c.spectral_abscissa);
    }
  io::HeatMap map;
  map.x_label = io::AxisLabel(io::QuantityOfPointer(spec.x.pointer));
  map.y_label = io::AxisLabel(io::QuantityOfPointer(spec.y.pointer));
  map.x = spec.x.values;
  map.y = spec.y.values;
  bool any_simulated = false;
  for (const StabilityMapCell& c : result.cells) {
    if (!c.analysed) map.colours.push_back(kNotAnalysedColour);
    else if (c.steady_states == 0) map.colours.push_back(kNoSteadyStateColour);
    else if (c.verdict == Verdict::kMarginal) map.colours.push_back(kMarginalColour);
    else if (c.verdict == Verdict::kStable)
      map.colours.push_back(Shade(kStableLight, kStableDark, most_stable > 0 ? -c.spectral_abscissa / most_stable : 1));
    else
      map.colours.push_back(
          Shade(kUnstableLight, kUnstableDark, most_unstable > 0 ? c.spectral_abscissa / most_unstable : 1));
    map.markers.push_back(MarkerOf(c.regime));
    any_simulated |= c.regime != Regime::kNotSimulated;
  }
  map.legend = {{"stable (darker: faster decay)", Shade(kStableLight, kStableDark, 0.6)},
                {"marginal (essential spectrum on Re s = 0)", kMarginalColour},
                {"unstable (darker: faster growth)", Shade(kUnstableLight, kUnstableDark, 0.6)},
                {"no steady rotation", kNoSteadyStateColour}};
  if (!result.cells.empty() && !result.cells.front().analysed)
    map.legend = {{"no linearization for this kind", kNotAnalysedColour}};
  if (any_simulated)
    for (Regime r : {Regime::kSmooth, Regime::kStickSlip, Regime::kBitBouncing, Regime::kFailed})
      map.legend.push_back({std::string("simulated: ") + RegimeName(r), "", MarkerOf(r)});
  return map;
}

namespace {
// P(stick-slip) per cell, white (0) to dark red (1): the simulated share where the map ran, the linear one otherwise.
io::HeatMap ProbabilityHeatMap(const StabilityMapSpec& spec, const StabilityMapResult& result) {
  io::HeatMap map;
  map.x_label = io::AxisLabel(io::QuantityOfPointer(spec.x.pointer));
  map.y_label = io::AxisLabel(io::QuantityOfPointer(spec.y.pointer));
  map.x = spec.x.values;
  map.y = spec.y.values;
  constexpr int kNone[3] = {0xff, 0xff, 0xff}, kCertain[3] = {0xa5, 0x0f, 0x15};
  const std::vector<double>& p = spec.simulate ? result.p_stick_slip : result.p_linearly_unstable;
  for (double v : p) map.colours.push_back(std::isfinite(v) ? Shade(kNone, kCertain, v) : kNoSteadyStateColour);
  for (double v : {0.0, 0.25, 0.5, 0.75, 1.0})
    map.legend.push_back({"P(stick-slip) = " + Fixed(v, 2), Shade(kNone, kCertain, v)});
  map.legend.push_back({"not known (no run or no linearization)", kNoSteadyStateColour});
  return map;
}
}  // namespace

void WriteStabilityMap2D(const nlohmann::json& document, const StabilityMapSpec& spec,
                         const StabilityMapResult& result, const std::string& out_dir) {
  io::OutputDirectory out(out_dir);
  std::ostream& csv = out.Open("stability_map.csv");
  csv << CsvName(spec.x.pointer, "x") << "," << CsvName(spec.y.pointer, "y")
      << ",steady_states,spectral_abscissa_per_s,frequency_rad_s,essential_abscissa_per_s,verdict,regime,"
         "stick_fraction"
      << (result.draws > 0 ? ",p_linearly_unstable,p_stick_slip" : "") << "\n";
  for (std::size_t k = 0; k < result.cells.size(); ++k) {
    const StabilityMapCell& c = result.cells[k];
    csv << Number(c.x) << "," << Number(c.y) << "," << c.steady_states << "," << Number(c.spectral_abscissa) << ","
        << Number(c.frequency_rad_s) << "," << Number(c.essential_abscissa) << ","
        << CellVerdictName(c) << ","
        << RegimeName(c.regime) << ","
        << Number(c.stick_fraction);
    if (result.draws > 0) csv << "," << Number(result.p_linearly_unstable[k]) << "," << Number(result.p_stick_slip[k]);
    csv << "\n";
  }
  out.Open("case.json") << document.dump(2) << "\n";
  if (result.draws > 0) {
    io::HeatMap p = ProbabilityHeatMap(spec, result);
    p.title = document.value("name", std::string("case")) + ": probability of stick-slip over " +
              std::to_string(result.draws) + " parameter draws" +
              (spec.simulate ? " (simulated regimes)" : " (linear verdict: no steady state that is not unstable)");
    io::WriteHeatMapSvg(p, out.Open("p_stick_slip.svg"));
  }

  io::HeatMap map = StabilityHeatMap(spec, result);
  map.title = document.value("name", std::string("case")) + ": linear stability" +
              (spec.simulate ? " and the regime simulated from the case's start" : "");
  io::WriteHeatMapSvg(map, out.Open("stability_map.svg"));

  std::ostream& report = out.Open("report.md");
  int counts[4] = {0, 0, 0, 0}, disagree = 0;  // stable, marginal, unstable, none
  for (const StabilityMapCell& c : result.cells) {
    if (!c.analysed) continue;
    ++counts[c.steady_states == 0 ? 3 : Rank(c.verdict)];
    const bool linear_stable = LinearlySteady(c);
    if ((c.regime == Regime::kStickSlip && linear_stable) || (c.regime == Regime::kSmooth && !linear_stable)) ++disagree;
  }
  report << "# Stability map of " << document.value("name", std::string("case")) << "\n\n"
         << spec.x.pointer << " (" << spec.x.values.size() << " values, " << Significant(spec.x.values.front(), 8)
         << " to " << Significant(spec.x.values.back(), 8) << ") x " << spec.y.pointer << " (" << spec.y.values.size()
         << " values, " << Significant(spec.y.values.front(), 8) << " to " << Significant(spec.y.values.back(), 8)
         << ").\n\n| verdict | points |\n|---|---|\n| stable | " << counts[0] << " |\n| marginal | " << counts[1]
         << " |\n| unstable | " << counts[2] << " |\n| no steady rotation | " << counts[3] << " |\n\n"
         << "Linear analysis: " << Significant(result.linear_wall_time_s, 3) << " s wall time on " << spec.jobs
         << " thread(s); " << result.full_spectra << " steady states by the full spectrum"
         << (spec.full_spectrum ? "" : ", the others' rightmost roots continued from the neighbouring point and "
                                       "certified by the argument principle")
         << ".";
  if (spec.simulate)
    report << " Simulations: " << Significant(result.simulation_wall_time_s, 3) << " s. At " << disagree
           << " points the run from the case's start disagrees with the linear verdict (stick-slip beside a stable or "
              "marginal steady state: two attractors, the start decides; or smooth motion although every steady state "
              "is unstable: an oscillation without sticking).";
  if (result.draws > 0) {
    std::string pointers;
    for (const std::string& q : result.draw_pointers) pointers += (pointers.empty() ? "" : ", ") + q;
    report << "\n\n## Probability of stick-slip over " << result.draws << " parameter draws\n\n"
           << "Every draw (" << pointers << " set to the draw's values) mapped as the case; per point "
           << "`p_linearly_unstable` is the share of draws with no steady state that is stable or marginal"
           << (spec.simulate ? ", `p_stick_slip` the share of the draws' runs that stick and slip (failed runs left "
                               "out); p_stick_slip.svg shows the latter"
                             : "; p_stick_slip.svg shows it (`--simulate` adds the simulated regimes' share)")
           << ". The verdict columns and stability_map.svg are the case's own.";
  }
  report << "\n\nEach point's verdict is that of its best steady state (stable before marginal before unstable). "
            "**Marginal** means that no characteristic root up to |Im s| = im_max lies to the right of the axis but "
            "the essential spectrum of the neutral difference operator lies on the imaginary axis (an inertial or "
            "speed-imposed top and an inertial bit reflect waves without loss at high frequency): root chains "
            "approach Re s = 0, perturbations do not decay at a uniform exponential rate, and whether the chains "
            "approach from the left or the right beyond im_max is not decided. A real string's distributed damping "
            "moves these chains to the left.\n";
  out.Commit();
}

}  // namespace drillwave::cases
