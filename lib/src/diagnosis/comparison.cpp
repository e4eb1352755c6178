#include "drillwave/diagnosis/comparison.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/validity.hpp"
#include "drillwave/io/axis_label.hpp"
#include "drillwave/io/json_number.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/io/svg_plot.hpp"

namespace drillwave::diagnosis {
namespace {

// Linear interpolation of (t, y) at the times `at` (held constant outside).
std::vector<double> Resample(const std::vector<double>& t, const std::vector<double>& y, const std::vector<double>& at) {
  std::vector<double> out(at.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < at.size(); ++i) {
    while (k + 1 < t.size() && t[k + 1] < at[i]) ++k;
    if (at[i] <= t.front()) out[i] = y.front();
    else if (k + 1 >= t.size()) out[i] = y.back();
    else out[i] = y[k] + (y[k + 1] - y[k]) * (at[i] - t[k]) / (t[k + 1] - t[k]);
  }
  return out;
}

// The features read from the two inspections, in the order Compare lists them before sorting.
const std::pair<const char*, double Inspection::*> kInspectionFeatures[] = {
    {"bit_oscillation_period_s", &Inspection::bit_oscillation_period_s},
    {"stick_slip_period_s", &Inspection::stick_slip_period_s},
    {"stick_fraction", &Inspection::stick_fraction},
    {"bit_speed_mean", &Inspection::bit_speed_mean},
    {"bit_speed_max", &Inspection::bit_speed_max},
    {"top_speed_mean", &Inspection::top_speed_mean},
    {"top_speed_fluctuation", &Inspection::top_speed_fluctuation}};

}  // namespace

std::vector<std::string> FeatureNames(const std::vector<ChannelMap>& maps) {
  std::vector<std::string> names;
  for (const auto& feature : kInspectionFeatures) names.push_back(feature.first);
  for (const ChannelMap& m : maps) {
    names.push_back(m.recording + " mean");
    names.push_back(m.recording + " std");
  }
  return names;
}

void CheckWindow(const Recording& rec, double model_begin_s, double model_end_s, double window_begin_s,
                 double window_end_s) {
  const double lo = std::max({window_begin_s, rec.time_s.front(), model_begin_s});
  const double hi = std::min({window_end_s, rec.time_s.back(), model_end_s});
  std::size_t samples = 0;
  for (double t : rec.time_s) samples += t >= lo && t <= hi ? 1 : 0;
  const bool whole = !(std::abs(window_begin_s) < 1e300) && !(std::abs(window_end_s) < 1e300);  // no --window
  if (samples < 10)
    throw ParameterError("window", "fewer than 10 recorded samples in [" + Fixed(lo, 3) + ", " + Fixed(hi, 3) +
                                     "] s, where " +
                                     (whole ? std::string()
                                            : "the window (" + ReadableNumber(window_begin_s) + " to " +
                                                  ReadableNumber(window_end_s) + " s), ") +
                                     "the recording (" +
                                     ReadableNumber(rec.time_s.front()) + " to " + ReadableNumber(rec.time_s.back()) +
                                     " s) and the model (" + ReadableNumber(model_begin_s) + " to " +
                                     ReadableNumber(model_end_s) + " s) overlap");
}

std::vector<cases::Channel> ProbeChannels(const cases::Case& c) {
  cases::RunSettings settings = c.settings;
  settings.duration_s = std::min(c.settings.duration_s, std::max(4 * c.settings.output_interval_s, 1e-3));
  settings.window_begin_s = 0;
  settings.window_end_s = settings.duration_s;
  return c.model->Run(settings).channels;
}

std::vector<ChannelMap> ResolveChannelMaps(const std::vector<std::string>& texts, const Recording& recording,
                                           const std::vector<cases::Channel>& model) {
  std::vector<ChannelMap> maps;
  auto list = [](const std::vector<std::string>& names) {
    std::string text;
    for (std::size_t j = 0; j < names.size() && j < 20; ++j) text += (text.empty() ? "" : ", ") + names[j];
    return names.size() > 20 ? text + ", ..." : text;
  };
  std::vector<std::string> model_names;
  for (const auto& ch : model) model_names.push_back(ch.name);
  for (const std::string& m : texts) {
    const ChannelMap map = ParseChannelMap(m);
    if (!recording.Has(map.recording))
      throw ParameterError("map", "'" + ReadableText(m) + "': " + recording.source +
                                               " has no channel " + ReadableText(map.recording) +
                                               " (it has: " + list(recording.names) + ")");
    if (std::find(model_names.begin(), model_names.end(), map.model) == model_names.end())
      throw ParameterError("map", "'" + ReadableText(m) + "': the model has no channel " +
                                               ReadableText(map.model) + " (it has: " + list(model_names) +
                                               ")");
    maps.push_back(map);
  }
  // Then the same quantity in kilo-units: a recording's x_kNm / x_kN against the model's x_Nm / x_N.
  auto kilo = [](const std::string& name) -> std::pair<std::string, double> {
    for (const auto& [from, to] : {std::pair<std::string, std::string>{"_kNm", "_Nm"}, {"_kN", "_N"}})
      if (name.size() > from.size() && name.compare(name.size() - from.size(), from.size(), from) == 0)
        return {name.substr(0, name.size() - from.size()) + to, 1e-3};
    return {"", 0};
  };
  for (const std::string& name : recording.names) {
    const bool mapped = std::any_of(maps.begin(), maps.end(), [&](const ChannelMap& m) { return m.recording == name; });
    if (mapped) continue;
    const auto [base, scale] = kilo(name);
    for (const auto& ch : model)
      if (ch.name == name) maps.push_back({name, name, 1.0});
      else if (!base.empty() && ch.name == base) maps.push_back({name, base, scale});
  }
  return maps;
}

ChannelMap ParseChannelMap(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw ParameterError("map", "'" + ReadableText(text) + "': expected recording_channel=model_channel[*scale]");
  ChannelMap m{text.substr(0, eq), text.substr(eq + 1), 1.0};
  const auto star = m.model.find('*');
  if (star != std::string::npos) {
    const std::string factor = m.model.substr(star + 1);
    m.model = m.model.substr(0, star);
    char* end = nullptr;
    m.scale = std::strtod(factor.c_str(), &end);
    if (factor.empty() || end != factor.c_str() + factor.size() || !std::isfinite(m.scale) || m.scale == 0)
      throw ParameterError("map", "'" + ReadableText(text) + "': the scale must be a finite non-zero number");
  }
  return m;
}

Comparison Compare(const Recording& rec, const cases::RunResult& model, const std::vector<ChannelMap>& maps,
                   double window_begin_s, double window_end_s, const InspectOptions& options) {
  ThrowIfInvalid(options);
  if (maps.empty()) throw ParameterError("map", "no channels to compare");
  Comparison c;
  CheckWindow(rec, model.time_s.front(), model.time_s.back(), window_begin_s, window_end_s);
  c.window_begin_s = std::max({window_begin_s, rec.time_s.front(), model.time_s.front()});
  c.window_end_s = std::min({window_end_s, rec.time_s.back(), model.time_s.back()});
  for (const std::string& needed : {options.bit_speed, options.top_speed})
    if (std::none_of(maps.begin(), maps.end(), [&](const ChannelMap& m) { return m.recording == needed; }))
      throw ParameterError("map", "the comparison needs the recording's " + needed + " mapped to a model channel");

  // Both sides on the recording's time grid within the window.
  Recording r, m;
  r.source = rec.source;
  m.source = "model";
  for (std::size_t i = 0; i < rec.time_s.size(); ++i)
    if (rec.time_s[i] >= c.window_begin_s && rec.time_s[i] <= c.window_end_s) r.time_s.push_back(rec.time_s[i]);
  r.sample_interval_s = m.sample_interval_s = rec.sample_interval_s;
  m.time_s = r.time_s;
  for (const ChannelMap& map : maps) {
    const std::vector<double>& recorded = rec.Channel(map.recording);
    r.names.push_back(map.recording);
    r.channels.push_back(Resample(rec.time_s, recorded, r.time_s));  // the same samples, cut to the window
    std::vector<double> simulated;
    try {
      simulated = model.channel(map.model).values;
    } catch (const std::out_of_range&) {
      std::string list;
      for (const auto& ch : model.channels) list += (list.empty() ? "" : ", ") + ch.name;
      throw ParameterError("map", "the model has no channel " + map.model + " (it has: " + list + ")");
    }
    for (double& v : simulated) v *= map.scale;
    m.names.push_back(map.recording);
    m.channels.push_back(Resample(model.time_s, simulated, m.time_s));
  }
  c.recording = InspectRecording(r, options);
  InspectOptions clean = options;
  clean.mask_artefacts = false;  // a simulation has no sensor artefacts: its sharp slips are physics
  c.model = InspectRecording(m, clean);

  for (std::size_t j = 0; j < maps.size(); ++j) {
    const auto& a = c.recording.cleaned[j];
    const auto& b = c.model.cleaned[j];
    double sum2 = 0, sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i) sum2 += (b[i] - a[i]) * (b[i] - a[i]), sum += b[i] - a[i];
    c.residuals.push_back({maps[j].recording, std::sqrt(sum2 / a.size()), sum / a.size(), Std(a)});
  }

