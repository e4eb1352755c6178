#include "drillwave/cases/stability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "drillwave/analysis/kelvin_voigt_continuum.hpp"
#include "drillwave/analysis/rightmost_root.hpp"
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

namespace drillwave::cases {
namespace {

double SteadySpeed(const nlohmann::json& steady) {
  for (const char* key : {"bit_speed_rad_s", "speed_rad_s"})
    if (steady.contains(key)) return steady.at(key).get<double>();
  return std::nan("");
}

// JSON has no infinities: -inf (no essential spectrum, no roots) is written as null.

nlohmann::json RootsToJson(const analysis::Spectrum& sp, int max_roots) {
  nlohmann::json roots = nlohmann::json::array();
  for (std::size_t k = 0; k < sp.roots.size() && static_cast<int>(k) < max_roots; ++k)
    roots.push_back({sp.roots[k].s.real(), sp.roots[k].s.imag(), sp.roots[k].residual});
  return roots;
}

nlohmann::json ContinuumToJson(const analysis::ContinuumSpectrum& c, int max_roots) {
  return {{"note",
           "the string as the continuum its pieces discretize (exact Kelvin-Voigt sections); the verdict "
           "above is the discretized model's, which the simulation integrates"},
          {"stable", c.spectrum.stable},
          {"verdict", analysis::VerdictName(c.spectrum.verdict)},
          {"spectral_abscissa", io::FiniteOrNull(c.spectrum.spectral_abscissa)},
          {"essential_abscissa", io::FiniteOrNull(c.spectrum.essential_abscissa)},
          {"certified", c.certified},
          {"box_re_left_re_right_im_max", {c.re_left, c.re_right, c.im_max}},
          {"roots_re_im_residual", RootsToJson(c.spectrum, max_roots)}};
}

// The continuum's verdict beside the discretized one, in the report.
void ReportContinuum(const analysis::ContinuumSpectrum& c, std::ostream& report) {
  const analysis::Spectrum& sp = c.spectrum;
  report << "The continuum string (exact Kelvin-Voigt sections, not the pieces the simulation integrates): "
         << analysis::VerdictName(sp.verdict) << ", rightmost root " << Significant(sp.spectral_abscissa, 8);
  if (!sp.roots.empty()) report << " + " << Significant(sp.roots.front().s.imag(), 8) << "i";
  report << " 1/s; its roots accumulate at Re s = -1/eta = " << Significant(sp.essential_abscissa, 8) << " 1/s; "
         << sp.roots.size() << " roots in " << Significant(c.re_left, 6) << " <= Re s <= " << Significant(c.re_right, 6)
         << ", 0 <= Im s <= " << Significant(c.im_max, 6)
         << (c.certified ? " (the argument principle counts no other)" : " (not certified: roots may be missing)")
         << ". Where the two differ, the pieces are too coarse for those modes.\n\n| Re s [1/s] | Im s [rad/s] |\n"
            "|---|---|\n";
  for (std::size_t j = 0; j < sp.roots.size() && j < 12; ++j)
    report << "| " << Significant(sp.roots[j].s.real(), 8) << " | " << Significant(sp.roots[j].s.imag(), 8) << " |\n";
  report << "\n";
}

}  // namespace

std::vector<OperatingPointStability> AnalyzeStability(const Case& c, const analysis::SpectrumOptions& options,
                                                      ContinuumRoots continuum) {
  ThrowIfInvalid(options);
  int full_spectra = 0;
  return AnalyzeStabilityFromNeighbour(c, {}, options, full_spectra, continuum);
}

std::vector<OperatingPointStability> AnalyzeStabilityFromNeighbour(const Case& c,
                                                                   const std::vector<OperatingPointStability>& neighbour,
                                                                   const analysis::SpectrumOptions& options,
                                                                   int& full_spectra, ContinuumRoots continuum) {
  constexpr std::size_t kSeedRoots = 24;  // the neighbour's rightmost roots Newton starts from
  std::vector<OperatingPointStability> out;
  for (LinearizedOperatingPoint& p : c.model->Linearize()) {
    const std::size_t b = out.size();
    analysis::Spectrum sp;
    try {
      bool certified = false;
      if (b < neighbour.size() && neighbour[b].point.system.dimension() == p.system.dimension()) {
        std::vector<std::complex<double>> seeds;
        for (const auto& r : neighbour[b].spectrum.roots)
          if (seeds.size() < kSeedRoots) seeds.push_back(r.s);
        const auto& near = neighbour[b];
        const std::optional<double> essential =
            p.system.SameDifferenceOperator(near.point.system) ? std::optional(near.spectrum.essential_abscissa)
                                                                : std::nullopt;
        analysis::SeededSpectrum seeded = analysis::SpectrumFromSeeds(p.system, seeds, options, essential);
        certified = seeded.certified;
        if (certified) sp = std::move(seeded.spectrum);
      }
      if (!certified) {
        sp = analysis::ComputeSpectrum(p.system, options);
        ++full_spectra;
      }
    } catch (const std::invalid_argument& e) {  // parameters so extreme that the linearization is out of range
      throw InputError("/model", std::string("the linearization cannot be analysed: ") + e.what());
    }
    std::optional<analysis::ContinuumSpectrum> exact;
    if (p.continuum && continuum == ContinuumRoots::kComputed)
      exact = analysis::ComputeContinuumSpectrum(*p.continuum, options);
    out.push_back({std::move(p), std::move(sp), std::move(exact)});
  }
  return out;
}

nlohmann::json StabilityToJson(const std::vector<OperatingPointStability>& result, int max_roots) {
  nlohmann::json points = nlohmann::json::array();
  for (const OperatingPointStability& r : result) {
    points.push_back({{"steady_state", r.point.steady_state},
                      {"state", r.point.state_names},
                      {"stable", r.spectrum.stable},
                      {"verdict", analysis::VerdictName(r.spectrum.verdict)},
                      {"spectral_abscissa", io::FiniteOrNull(r.spectrum.spectral_abscissa)},
                      {"essential_abscissa", io::FiniteOrNull(r.spectrum.essential_abscissa)},
                      {"roots_re_im_residual", RootsToJson(r.spectrum, max_roots)}});
    if (r.continuum) points.back()["continuum_kelvin_voigt"] = ContinuumToJson(*r.continuum, max_roots);
  }
  return {{"operating_points", points}};
}

void WriteStabilityOutputs(const Case& c, const std::vector<OperatingPointStability>& result,
                           const std::string& out_dir, const RunFromStart* from_start) {
  io::OutputDirectory out(out_dir);
  nlohmann::json stability = StabilityToJson(result);
  if (from_start) {
    stability["run_from_start"] = {{"ran", from_start->ran}, {"note", from_start->note}};
    if (from_start->ran) {
      stability["run_from_start"]["sticks"] = from_start->sticks;
      stability["run_from_start"]["stick_fraction"] = from_start->stick_fraction;
    }
  }
  out.Open("stability.json") << stability.dump(2) << "\n";
  out.Open("case.json") << c.document.dump(2) << "\n";
  std::vector<double> point, re, im, residual;
  for (std::size_t k = 0; k < result.size(); ++k)
    for (const auto& r : result[k].spectrum.roots) {
      point.push_back(static_cast<double>(k));
      re.push_back(r.s.real());
      im.push_back(r.s.imag());
      residual.push_back(r.residual);
    }
  io::WriteCsv(out.Open("roots.csv"), {"operating_point", "re_per_s", "im_rad_per_s", "residual"},
               {point, re, im, residual});

  std::ostream& report = out.Open("report.md");
  report << "# Linearized stability of " << c.name << "\n\n";
  if (result.empty()) report << "No steady sliding state at the inputs' final values (e.g. held by static friction, "
                                "or below the break-away level): nothing to linearize.\n";
  for (std::size_t k = 0; k < result.size(); ++k) {
    const auto& r = result[k];
    report << "## Operating point " << k << ": " << analysis::VerdictName(r.spectrum.verdict) << "\n\n"
           << "Steady state: `" << r.point.steady_state.dump() << "`\n\n"
           << "Rightmost root real part " << Significant(r.spectrum.spectral_abscissa, 8)
           << " 1/s; essential spectrum of the difference operator at Re s = " << Significant(r.spectrum.essential_abscissa, 8)
           << " 1/s (-inf: retarded or delay-free). " << r.spectrum.roots.size() << " roots found (upper half plane)."
           << "\n\n| Re s [1/s] | Im s [rad/s] | residual |\n|---|---|---|\n";
    for (std::size_t j = 0; j < r.spectrum.roots.size() && j < 12; ++j)
      report << "| " << Significant(r.spectrum.roots[j].s.real(), 8) << " | " << Significant(r.spectrum.roots[j].s.imag(), 8) << " | "
             << Significant(r.spectrum.roots[j].residual, 8) << " |\n";
    report << "\n";
    if (r.continuum) ReportContinuum(*r.continuum, report);
  }
  report << "A steady state is stable when every characteristic root and the essential spectrum lie in the left "
            "half plane. It is marginal when no root found (up to |Im s| = im_max) lies to the right but the essential "
            "spectrum lies on the imaginary axis: an inertial or speed-imposed top and an inertial bit reflect waves "
            "without loss at high frequency, so root chains approach Re s = 0 and no uniform decay rate exists (a real "
            "string's distributed damping moves them left). Linear stability says nothing of large perturbations: stick-slip can coexist with a stable "
            "steady state (simulate the case from rest to see which motion it reaches).\n";
  if (from_start) {
    report << "\n## The run from the case's start\n\n";
    if (from_start->ran)
      report << "The case run as `drillwave run` runs it " << (from_start->sticks ? "sticks and slips" : "does not stick")
             << " (stick fraction " << Significant(from_start->stick_fraction, 4) << ")"
             << (from_start->note.empty() ? ", as the linear verdict leads one to expect.\n"
                                          : ": " + from_start->note + ".\n");
    else
      report << from_start->note << ".\n";
  }
  out.Commit();
}

std::vector<StabilityMapRow> StabilityMap(const nlohmann::json& document, const SweepSpec& spec,
                                          const analysis::SpectrumOptions& options) {
  ThrowIfInvalid(options);
  if (spec.values.empty()) throw ParameterError("values", "no values to sweep");
  if (spec.jobs < 1) throw ParameterError("jobs", std::to_string(spec.jobs) + " is not >= 1");
  std::vector<Case> cases;
  for (double v : spec.values) {
    if (cases.size() == 1) CheckPointsWork(cases.front(), static_cast<double>(spec.values.size()), false, "values");
    nlohmann::json doc = document;
    io::SetByPointer(doc, spec.pointer, v);
    try {
      cases.push_back(ParseCase(doc));
    } catch (const InputError& e) {
      throw InputError(e.json_path(), e.message() + " (sweep value " + spec.pointer + " = " + Significant(v, 8) + ")",
                       e.mentioned_parameters());
    }
  }
  cases.front().model->Linearize();  // a kind without linearization fails here, before the threads start
  const auto per_value = ParallelMap(cases.size(), spec.jobs, [&](std::size_t i) {
    std::vector<StabilityMapRow> rows;
    const auto analysis = AnalyzeStability(cases[i], options, ContinuumRoots::kSkipped);
    for (std::size_t b = 0; b < analysis.size(); ++b) {
      const auto& sp = analysis[b].spectrum;
      rows.push_back({spec.values[i], static_cast<int>(b), SteadySpeed(analysis[b].point.steady_state),
                      sp.spectral_abscissa, sp.roots.empty() ? 0.0 : sp.roots.front().s.imag(), sp.essential_abscissa,
                      sp.stable, sp.verdict});
    }
    return rows;
  });
  std::vector<StabilityMapRow> rows;
  for (auto& v : per_value) rows.insert(rows.end(), v.begin(), v.end());
  return rows;
}

void WriteStabilityMap(const nlohmann::json& document, const SweepSpec& spec,
                       const std::vector<StabilityMapRow>& rows, const std::string& out_dir) {
  io::OutputDirectory out(out_dir);
  std::vector<double> value, branch, speed, abscissa, frequency, essential, stable, verdict;
  for (const auto& r : rows) {
    value.push_back(r.value);
    branch.push_back(r.branch);
    speed.push_back(r.speed_rad_s);
    abscissa.push_back(r.spectral_abscissa);
    frequency.push_back(r.frequency_rad_s);
    essential.push_back(r.essential_abscissa);
    stable.push_back(r.stable ? 1 : 0);
    verdict.push_back(r.verdict == analysis::Spectrum::Verdict::kStable     ? 1
                      : r.verdict == analysis::Spectrum::Verdict::kMarginal ? 0
                                                                            : -1);
  }
  const std::string param = spec.pointer.find_first_of(",\"\n") == std::string::npos ? spec.pointer : "parameter";
  io::WriteCsv(out.Open("stability_map.csv"),
               {param, "branch", "steady_speed_rad_s", "spectral_abscissa_per_s", "frequency_rad_s",
                "essential_abscissa_per_s", "stable", "verdict"},
               {value, branch, speed, abscissa, frequency, essential, stable, verdict});
  out.Open("case.json") << document.dump(2) << "\n";

  // One series per branch and stability, with breaks (NaN) where the branch is absent or of the other kind.
  int branches = 0;
  for (const auto& r : rows) branches = std::max(branches, r.branch + 1);
  io::Figure figure;
  figure.title = document.value("name", std::string("case")) + ": linearized stability against " + spec.pointer;
  figure.x_label = io::AxisLabel(io::QuantityOfPointer(spec.pointer));
  io::Panel speeds{"steady speed [rad/s]", {}}, real_parts{"rightmost Re s [1/s]", {}};
  for (int b = 0; b < branches; ++b)
    for (bool want_stable : {true, false}) {
      io::Series s{std::string(want_stable ? "stable" : "unstable") + (branches > 1 ? " (branch " + std::to_string(b) + ")" : ""), {}, {}};
      io::Series a = s;
      for (double v : spec.values) {
        const auto it = std::find_if(rows.begin(), rows.end(),
                                     [&](const StabilityMapRow& r) { return r.value == v && r.branch == b; });
        const bool use = it != rows.end() && it->stable == want_stable;
        s.x.push_back(v), a.x.push_back(v);
        s.y.push_back(use ? it->speed_rad_s : std::nan(""));
        a.y.push_back(it != rows.end() && std::isfinite(it->spectral_abscissa) && use ? it->spectral_abscissa : std::nan(""));
      }
      speeds.series.push_back(s);
      real_parts.series.push_back(a);
    }
  figure.panels = {speeds, real_parts};
  io::WriteSvg(figure, out.Open("stability_map.svg"));

  std::ostream& report = out.Open("report.md");
  report << "# Stability map of " << document.value("name", std::string("case")) << " over " << spec.pointer
         << "\n\n| " << spec.pointer << " | branch | steady speed [rad/s] | rightmost Re s [1/s] | Im s [rad/s] | "
         << "essential [1/s] | verdict |\n|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows)
    report << "| " << Significant(r.value, 8) << " | " << r.branch << " | " << Significant(r.speed_rad_s, 8) << " | "
           << Significant(r.spectral_abscissa, 8) << " | " << Significant(r.frequency_rad_s, 8) << " | "
           << Significant(r.essential_abscissa, 8) << " | " << analysis::VerdictName(r.verdict) << " |\n";
  // Crossings of the rightmost real part through zero along branch 0, located by linear interpolation.
  report << "\nStability changes along branch 0 (linear interpolation between neighbouring values):\n";
  const StabilityMapRow* prev = nullptr;
  for (const auto& r : rows) {
    if (r.branch != 0) continue;
    if (prev && prev->stable != r.stable && std::isfinite(prev->spectral_abscissa) &&
        std::isfinite(r.spectral_abscissa)) {
      const double x = prev->value + (r.value - prev->value) * prev->spectral_abscissa /
                                         (prev->spectral_abscissa - r.spectral_abscissa);
      report << "- near " << spec.pointer << " = " << Significant(x, 8) << " (" << (r.stable ? "becomes stable" : "loses stability")
             << ", frequency " << Significant(r.frequency_rad_s, 8) << " rad/s)\n";
    }
    prev = &r;
  }
  out.Commit();
}

std::string LinearVerdictNote(const std::vector<OperatingPointStability>& points, bool sticks, const std::string& run) {
  // A marginal steady state (essential spectrum on the axis, no root to the right) counts as not unstable here.
  auto not_unstable = [](const OperatingPointStability& p) {
    return p.spectrum.verdict != analysis::Spectrum::Verdict::kUnstable;
  };
  for (const auto& p : points) {
    if (!sticks || !not_unstable(p)) continue;
    const auto& state = p.point.steady_state;  // wave kinds name the bit's speed, lumped kinds the common one
    const double speed = state.contains("bit_speed_rad_s") ? state.value("bit_speed_rad_s", 0.0)
                                                           : state.value("speed_rad_s", 0.0);
    return std::string("a ") + analysis::VerdictName(p.spectrum.verdict) + " steady state (bit at " + Fixed(speed, 4) +
           " rad/s, rightmost root Re s = " + Fixed(p.spectrum.spectral_abscissa, 4) + " 1/s) coexists with the " +
           "stick-slip " + run + " found: which motion appears depends on the start";
  }
  if (!sticks && !points.empty() && std::none_of(points.begin(), points.end(), not_unstable))
    return "every steady state is linearly unstable (rightmost root Re s = " +
           Fixed(points.front().spectrum.spectral_abscissa, 4) + " 1/s), yet the bit did not stick in " + run +
           ": it ends on an oscillation without sticking";
  return "";
}

RunFromStart CompareWithRunFromStart(const Case& c, const std::vector<OperatingPointStability>& points) {
  RunFromStart out;
  nlohmann::json summary;
  try {
    summary = RunCase(c).summary;
  } catch (const NumericalError& e) {
    out.note = std::string("the run from the case's start failed: ") + e.what();
    return out;
  }
  if (!summary.contains("stick_onsets") || !summary.at("stick_onsets").is_number()) {
    out.note = "this kind reports no stick statistics: no run compared";
    return out;
  }
  out.ran = true;
  out.sticks = summary.at("stick_onsets").get<int>() > 0;
  if (summary.contains("stick_fraction") && summary.at("stick_fraction").is_number())
    out.stick_fraction = summary.at("stick_fraction").get<double>();
  out.note = LinearVerdictNote(points, out.sticks, "the run from the case's start");
  return out;
}

void AddLinearVerdict(const Case& c, nlohmann::json& summary) {
  // Beyond 64 states (the coupled model's 20 sub-sections: 87) `stability` answers: the full spectrum costs seconds,
  // more than the run, and so can the difference operator's abscissa the counts need first (several sections). The
  // counts cost a banded LU of det Delta per step along their contours: beyond 2e5 multiply-adds per LU (a
  // Kelvin-Voigt string in 20 sub-sections, whose dashpots make Delta dense, needs 1.4e5; in 30, 4.6e5) as well.
  constexpr int kLinearVerdictStates = 64;
  constexpr double kCountLuCost = 2e5;
  if (!summary.contains("stick_onsets") || !summary.at("stick_onsets").is_number()) return;
  const bool sticks = summary.at("stick_onsets").get<int>() > 0;
  std::vector<OperatingPointStability> points;
  try {
    const std::vector<LinearizedOperatingPoint> linearized = c.model->Linearize();
    for (const LinearizedOperatingPoint& p : linearized) {
      p.system.Validate();
      const analysis::CharacteristicDeterminant det(p.system);
      const double lower = det.lower_bandwidth(), upper = det.upper_bandwidth();
      if (p.system.dimension() > kLinearVerdictStates ||
          p.system.dimension() * (lower + 1) * (lower + upper + 1) > kCountLuCost)
        return;
    }
    // The note speaks only where a run that sticks meets a steady state that is not unstable, or a run that does not
    // stick meets only unstable ones. Counting the roots right of the axis (milliseconds) tells most runs that there
    // is nothing to say, before the full spectra its numbers need (seconds with many sub-sections, issue 33).
    std::vector<std::optional<bool>> unstable;
    for (const LinearizedOperatingPoint& p : linearized)
      unstable.push_back(analysis::UnstableByArgumentPrinciple(p.system, {}));
    const auto known = [](bool value) { return [value](const std::optional<bool>& u) { return u == value; }; };
    if (sticks && std::all_of(unstable.begin(), unstable.end(), known(true))) return;
    if (!sticks && std::any_of(unstable.begin(), unstable.end(), known(false))) return;
    // The note's numbers are a verdict and a spectral abscissa: from counts of the same kind (tens of milliseconds
    // where the full spectrum of 20 sub-sections costs seconds); the full spectra where a count cannot be made.
    for (const LinearizedOperatingPoint& p : linearized) {
      std::optional<analysis::Spectrum> sp = analysis::AbscissaByArgumentPrinciple(p.system, {}, 1e-5);
      if (!sp) break;
      points.push_back({p, std::move(*sp)});
    }
    if (points.size() != linearized.size())
      points = AnalyzeStability(c, {}, ContinuumRoots::kSkipped);  // the note sets the run against the pieces' roots
  } catch (const InputError&) {
    return;  // this kind or configuration has no linearization
  } catch (const std::invalid_argument&) {
    return;  // a linearization out of range (AnalyzeStability says so as an InputError)
  }
  const std::string note = LinearVerdictNote(points, sticks, "this run");
  if (!note.empty()) summary["linear_verdict"] = note;
}

}  // namespace drillwave::cases
