#include "drillwave/cases/case_runner.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>

#include "drillwave/core/error.hpp"
#include "drillwave/io/csv.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/io/svg_plot.hpp"

namespace drillwave::cases {

using io::JsonReader;
using Range = io::Range;

Case ParseCase(const nlohmann::json& document) {
  Case c;
  c.document = document;
  const JsonReader root(document, "");
  c.name = root.String("name", {});
  root.Allow("description");
  root.Allow("references");
  root.Allow("notes");

  const JsonReader sim = root.Object("simulation");
  c.settings.duration_s = sim.Number("duration_s", Range::Positive());
  c.settings.output_interval_s = sim.Number("output_interval_s", Range::NonNegative(), 1e-3);
  c.settings.integrator.abs_tol = sim.Number("abs_tol", Range::Between(1e-14, 1e-2), 1e-8);
  c.settings.integrator.rel_tol = sim.Number("rel_tol", Range::Between(1e-14, 1e-2), 1e-8);
  c.settings.integrator.max_step = sim.Number("max_step_s", Range::Positive(), c.settings.integrator.max_step);
  sim.Finish();
  if (c.settings.output_interval_s > 0 && c.settings.duration_s / c.settings.output_interval_s > 5e7)
    throw InputError(sim.PathOf("output_interval_s"), "more than 5e7 samples; choose a larger interval");

  c.settings.window_begin_s = 0;
  c.settings.window_end_s = c.settings.duration_s;
  if (root.Has("statistics")) {
    const JsonReader stats = root.Object("statistics");
    if (stats.Has("window_s")) {
      const std::vector<double> w = stats.NumberArray("window_s", Range::NonNegative());
      if (w.size() != 2 || !(w[0] < w[1]) || w[1] > c.settings.duration_s)
        throw InputError(stats.PathOf("window_s"),
                         "expected [begin, end] with 0 <= begin < end <= simulation.duration_s");
      c.settings.window_begin_s = w[0];
      c.settings.window_end_s = w[1];
    }
    stats.Finish();
  }

  const JsonReader model = root.Object("model");
  c.kind = model.String("kind", {});
  const ModelKind& kind = FindKind(c.kind, model.PathOf("kind"));
  c.model = kind.Prepare(model);

  if (root.Has("sensors")) c.sensors = ReadSensors(root.Object("sensors"));

  if (root.Has("expect")) {
    c.expect = root.Raw("expect");
    if (!c.expect.is_object()) throw InputError("/expect", "expected an object of summary keys");
    for (const auto& item : c.expect.items()) {
      const std::string path = "/expect/" + item.key();
      const auto& e = item.value();
      if (e.is_null()) continue;
      if (!e.is_object()) throw InputError(path, "expected {\"min\", \"max\"}, {\"value\", \"rel_tol\"} or null");
      for (const auto& f : e.items())
        if (f.key() != "min" && f.key() != "max" && f.key() != "value" && f.key() != "rel_tol" && f.key() != "abs_tol")
          throw InputError(path + "/" + f.key(), "unknown field; expected one of: min, max, value, rel_tol, abs_tol");
    }
  }
  root.Finish();
  return c;
}

CaseRun RunCase(const Case& c) {
  const auto start = std::chrono::steady_clock::now();
  CaseRun run{c.model->Run(c.settings), nlohmann::json::object()};
  ApplySensors(c.sensors, run.result);
  run.summary = run.result.summary;
  run.summary["case"] = c.name;
  run.summary["kind"] = c.kind;
  run.summary["window_s"] = {c.settings.window_begin_s, c.settings.window_end_s};
  run.summary["simulated_time_s"] = c.settings.duration_s;
  run.summary["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

std::vector<ExpectationCheck> CheckExpectations(const nlohmann::json& expect, const nlohmann::json& summary) {
  std::vector<ExpectationCheck> checks;
  for (const auto& item : expect.items()) {
    const std::string& key = item.key();
    const auto& e = item.value();
    std::ostringstream detail;
    if (!summary.contains(key)) {
      checks.push_back({key, false, key + " is not in the summary"});
      continue;
    }
    const auto& actual = summary.at(key);
    if (e.is_null()) {
      checks.push_back({key, actual.is_null(), key + " = " + actual.dump() + " (expected null)"});
      continue;
    }
    if (!actual.is_number()) {
      checks.push_back({key, false, key + " = " + actual.dump() + " (expected a number)"});
      continue;
    }
    const double v = actual.get<double>();
    bool ok = true;
    detail << key << " = " << v;
    if (e.contains("min")) ok &= v >= e.at("min").get<double>();
    if (e.contains("max")) ok &= v <= e.at("max").get<double>();
    if (e.contains("min") || e.contains("max"))
      detail << " in [" << (e.contains("min") ? e.at("min").dump() : "-inf") << ", "
             << (e.contains("max") ? e.at("max").dump() : "inf") << "]";
    if (e.contains("value")) {
      const double target = e.at("value").get<double>();
      const double tol = e.value("abs_tol", 0.0) + e.value("rel_tol", 0.0) * std::abs(target);
      ok &= std::abs(v - target) <= tol;
      detail << " vs " << target << " ± " << tol;
    }
    checks.push_back({key, ok, detail.str()});
  }
  return checks;
}

void WriteCaseOutputs(const Case& c, const CaseRun& run, const std::string& out_dir) {
  io::OutputDirectory out(out_dir);
  const RunResult& r = run.result;

  std::vector<std::string> header{"time_s"};
  std::vector<std::vector<double>> columns{r.time_s};
  for (const Channel& ch : r.channels) {
    header.push_back(ch.name);
    columns.push_back(ch.values);
  }
  io::WriteCsv(out.Open("trajectory.csv"), header, columns);
  out.Open("summary.json") << run.summary.dump(2) << "\n";
  out.Open("case.json") << c.document.dump(2) << "\n";

  io::Figure figure;
  figure.title = c.name + " (" + c.kind + ")";
  figure.x_label = "time [s]";
  for (const auto& panel_channels : r.plot_panels) {
    io::Panel panel;
    for (const std::string& name : panel_channels) {
      panel.y_label += (panel.y_label.empty() ? "" : ", ") + name;
      panel.series.push_back({name, r.time_s, r.channel(name).values});
    }
    figure.panels.push_back(panel);
  }
  io::WriteSvg(figure, out.Open("plot.svg"));

  std::ostream& report = out.Open("report.md");
  report << "# " << c.name << "\n\n";
  if (c.document.contains("description")) report << c.document.at("description").get<std::string>() << "\n\n";
  report << "Model kind `" << c.kind << "`, simulated " << c.settings.duration_s << " s in "
         << run.summary.value("wall_time_s", 0.0) << " s wall time; statistics over [" << c.settings.window_begin_s
         << ", " << c.settings.window_end_s << "] s.\n\n| quantity | value |\n|---|---|\n";
  for (const auto& item : run.summary.items())
    if (item.value().is_primitive()) report << "| " << item.key() << " | " << item.value().dump() << " |\n";
  if (!c.expect.empty()) {
    report << "\n## Expectations\n\n";
    for (const ExpectationCheck& check : CheckExpectations(c.expect, run.summary))
      report << "- " << (check.passed ? "PASS " : "FAIL ") << check.detail << "\n";
  }
  report << "\nFiles: `trajectory.csv` (sampled channels), `summary.json`, `plot.svg`, `case.json` (the case as run).\n";
  out.Commit();
}

}  // namespace drillwave::cases