  auto add = [&](const std::string& name, double rv, double mv) {
    const double rel = std::isfinite(rv) && rv != 0 && std::isfinite(mv) ? (mv - rv) / std::abs(rv) : std::nan("");
    c.features.push_back({name, rv, mv, rel});
  };
  const Inspection &ri = c.recording, &mi = c.model;
  for (const auto& [name, member] : kInspectionFeatures) add(name, ri.*member, mi.*member);
  for (std::size_t j = 0; j < maps.size(); ++j) {
    add(maps[j].recording + " mean", Mean(ri.cleaned[j]), Mean(mi.cleaned[j]));
    add(maps[j].recording + " std", Std(ri.cleaned[j]), Std(mi.cleaned[j]));
  }
  std::stable_sort(c.features.begin(), c.features.end(), [](const FeatureDifference& x, const FeatureDifference& y) {
    const double a = std::isfinite(x.relative) ? std::abs(x.relative) : -1, b = std::isfinite(y.relative) ? std::abs(y.relative) : -1;
    return a > b;
  });

  // Findings: the largest differences, and what each usually points to.
  auto& f = c.findings;
  for (const FeatureDifference& d : c.features)
    if (std::isfinite(d.relative) && std::abs(d.relative) > 0.1 && f.size() < 6)
      f.push_back(d.feature + ": model " + Fixed(d.model, 3) + " against recording " + Fixed(d.recording, 3) + " (" +
                  (d.relative > 0 ? "+" : "") + Fixed(100 * d.relative, 0) + " %).");
  const double fluct_ratio = ri.top_speed_fluctuation / std::max(mi.top_speed_fluctuation, 1e-12);
  if (ri.top_drive_soft && fluct_ratio > 3)
    f.push_back("the recording's top speed fluctuates " + Fixed(fluct_ratio, 1) + "x more than the model's: the model's "
                "top drive is stiffer than the real one; model its inertia and speed controller (or motor) and fit "
                "them.");
  for (const FeatureDifference& d : c.features)
    if (d.feature == "bit_oscillation_period_s" && std::isfinite(d.relative) && std::abs(d.relative) > 0.2)
      f.push_back("the bit's oscillation period is off by " + Fixed(100 * d.relative, 0) +
                  " %: the string's torsional stiffness and the inertias (bit, BHA, top drive) set it; check them "
                  "first.");
    else if (d.feature == "stick_fraction" && std::isfinite(d.relative) && std::abs(d.relative) > 0.3)
      f.push_back("the time spent stuck differs by " + Fixed(100 * d.relative, 0) +
                  " %: the bit friction's static and kinetic levels (velocity weakening) are the usual suspects.");
  if (f.empty()) f.push_back("no feature differs by more than 10 %.");
  return c;
}

