#include "drillwave/cases/edge_tracking.hpp"

#include <algorithm>
#include <cmath>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/sweep.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/io/csv.hpp"
#include "drillwave/io/json_reader.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/io/axis_label.hpp"
#include "drillwave/io/svg_plot.hpp"

namespace drillwave::cases {

namespace {

struct Outcome {
  bool sticks;
  RunResult result;
};

Outcome RunAt(const nlohmann::json& document, const std::string& pointer, double value) {
  nlohmann::json doc = document;
  io::SetByPointer(doc, pointer, value);
  CaseRun run = RunCase(ParseCase(doc));
  const bool sticks = run.summary.value("stick_onsets", 0) > 0;
  return {sticks, std::move(run.result)};
}

}  // namespace

EdgeResult TrackEdge(const nlohmann::json& document, const EdgeSpec& spec,
                     const std::function<void(int runs, double decays, double sticks)>& progress) {
  EdgeResult r;
  r.decays = spec.decays, r.sticks = spec.sticks;
  Outcome low = RunAt(document, spec.pointer, spec.decays), high = RunAt(document, spec.pointer, spec.sticks);
  r.runs = 2;
  if (low.sticks || !high.sticks)
    throw InputError(spec.pointer, "the values " + Significant(spec.decays, 10) + " and " +
                                       Significant(spec.sticks, 10) + " do not straddle the boundary: the first " +
                                       (low.sticks ? "sticks" : "does not stick") + ", the second " +
                                       (high.sticks ? "sticks" : "does not stick"));
  r.edge = std::move(low.result);
  if (progress) progress(r.runs, r.decays, r.sticks);
  while (std::abs(r.sticks - r.decays) > spec.tolerance * std::max(1.0, std::abs(r.decays))) {
    const double mid = 0.5 * (r.decays + r.sticks);
    if (mid == r.decays || mid == r.sticks) break;
    Outcome o = RunAt(document, spec.pointer, mid);
    ++r.runs;
    if (o.sticks) {
      r.sticks = mid;
    } else {
      r.decays = mid;
      r.edge = std::move(o.result);
    }
    if (progress) progress(r.runs, r.decays, r.sticks);
  }
  return r;
}

EdgeSpec ParseEdgeOption(const std::string& text, const nlohmann::json& document) {
  const auto eq = text.rfind('=');
  const auto colon = eq == std::string::npos ? std::string::npos : text.find(':', eq);
  if (eq == std::string::npos || eq == 0 || colon == std::string::npos)
    throw ParameterError("edge", "expected POINTER=decays:sticks (a value whose run decays, one whose run sticks), got '" +
                                   text + "'");
  EdgeSpec spec;
  spec.pointer = text.substr(0, eq);
  spec.decays = ParseNumber(text.substr(eq + 1, colon - eq - 1), "edge");
  spec.sticks = ParseNumber(text.substr(colon + 1), "edge");
  if (spec.decays == spec.sticks) throw ParameterError("edge", "the two values must differ");
  nlohmann::json probe = document;
  io::SetByPointer(probe, spec.pointer, spec.decays);  // names the pointer if the case has nothing there
  return spec;
}

void WriteEdgeOutputs(const nlohmann::json& document, const EdgeSpec& spec, const EdgeResult& edge,
                      const std::string& channel, double after_s, const ShadowedCycle& cycle,
                      const std::string& out_dir) {
  io::OutputDirectory out(out_dir);
  nlohmann::json j = {{"pointer", spec.pointer},     {"decays", edge.decays},   {"sticks", edge.sticks},
                      {"runs", edge.runs},           {"channel", channel},      {"after_s", after_s},
                      {"cycle_found", cycle.found}};
  if (cycle.found)
    j["saddle_cycle"] = {{"period_s", cycle.period_s}, {"peak_to_peak", cycle.amplitude}, {"time_s", cycle.time_s},
                         {"relative_change_per_cycle", cycle.relative_change}};
  out.Open("edge.json") << j.dump(2) << "\n";
  out.Open("case.json") << document.dump(2) << "\n";
  std::vector<std::string> header{"time_s"};
  std::vector<std::vector<double>> columns{edge.edge.time_s};
  for (const auto& c : edge.edge.channels) header.push_back(c.name), columns.push_back(c.values);
  io::WriteCsv(out.Open("edge_run.csv"), header, columns);
  io::Figure figure;
  figure.title = "run at the edge: " + spec.pointer + " = " + Significant(edge.decays, 12);
  figure.x_label = "time [s]";
  const std::vector<double>& values = edge.edge.channel(channel).values;
  io::Panel panel{io::AxisLabelOfChannels({channel}), {{channel, edge.edge.time_s, values}}};
  if (cycle.found) {  // the shadowed cycle, drawn again over its own stretch
    io::Series marked{"saddle cycle (period " + Significant(cycle.period_s, 5) + " s)", {}, {}};
    for (std::size_t i = 0; i < edge.edge.time_s.size(); ++i) {
      const double t = edge.edge.time_s[i];
      if (t >= cycle.time_s && t <= cycle.time_s + cycle.period_s) marked.x.push_back(t), marked.y.push_back(values[i]);
    }
    panel.series.push_back(std::move(marked));
  }
  figure.panels.push_back(std::move(panel));
  io::WriteSvg(figure, out.Open("edge.svg"));
  std::ostream& report = out.Open("report.md");
  report << "# Edge tracking on " << spec.pointer << "\n\n"
         << "Bisection between a run that decays to the steady state and one that sticks: after " << edge.runs
         << " runs the boundary lies in [" << Significant(edge.decays, 12) << ", " << Significant(edge.sticks, 12)
         << "]. The run on the decaying side shadows the saddle cycle that separates the two basins before it leaves "
            "it.\n\n";
  if (cycle.found)
    report << "Saddle cycle in `" << channel << "` (the most nearly steady cycle after " << Significant(after_s, 6)
           << " s): period " << Significant(cycle.period_s, 6) << " s, peak-to-peak " << Significant(cycle.amplitude, 6)
           << ", from t = " << Significant(cycle.time_s, 6) << " s, amplitude changing by "
           << Significant(100 * cycle.relative_change, 3) << " % per cycle.\n";
  else
    report << "No cycle of `" << channel << "` after " << Significant(after_s, 6)
           << " s: the run at the edge did not oscillate there (perturb later, or run longer).\n";
  out.Commit();
}

ShadowedCycle FindShadowedCycle(const std::vector<double>& t, const std::vector<double>& y, double t_from) {
  // Local maxima and the least value between consecutive maxima.
  std::vector<std::size_t> peaks;
  for (std::size_t i = 1; i + 1 < t.size(); ++i)
    if (t[i] >= t_from && y[i] > y[i - 1] && y[i] >= y[i + 1]) peaks.push_back(i);
  std::vector<double> amplitude;
  for (std::size_t k = 0; k + 1 < peaks.size(); ++k) {
    const double low = *std::min_element(y.begin() + peaks[k], y.begin() + peaks[k + 1]);
    amplitude.push_back(std::max(y[peaks[k]], y[peaks[k + 1]]) - low);
  }
  // Peak times refined by the parabola through the sample and its neighbours.
  auto peak_time = [&](std::size_t i) {
    const double a = y[i - 1], b = y[i], c = y[i + 1], den = a - 2 * b + c;
    const double shift = den < 0 ? 0.5 * (a - c) / den : 0.0;
    return t[i] + shift * 0.5 * (t[i + 1] - t[i - 1]);
  };
  ShadowedCycle best;
  // The decayed tail (an oscillation at round-off level) is steady too: only cycles of at least 1 % of the largest.
  const double largest = amplitude.empty() ? 0.0 : *std::max_element(amplitude.begin(), amplitude.end());
  for (std::size_t k = 1; k + 1 < amplitude.size(); ++k) {
    if (!(amplitude[k] > 0.01 * largest)) continue;
    const double change = std::abs(amplitude[k + 1] - amplitude[k - 1]) / (2 * amplitude[k]);
    if (!best.found || change < best.relative_change) {
      best.found = true;
      best.relative_change = change;
      best.amplitude = amplitude[k];
      best.time_s = peak_time(peaks[k]);
      best.period_s = peak_time(peaks[k + 1]) - best.time_s;
    }
  }
  return best;
}

}  // namespace drillwave::cases
