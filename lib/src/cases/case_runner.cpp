#include "drillwave/cases/case_runner.hpp"

#include <atomic>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "drillwave/core/error.hpp"
#include "drillwave/core/stopwatch.hpp"
#include "drillwave/io/csv.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/io/axis_label.hpp"
#include "drillwave/io/svg_plot.hpp"

namespace drillwave::cases {

using io::JsonReader;
using Range = io::Range;

namespace {

std::atomic<double> max_samples{1e7};

// The work a case asks for, estimated before it runs: output samples (duration / output interval) and the fewest
// integration steps (duration / max_step_s). Each is refused above MaxSamples(), with how to raise the limit.
void CheckWork(const RunSettings& s, const JsonReader& sim) {
  const double limit = MaxSamples();
  auto refuse = [&](const std::string& key, double count, const std::string& what) {
    throw InputError(sim.PathOf(key), ReadableNumber(s.duration_s) + " s simulated " + what + " is " +
                                          ReadableNumber(count) + ", above the limit of " + ReadableNumber(limit) +
                                          "; choose a larger " + key + ", a shorter duration_s, or raise max_samples",
                                      {"max_samples"});
  };
  if (s.output_interval_s > 0 && s.duration_s / s.output_interval_s > limit)
    refuse("output_interval_s", s.duration_s / s.output_interval_s,
           "every " + ReadableNumber(s.output_interval_s) + " s: the number of output samples");
  if (std::isfinite(s.integrator.max_step) && s.duration_s / s.integrator.max_step > limit)
    refuse("max_step_s", s.duration_s / s.integrator.max_step,
           "in steps of at most " + ReadableNumber(s.integrator.max_step) + " s: the number of integration steps");
}

// An expect entry: null, {"min", "max"} (either or both, min <= max) or {"value", "rel_tol", "abs_tol"}.
void CheckExpectation(const nlohmann::json& e, const std::string& path) {
  if (e.is_null()) return;
  if (!e.is_object())
    throw InputError(path, "expected {\"min\": a, \"max\": b}, {\"value\": v, \"rel_tol\": r} or null, got " +
                               ReadableText(e.dump()));
  const JsonReader r(e, path);
  const double inf = std::numeric_limits<double>::infinity();
  const double lo = r.Number("min", Range::Any(), -inf), hi = r.Number("max", Range::Any(), inf);
  if (lo > hi)
    throw InputError(path, "the range [min, max] = [" + ReadableNumber(lo) + ", " + ReadableNumber(hi) +
                               "] is reversed; expected min <= max");
  const bool has_value = r.Has("value");
  if (has_value) r.Number("value", Range::Any());
  for (const char* tol : {"rel_tol", "abs_tol"}) {
    if (!r.Has(tol)) continue;
    r.Number(tol, Range::NonNegative());
    if (!has_value) throw InputError(r.PathOf(tol), "a tolerance needs a \"value\" to apply to");
  }
  r.Finish();
  if (!has_value && !r.Has("min") && !r.Has("max"))
    throw InputError(path, "expected min and/or max, or value with rel_tol/abs_tol; got an empty object");
}

// A run whose outputs are not finite has failed numerically, however far it got: the first such sample, with the
// channel that went bad and every channel's value there.
void CheckFinite(const RunResult& r) {
  for (std::size_t i = 0; i < r.time_s.size(); ++i) {
    std::string bad = std::isfinite(r.time_s[i]) ? "" : "time_s";
    for (const Channel& ch : r.channels)
      if (bad.empty() && i < ch.values.size() && !std::isfinite(ch.values[i])) bad = ch.name;
    if (bad.empty()) continue;
    std::vector<double> state;
    std::string names;
    for (const Channel& ch : r.channels) {
      state.push_back(i < ch.values.size() ? ch.values[i] : std::nan(""));
      names += (names.empty() ? "" : ", ") + ch.name;
    }
    const std::string where = i == 0 ? "at the first sample" : "after t = " + ReadableNumber(r.time_s[i - 1]) + " s";
    throw NumericalError("output " + bad + " is not finite (" + where + "; channels " + names + ")", r.time_s[i],
                         state);
  }
}

// Summaries hold measured numbers or null (undefined, e.g. a period with fewer than two onsets), never NaN, inf or
// a sentinel such as -1e300 left by an empty window.
void NullifySentinels(nlohmann::json& value) {
  if (value.is_structured()) {
    for (auto& item : value) NullifySentinels(item);
  } else if (value.is_number_float()) {
    const double x = value.get<double>();
    if (!std::isfinite(x) || std::abs(x) >= 1e300) value = nullptr;
  }
}

}  // namespace

void SetMaxSamples(double limit) {
  if (!(limit >= 1) || !std::isfinite(limit))
    throw ParameterError("max_samples", "expected a finite number >= 1, got " + ReadableNumber(limit));
  max_samples = limit;
}

double MaxSamples() { return max_samples; }

Case ParseCase(const nlohmann::json& document) {
  Case c;
  c.document = document;
  const JsonReader root(document, "");
  c.name = root.String("name", {});
  root.String("description", {}, "");  // free text, but the report writes it as text: a string or nothing
  root.Allow("references");
  root.Allow("notes");

  const JsonReader sim = root.Object("simulation");
  c.settings.duration_s = sim.Number("duration_s", Range::Positive());
  c.settings.output_interval_s = sim.Number("output_interval_s", Range::NonNegative(), 1e-3);
  c.settings.integrator.abs_tol = sim.Number("abs_tol", Range::Between(1e-14, 1e-2), 1e-8);
  c.settings.integrator.rel_tol = sim.Number("rel_tol", Range::Between(1e-14, 1e-2), 1e-8);
  c.settings.integrator.max_step = sim.Number("max_step_s", Range::Positive(), c.settings.integrator.max_step);
  sim.Finish();
  CheckWork(c.settings, sim);
  // A run that would need more steps than samples allowed is refused before it starts; one that makes more than
  // ten times as many derivative evaluations anyway (a step size collapsed by stiffness) stops with a NumericalError.
  c.settings.integrator.max_planned_steps = MaxSamples();
  c.settings.integrator.max_evaluations = static_cast<long>(std::min(10 * MaxSamples(), 9e18));

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
    if (!c.expect.is_object())
      throw InputError("/expect", "expected an object of summary keys, got " + ReadableText(c.expect.dump()));
    for (const auto& item : c.expect.items()) CheckExpectation(item.value(), "/expect/" + item.key());
  }
  root.Finish();
  return c;
}

CaseRun RunCase(const Case& c) {
  const Stopwatch clock;
  CaseRun run{c.model->Run(c.settings), nlohmann::json::object()};
  ApplySensors(c.sensors, run.result);
  CheckFinite(run.result);
  run.summary = run.result.summary;
  NullifySentinels(run.summary);
  run.summary["case"] = c.name;
  run.summary["kind"] = c.kind;
  run.summary["window_s"] = {c.settings.window_begin_s, c.settings.window_end_s};
  run.summary["simulated_time_s"] = c.settings.duration_s;
  run.summary["wall_time_s"] = clock.Seconds();
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
    io::Panel panel{io::AxisLabelOfChannels(panel_channels), {}};
    for (const std::string& name : panel_channels) panel.series.push_back({name, r.time_s, r.channel(name).values});
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