nlohmann::json ComparisonToJson(const Comparison& c) {
  nlohmann::json residuals = nlohmann::json::array(), features = nlohmann::json::array();
  for (const auto& r : c.residuals)
    residuals.push_back({{"channel", r.channel}, {"rms", r.rms}, {"bias", r.bias}, {"recording_std", r.recording_std}});
  for (const auto& d : c.features)
    features.push_back({{"feature", d.feature},
                        {"recording", io::FiniteOrNull(d.recording)},
                        {"model", io::FiniteOrNull(d.model)},
                        {"relative_difference", io::FiniteOrNull(d.relative)}});
  return {{"window_s", {c.window_begin_s, c.window_end_s}},
          {"residuals", residuals},
          {"features", features},
          {"findings", c.findings},
          {"recording_inspection", InspectionToJson(c.recording)},
          {"model_inspection", InspectionToJson(c.model)}};
}

io::Figure ComparisonFigure(const Recording& rec, const std::vector<ChannelMap>& maps, const Comparison& c) {
  io::Figure figure;
  figure.title = "model against " + rec.source;
  figure.x_label = "time [s]";
  std::vector<double> t;
  for (double ti : rec.time_s)
    if (ti >= c.window_begin_s && ti <= c.window_end_s) t.push_back(ti);
  for (std::size_t j = 0; j < maps.size(); ++j) {
    io::Panel panel{io::AxisLabelOfChannels({maps[j].recording}), {}};
    panel.series.push_back({maps[j].recording + " (recording, artefacts masked)", t, c.recording.cleaned[j]});
    panel.series.push_back({maps[j].model + " (model)", t, c.model.cleaned[j]});
    figure.panels.push_back(panel);
  }
  return figure;
}

