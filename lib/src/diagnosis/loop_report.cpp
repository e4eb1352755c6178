#include "drillwave/diagnosis/loop_report.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "drillwave/core/format.hpp"
#include "drillwave/diagnosis/recording.hpp"
#include "drillwave/io/csv.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/io/axis_label.hpp"
#include "drillwave/io/svg_plot.hpp"
#include "channel_figure.hpp"

namespace drillwave::diagnosis {
namespace {

std::string Html(const std::string& text) { return io::EscapeXml(text); }

std::string Cell(double v, int digits = 4) { return std::isfinite(v) ? Significant(v, digits) : "-"; }

// The samples the loop masked as artefacts in each of the channels `names`: the loop keeps only their counts, and it
// masks each channel alone and deterministically (MaskArtefacts), so masking them again finds the same samples.
std::vector<std::vector<char>> MaskedSamples(const Recording& rec, const std::vector<std::string>& names) {
  Recording chosen{rec.source, rec.time_s, {}, {}, rec.sample_interval_s};
  for (const std::string& name : names) chosen.names.push_back(name), chosen.channels.push_back(rec.Channel(name));
  return MaskArtefacts(chosen).flagged;
}

// Channel j: the recording over [from_s, to_s] (its masked samples apart), the baseline and the fitted model.
std::vector<io::Series> ChannelSeries(const DiagnosisLoop& loop, const Recording& rec, std::size_t j,
                                      const std::vector<char>& masked, double from_s, double to_s) {
  const Recording& base = loop.baseline_model;
  std::vector<io::Series> series =
      figure_internal::RecordedSeries("recording", rec.time_s, rec.Channel(base.names[j]), masked, from_s, to_s);
  series.push_back({"baseline", base.time_s, base.channels[j]});
  if (loop.kept >= 0) series.push_back({"fitted", loop.fitted_model.time_s, loop.fitted_model.channels[j]});
  return series;
}

}  // namespace

io::Figure DiagnosisFigure(const DiagnosisLoop& loop, const Recording& rec) {
  io::Figure figure;
  figure.title = "recording, baseline and fitted model (fit window, then held out)";
  figure.x_label = "recording time [s]";
  figure.spans = {{"fit window", loop.recording_fit.begin_s, loop.recording_fit.end_s},
                  {"held out", loop.recording_held_out.begin_s, loop.recording_held_out.end_s}};
  const Recording& base = loop.baseline_model;
  if (base.names.empty() || base.time_s.empty()) return figure;
  const std::vector<std::vector<char>> masked = MaskedSamples(rec, base.names);
  for (std::size_t j = 0; j < base.names.size(); ++j)
    figure.panels.push_back({io::AxisLabelOfChannels({base.names[j]}),
                             ChannelSeries(loop, rec, j, masked[j], base.time_s.front(), base.time_s.back())});
  // Stick-slip cycles are too short to compare over the whole span: the bit speed's last few of the held-out window
  // again, on a time axis of their own, where the model's cycles are judged.
  const auto bit = std::find(base.names.begin(), base.names.end(), loop.bit_speed);
  if (bit == base.names.end()) return figure;
  const std::size_t j = static_cast<std::size_t>(bit - base.names.begin());
  const figure_internal::Zoom zoom =
      figure_internal::LastCycles(loop.recording_held_out.Value("period_s"), loop.recording_held_out.begin_s,
                                  loop.recording_held_out.end_s, figure.x_label, "held-out window");
  figure.panels.push_back(figure_internal::ZoomPanel(io::AxisLabelOfChannels({loop.bit_speed}),
                                                     ChannelSeries(loop, rec, j, masked[j], zoom.from_s, zoom.to_s),
                                                     zoom));
  return figure;
}

namespace {

void FeatureTable(std::ostream& out, const FeatureSet& recording, const FeatureSet& before, const FeatureSet& after) {
  out << "<table><tr><th>feature</th><th>recording</th><th>scale</th><th>baseline</th><th>(scales)</th>"
         "<th>fitted</th><th>(scales)</th></tr>\n";
  for (const Feature& f : recording.features) {
    const double b = before.Value(f.name), a = after.Value(f.name);
    out << "<tr><td>" << Html(f.name) << "</td><td>" << Cell(f.value) << "</td><td>" << Cell(f.scale, 2) << "</td><td>"
        << Cell(b) << "</td><td>" << Cell((b - f.value) / f.scale, 2) << "</td><td>" << Cell(a) << "</td><td>"
        << Cell((a - f.value) / f.scale, 2) << "</td></tr>\n";
  }
  out << "</table>\n";
}

}  // namespace

void WriteLoopHtml(const DiagnosisLoop& loop, const Recording& rec, std::ostream& out) {
  out << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>drillwave diagnosis of "
      << Html(rec.source) << "</title>\n<style>body{font-family:sans-serif;max-width:1100px;margin:1em auto;}"
         "table{border-collapse:collapse;font-size:0.9em}td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}"
         "td:first-child,th:first-child{text-align:left}.kept{background:#e6f4e6}</style></head><body>\n";
  out << "<h1>Diagnosis of " << Html(rec.source) << "</h1>\n";
  out << "<p>Fit window [" << Fixed(loop.recording_fit.begin_s, 2) << ", " << Fixed(loop.recording_fit.end_s, 2)
      << "] s, held out [" << Fixed(loop.recording_held_out.begin_s, 2) << ", "
      << Fixed(loop.recording_held_out.end_s, 2) << "] s; " << loop.model_runs << " model runs in "
      << Fixed(loop.wall_seconds.total, 0) << " s (the effects' fits " << Fixed(loop.wall_seconds.selection, 0)
      << " s, the base's calibration " << Fixed(loop.wall_seconds.calibration, 0) << " s).</p>\n";
  out << "<h2>Result</h2>\n<p>";
  if (loop.kept < 0) {
    out << "No effect kept: the baseline stands.";
  } else {
    out << "Kept: <b>";
    for (const std::string& e : loop.candidates[loop.kept].effects) out << Html(e) << " ";
    out << "</b>.";
  }
  out << " Held-out error (mean squared feature difference in feature scales) " << Cell(loop.baseline_held_out_error)
      << " &rarr; " << Cell(loop.fitted_held_out_error) << "; on the fit window " << Cell(loop.baseline_fit_error)
      << " &rarr; " << Cell(loop.fitted_fit_error) << ".</p>\n";
  // Where some of the baseline's draws reached the other regime (a bistable point), how many, and what counts.
  const auto in_regime = std::count(loop.baseline_draw_in_regime.begin(), loop.baseline_draw_in_regime.end(), 1);
  if (in_regime < static_cast<long>(loop.baseline_draw_in_regime.size()))
    out << "<p>Regime: the recording's bit " << (loop.recording_bounces ? "bounces" : "stays on the bottom") << " (off "
        << "the bottom " << Fixed(100 * loop.recorded_off_bottom_share, 1) << " % of the time); " << in_regime << " of "
        << loop.baseline_draw_in_regime.size() << " draws of the baseline did the same, and "
        << (in_regime ? "only those are judged, the fits running draw " + std::to_string(loop.fit_draw) + "."
                      : std::string("none did: all are judged.")) << "</p>\n";
  std::ostringstream svg;
  io::WriteSvg(DiagnosisFigure(loop, rec), svg);
  std::string picture = svg.str();
  if (picture.rfind("<?xml", 0) == 0) picture = picture.substr(picture.find("?>") + 2);  // inline: no prolog
  out << "<figure id=\"channels\">" << picture << "</figure>\n";

  out << "<h2>Candidates</h2>\n<table><tr><th>effects</th><th>runs</th><th>s</th><th>fit error</th>"
         "<th>held-out error</th><th>AIC</th><th>parameters (&plusmn; 1 sigma)</th><th>note</th></tr>\n";
  out << "<tr><td>baseline</td><td>1</td><td></td><td>" << Cell(loop.baseline_fit_error) << "</td><td>"
      << Cell(loop.baseline_held_out_error) << "</td><td>" << Cell(loop.baseline_aic)
      << "</td><td></td><td></td></tr>\n";
  for (const Candidate& c : loop.candidates) {
    out << "<tr" << (c.kept ? " class=\"kept\"" : "") << "><td>";
    for (const std::string& e : c.effects) out << Html(e) << " ";
    out << "</td><td>" << c.evaluations + c.redrawn_runs << "</td><td>" << Fixed(c.wall_seconds, 0) << "</td><td>"
        << Cell(c.fit_error) << "</td><td>" << Cell(c.held_out_error) << "</td><td>" << Cell(c.aic) << "</td><td>";
    for (const FittedParameter& p : c.parameters)
      out << Html(p.name) << " = " << Cell(p.value) << " &plusmn; " << Cell(p.sigma, 2) << " " << Html(p.unit) << "<br>";
    // The decision with its numbers (Candidate::verdict), or why it could not be judged.
    out << "</td><td>" << Html(c.failure.empty() ? (c.verdict.empty() && c.kept ? "kept" : c.verdict) : c.failure)
        << "</td></tr>\n";
  }
  out << "</table>\n<p>Relative probability of each model (Akaike weights of the fit window's AIC: the models' "
         "evidence as far as the fit window tells; the loop decides on the held-out window): ";
  std::string list;
  for (const ModelProbability& m : AkaikeWeights(loop)) {
    if (m.weight < 0.01) continue;
    std::string name;
    for (const std::string& e : m.effects) name += (name.empty() ? "" : " + ") + e;
    list += (list.empty() ? "" : ", ") + Html(name.empty() ? "baseline" : name) + " " + Fixed(m.weight, 2);
  }
  out << (list.empty() ? std::string("none above 0.01") : list) << ".</p>\n<h2>Evidence</h2>\n<ul>\n";
  for (const Effect& e : loop.proposals)
    if (e.strength > 0) out << "<li><b>" << Html(e.name) << "</b> (" << Fixed(e.strength, 1) << "): " << Html(e.evidence) << "</li>\n";
  out << "</ul>\n<h2>Features, held out</h2>\n";
  FeatureTable(out, loop.recording_held_out, loop.baseline_held_out, loop.fitted_held_out);
  out << "<h2>Features, fit window</h2>\n";
  FeatureTable(out, loop.recording_fit, loop.baseline_fit, loop.fitted_fit);
  out << "<h2>Regime</h2>\n<p>" << Html(RegimeMarginText(loop.regime_margin)) << ".</p>\n";
  out << "<h2>Unexplained (held out, more than 3 scales off)</h2>\n<ul>\n";
  for (const std::string& u : loop.unexplained) out << "<li>" << Html(u) << "</li>\n";
  if (loop.unexplained.empty()) out << "<li>none</li>\n";
  out << "</ul>\n<h2>Sensor noise estimated from the recording</h2>\n<ul>\n";
  for (const auto& [channel, sigma] : loop.noise) out << "<li>" << Html(channel) << ": " << Cell(sigma, 3) << "</li>\n";
  out << "</ul>\n<h2>Artefacts masked (not modelled)</h2>\n<ul>\n";
  for (const auto& [channel, count] : loop.masked_samples)
    out << "<li>" << Html(channel) << ": " << count << " samples</li>\n";
  for (const std::string& channel : loop.channels_left_whole)
    out << "<li>" << Html(channel) << ": left whole, its bursts too many for artefacts (motion, e.g. a bouncing bit's "
        << "impacts)</li>\n";
  out << "</ul>\n</body></html>\n";
}

void WriteDiagnosisLoop(const DiagnosisLoop& loop, const Recording& rec, const std::string& out_dir,
                        const Recording* prediction) {
  io::OutputDirectory out(out_dir);
  if (prediction) {
    std::vector<std::string> header = {"time_s"};
    header.insert(header.end(), prediction->names.begin(), prediction->names.end());
    std::vector<std::vector<double>> columns = {prediction->time_s};
    columns.insert(columns.end(), prediction->channels.begin(), prediction->channels.end());
    io::WriteCsv(out.Open("prediction.csv"), header, columns);
  }
  out.Open("diagnosis.json") << DiagnosisLoopToJson(loop).dump(2) << "\n";
  out.Open("fitted-case.json") << loop.fitted_document.dump(2) << "\n";
  out.Open("case.json") << loop.baseline_document.dump(2) << "\n";
  io::WriteSvg(DiagnosisFigure(loop, rec), out.Open("plot.svg"));
  WriteLoopHtml(loop, rec, out.Open("report.html"));
  out.Commit();
}

}  // namespace drillwave::diagnosis
