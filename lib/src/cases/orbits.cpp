#include "drillwave/cases/orbits.hpp"

#include <cmath>
#include <limits>
#include <ostream>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/sweep.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/stopwatch.hpp"
#include "drillwave/io/json_reader.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/io/axis_label.hpp"
#include "drillwave/io/svg_plot.hpp"

namespace drillwave::cases {

namespace {
constexpr int kDefaultGrid = 201;
}

analysis::FieldFamily CaseFieldFamily(const nlohmann::json& document, const std::string& pointer) {
  return [document, pointer](double p) {
    nlohmann::json doc = document;
    io::SetByPointer(doc, pointer, p);
    return ParseCase(doc).model->OrbitField();
  };
}

OrbitsSpec ParseContinueOption(const std::string& text, const nlohmann::json& document) {
  const auto eq = text.rfind('=');
  if (eq == std::string::npos || eq == 0 || text[0] != '/')
    throw ParameterError("continue", "'" + text + "': expected /json/pointer=first:last or /json/pointer=first:last:count");
  std::string range = text.substr(eq + 1);
  if (std::count(range.begin(), range.end(), ':') == 1) range += ":" + std::to_string(kDefaultGrid);
  OrbitsSpec spec{text.substr(0, eq), ParseSweepValues(range, "continue " + text.substr(0, eq))};
  if (spec.grid.size() < 2 || !(spec.grid.front() < spec.grid.back()))
    throw ParameterError("continue", "'" + text + "': expected first < last and a count of at least 2");
  for (double v : {spec.grid.front(), spec.grid.back()}) {
    nlohmann::json probe = document;
    try {
      io::SetByPointer(probe, spec.pointer, v);
      ParseCase(probe).model->OrbitField();
    } catch (const InputError& e) {
      throw ParameterError("continue", "'" + text + "': " + e.what());  // what() names its path
    }
  }
  nlohmann::json first = document;
  io::SetByPointer(first, spec.pointer, spec.grid.front());
  CheckPointsWork(ParseCase(first), static_cast<double>(spec.grid.size()), false, "continue");
  return spec;
}

OrbitsResult ContinueOrbits(const nlohmann::json& document, const OrbitsSpec& spec, const OrbitsProgress& progress) {
  const Stopwatch clock;
  const analysis::FieldFamily family = CaseFieldFamily(document, spec.pointer);
  OrbitsResult result;
  const double lo = spec.grid.front(), hi = spec.grid.back(), width = hi - lo;
  result.equilibria = analysis::ContinueEquilibria(family, spec.grid, 1e-10 * std::max(1.0, width));
  for (const analysis::HopfPoint& h : result.equilibria.hopf) {
    // A branch that already ended at this Hopf point has it.
    bool reached = false;
    for (const auto& b : result.branches)
      reached |= b.end.rfind("reached the equilibrium", 0) == 0 && !b.points.empty() &&
                 std::abs(b.points.back().p - h.p) < 1e-2 * width;
    if (reached) continue;
    analysis::ContinuationOptions o;
    o.p_min = lo, o.p_max = hi;
    o.p_scale = width / 20;  // the parameter range weighs like 20 state units in the arclength
    o.initial_step = 0.05, o.max_step = 0.5, o.min_step = 1e-6;
    o.hopf_amplitude = 1e-3 * std::max(1.0, h.x.norm());
    o.end_amplitude = 2e-4 * std::max(1.0, h.x.norm());
    o.max_points = 600;
    const int index = static_cast<int>(result.branches.size());
    if (progress) o.progress = [&](int points, double p, double period) { progress(index, points, p, period); };
    result.starts.push_back(h);
    result.branches.push_back(analysis::ContinueFromHopf(family, h, o));
  }
  result.wall_time_s = clock.Seconds();
  return result;
}

std::vector<std::pair<double, double>> CoexistenceRanges(const OrbitsResult& result) {
  auto stable_orbit_at = [&](double p) {
    for (const auto& br : result.branches)
      for (std::size_t i = 1; i < br.points.size(); ++i) {
        const auto &a = br.points[i - 1], &b = br.points[i];
        if (a.orbit.stable && b.orbit.stable && (a.p - p) * (b.p - p) <= 0) return true;
      }
    return false;
  };
  std::vector<std::pair<double, double>> ranges;
  bool open = false;
  for (const auto& e : result.equilibria.points) {
    const bool both = e.stable && stable_orbit_at(e.p);
    if (both && open) ranges.back().second = e.p;
    if (both && !open) ranges.push_back({e.p, e.p});
    open = both;
  }
  return ranges;
}

void WriteOrbitsOutputs(const nlohmann::json& document, const OrbitsSpec& spec, const OrbitsResult& result,
                        const std::string& out_dir) {
  io::OutputDirectory out(out_dir);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto last = [](const Eigen::VectorXd& x) { return x[x.size() - 1]; };

  std::ostream& csv = out.Open("orbits.csv");
  csv << "type,branch,parameter,period_s,amplitude,amplitude_min,amplitude_max,max_abs_floquet_multiplier,stable,"
         "stick_slip\n";
  auto row = [&](const std::string& type, int branch, double p, double period, double a_min, double a_max,
                 double mu, bool stable, bool sticks) {
    csv << type << "," << branch << "," << Significant(p, 12) << "," << Significant(period, 12) << ","
        << Significant(a_max - a_min, 12) << "," << Significant(a_min, 12) << "," << Significant(a_max, 12) << ","
        << Significant(mu, 10) << "," << (stable ? 1 : 0) << "," << (sticks ? 1 : 0) << "\n";
  };
  for (const auto& e : result.equilibria.points)
    row("equilibrium", 0, e.p, nan, last(e.x), last(e.x), nan, e.stable, false);
  for (const auto& h : result.equilibria.hopf) row("hopf", 0, h.p, 2 * kPi / h.omega, last(h.x), last(h.x), 1, false, false);
  for (std::size_t b = 0; b < result.branches.size(); ++b) {
    for (const auto& pt : result.branches[b].points)
      row("periodic", static_cast<int>(b), pt.p, pt.orbit.period, pt.amplitude_min, pt.amplitude_max,
          pt.orbit.max_nontrivial, pt.orbit.stable, pt.orbit.switches > 0);
    for (const auto& f : result.branches[b].folds)
      row("fold", static_cast<int>(b), f.p, f.period, f.amplitude_min, f.amplitude_max, std::abs(f.critical_multiplier),
          false, false);
  }
  out.Open("case.json") << document.dump(2) << "\n";

  // Bifurcation diagram: the last state (e.g. the lower disc's speed) at the equilibria and its extremes on the
  // orbits, solid lines per stability; the period below.
  io::Figure figure;
  figure.title = document.value("name", std::string("case")) + ": bifurcation diagram over " + spec.pointer;
  figure.x_label = io::AxisLabel(io::QuantityOfPointer(spec.pointer));
  io::Panel state{"last state (bit / lower-disc speed) [rad/s]", {}}, periods{"period [s]", {}};
  for (bool want : {true, false}) {
    io::Series s{std::string(want ? "stable" : "unstable") + " equilibria", {}, {}};
    for (const auto& e : result.equilibria.points) {
      s.x.push_back(e.p);
      s.y.push_back(e.stable == want ? last(e.x) : nan);
    }
    state.series.push_back(s);
  }
  for (std::size_t b = 0; b < result.branches.size(); ++b)
    for (bool want : {true, false}) {
      const std::string tag = std::string(want ? "stable" : "unstable") + " orbits" +
                              (result.branches.size() > 1 ? " (branch " + std::to_string(b) + ")" : "");
      io::Series mx{tag + ": max", {}, {}}, mn{tag + ": min", {}, {}}, per{tag, {}, {}};
      for (const auto& pt : result.branches[b].points) {
        const bool use = pt.orbit.stable == want;
        for (io::Series* s : {&mx, &mn, &per}) s->x.push_back(pt.p);
        mx.y.push_back(use ? pt.amplitude_max : nan);
        mn.y.push_back(use ? pt.amplitude_min : nan);
        per.y.push_back(use ? pt.orbit.period : nan);
      }
      state.series.push_back(mx);
      state.series.push_back(mn);
      periods.series.push_back(per);
    }
  figure.panels = {state, periods};
  io::WriteSvg(figure, out.Open("orbits.svg"));

  std::ostream& report = out.Open("report.md");
  report << "# Periodic orbits of " << document.value("name", std::string("case")) << " over " << spec.pointer
         << "\n\nSteady states on " << spec.grid.size() << " values in [" << Significant(spec.grid.front(), 8) << ", "
         << Significant(spec.grid.back(), 8) << "]; periodic orbits by single shooting (Newton on the start point "
         << "and the period, Poincaré phase condition) and pseudo-arclength continuation from each Hopf point. Floquet "
         << "multipliers from the monodromy matrix: variational equations, with the saltation matrix at every stick "
         << "and slip event. Wall time " << Significant(result.wall_time_s, 3) << " s.\n\n## Hopf points\n\n";
  report << "| " << spec.pointer << " | frequency [rad/s] | period 2π/ω [s] | last state [rad/s] |\n|---|---|---|---|\n";
  for (const auto& h : result.equilibria.hopf)
    report << "| " << Significant(h.p, 10) << " | " << Significant(h.omega, 8) << " | "
           << Significant(2 * kPi / h.omega, 8) << " | " << Significant(last(h.x), 8) << " |\n";
  const auto coexistence = CoexistenceRanges(result);
  if (!coexistence.empty()) {
    report << "\n## Coexisting attractors\n\nA stable steady state and a stable periodic orbit at the same value (which one "
              "a run reaches depends on its start; an unstable orbit between them separates the basins):\n";
    for (const auto& [a, b] : coexistence)
      report << "- " << spec.pointer << " in [" << Significant(a, 8) << ", " << Significant(b, 8)
             << "] (grid values of stable steady states inside a stable stretch of a branch)\n";
  }
  for (std::size_t b = 0; b < result.branches.size(); ++b) {
    const auto& br = result.branches[b];
    report << "\n## Branch " << b << " (from the Hopf point at " << Significant(result.starts[b].p, 10) << ")\n\n"
           << br.points.size() << " orbits; ended: " << br.end << ".\n\n";
    for (const auto& f : br.folds)
      report << "- fold at " << spec.pointer << " = " << Significant(f.p, 10) << ": period " << Significant(f.period, 8)
             << " s, last state from " << Significant(f.amplitude_min, 8) << " to " << Significant(f.amplitude_max, 8)
             << ", critical multiplier " << Significant(f.critical_multiplier, 6) << "\n";
    // Changes of stability and of sticking along the branch, between neighbouring points.
    for (std::size_t i = 1; i < br.points.size(); ++i) {
      const auto &a = br.points[i - 1], &c = br.points[i];
      if (a.orbit.stable != c.orbit.stable)
        report << "- " << (c.orbit.stable ? "becomes stable" : "loses stability") << " between "
               << Significant(a.p, 8) << " and " << Significant(c.p, 8) << "\n";
      if ((a.orbit.switches > 0) != (c.orbit.switches > 0))
        report << "- " << (c.orbit.switches > 0 ? "starts" : "stops") << " to stick (grazing) between "
               << Significant(a.p, 8) << " and " << Significant(c.p, 8) << "\n";
    }
  }
  out.Commit();
}

}  // namespace drillwave::cases