void WriteComparison(const Recording& rec, const cases::RunResult&, const std::vector<ChannelMap>& maps,
                     const Comparison& c, const std::string& out_dir) {
  io::OutputDirectory out(out_dir);
  out.Open("comparison.json") << ComparisonToJson(c).dump(2) << "\n";
  io::WriteSvg(ComparisonFigure(rec, maps, c), out.Open("plot.svg"));
  std::ostream& report = out.Open("report.md");
  report << "# Model against " << rec.source << "\n\nWindow [" << c.window_begin_s << ", " << c.window_end_s
         << "] s.\n\n## Findings\n\n";
  for (const std::string& f : c.findings) report << "- " << f << "\n";
  report << "\n## Features (largest relative difference first)\n\n| feature | recording | model | difference |\n"
         << "|---|---|---|---|\n";
  for (const auto& d : c.features)
    report << "| " << d.feature << " | " << Fixed(d.recording, 4) << " | " << Fixed(d.model, 4) << " | "
           << (std::isfinite(d.relative) ? Fixed(100 * d.relative, 1) + " %" : "-") << " |\n";
  report << "\n## Point-by-point residuals\n\n| channel | rms | bias | recording std |\n|---|---|---|---|\n";
  for (const auto& r : c.residuals)
    report << "| " << r.channel << " | " << Fixed(r.rms, 4) << " | " << Fixed(r.bias, 4) << " | "
           << Fixed(r.recording_std, 4) << " |\n";
  report << "\nIn stick-slip the point-by-point residual is dominated by phase drift; the features locate a mismatch."
            "\n";
  out.Commit();
}

}  // namespace drillwave::diagnosis
