#include "drillwave/estimation/estimate_report.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "drillwave/core/format.hpp"

namespace drillwave::estimation {
namespace {

using nlohmann::json;

std::string Html(const std::string& text) { return io::EscapeXml(text); }

// A number of the summary, "-" where it is absent or not finite.
std::string Cell(const json& object, const char* key, int digits = 4) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_number()) return "-";
  const double v = it->get<double>();
  return std::isfinite(v) ? Significant(v, digits) : "-";
}

void ErrorRow(std::ostream& out, const std::string& what, const json& e, const std::string& unit) {
  out << "<tr><td>" << Html(what) << "</td><td>" << Html(e.value("channel", std::string("-"))) << "</td><td>"
      << Cell(e, "rms") << " " << unit << "</td><td>" << Cell(e, "rms_percent_of_mean", 3) << " %</td><td>"
      << Cell(e, "bias") << " " << unit << "</td><td>" << Cell(e, "measured_mean") << " " << unit << "</td><td>"
      << e.value("samples", 0L) << "</td></tr>\n";
}

void Errors(std::ostream& out, const json& errors) {
  out << "<h2>Errors against the downhole channels</h2>\n";
  if (errors.empty()) {
    out << "<p>The recording holds no downhole channel: nothing to score the estimate against.</p>\n";
    return;
  }
  const json window = errors.value("window_s", json::array());
  out << "<p>Read only after the estimate, to score it";
  if (window.size() == 2) out << ", over [" << Fixed(window[0], 2) << ", " << Fixed(window[1], 2) << "] s";
  out << ".</p>\n<table><tr><th>estimate</th><th>measured channel</th><th>RMS</th><th>RMS of the mean</th>"
         "<th>bias</th><th>measured mean</th><th>samples</th></tr>\n";
  if (errors.contains("bit_rpm")) ErrorRow(out, "bit speed", errors["bit_rpm"], "rpm");
  if (errors.contains("bit_torque_Nm")) ErrorRow(out, "torque on bit", errors["bit_torque_Nm"], "N m");
  if (errors.contains("wob_N")) ErrorRow(out, "weight on bit", errors["wob_N"], "N");
  out << "</table>\n";
  if (errors.contains("stuck")) {
    const json& s = errors["stuck"];
    out << "<p>Stuck samples: precision " << Cell(s, "precision", 3) << ", recall " << Cell(s, "recall", 3) << ", F1 "
        << Cell(s, "f1", 3) << " (the measured bit stuck " << Cell(s, "measured_stuck_fraction", 3)
        << " of the time).</p>\n";
  }
  if (errors.contains("bit_rpm_at_downhole_delay")) {
    const json& a = errors["bit_rpm_at_downhole_delay"];
    out << "<p>The measured bit speed lags the estimate by " << Cell(a, "delay_s", 3)
        << " s (a telemetry delay, or a sensor's averaging where it is a few samples): at that delay the RMS is "
        << Cell(a, "rms") << " rpm (" << Cell(a, "rms_percent_of_mean", 3) << " % of the mean), stuck F1 "
        << Cell(a, "stuck_f1", 3) << ".</p>\n";
  }
}

void Events(std::ostream& out, const json& events) {
  out << "<h2>Stick-slip events (estimated)</h2>\n";
  if (events.empty()) {
    out << "<p>The estimated bit never sticks.</p>\n";
    return;
  }
  double total = 0, longest = 0;
  for (const json& e : events) {
    const double d = e["stick_end_s"].get<double>() - e["stick_begin_s"].get<double>();
    total += d, longest = std::max(longest, d);
  }
  out << "<p>" << events.size() << " stuck episodes, " << Fixed(total, 2) << " s stuck in all, the longest "
      << Fixed(longest, 2) << " s.</p>\n<table><tr><th>stuck from [s]</th><th>to [s]</th><th>for [s]</th></tr>\n";
  constexpr std::size_t kListed = 30;  // the rest are in estimate.json
  for (std::size_t i = 0; i < std::min(events.size(), kListed); ++i) {
    const double b = events[i]["stick_begin_s"].get<double>(), e = events[i]["stick_end_s"].get<double>();
    out << "<tr><td>" << Fixed(b, 2) << "</td><td>" << Fixed(e, 2) << "</td><td>" << Fixed(e - b, 2) << "</td></tr>\n";
  }
  out << "</table>\n";
  if (events.size() > kListed) out << "<p>The first " << kListed << "; all in estimate.json.</p>\n";
}

void Severity(std::ostream& out, const json& summary) {
  const json windows = summary.value("severity_windows", json::array());
  out << "<h2>Stick-slip severity</h2>\n<p>" << Html(summary.value("severity_definition", std::string())) << ".</p>\n";
  if (windows.empty()) {
    out << "<p>No window long enough.</p>\n";
    return;
  }
  out << "<table><tr><th>window [s]</th><th>severity</th><th>stuck share</th></tr>\n";
  for (const json& w : windows)
    out << "<tr><td>" << Fixed(w["begin_s"].get<double>(), 1) << " &ndash; " << Fixed(w["end_s"].get<double>(), 1)
        << "</td><td>" << Cell(w, "severity", 3) << "</td><td>" << Cell(w, "stuck_fraction", 3) << "</td></tr>\n";
  out << "</table>\n";
}

}  // namespace

void WriteEstimateHtml(const std::string& source, const json& summary, const io::Figure& figure, std::ostream& out) {
  out << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>drillwave estimate of "
      << Html(source) << "</title>\n<style>body{font-family:sans-serif;max-width:1100px;margin:1em auto;}"
         "table{border-collapse:collapse;font-size:0.9em}td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}"
         "td:first-child,th:first-child{text-align:left}</style></head><body>\n";
  out << "<h1>The bit estimated from the surface: " << Html(source) << "</h1>\n";
  out << "<p>Method: " << Html(summary.value("method", std::string())) << ". Latency " << Cell(summary, "latency_s", 3)
      << " s (the estimate for time t needs the surface signals up to t plus that). Stuck: "
      << Html(summary.value("stuck_rule", std::string())) << " (" << Cell(summary, "stuck_threshold_rpm", 3)
      << " rpm).</p>\n";
  std::ostringstream svg;
  io::WriteSvg(figure, svg);
  std::string picture = svg.str();
  if (picture.rfind("<?xml", 0) == 0) picture = picture.substr(picture.find("?>") + 2);  // inline: no prolog
  out << "<figure id=\"estimate\">" << picture << "</figure>\n";
  Errors(out, summary.value("errors", json::object()));
  Events(out, summary.value("stuck_events", json::array()));
  Severity(out, summary);
  out << "<h2>Notes</h2>\n<ul>\n";
  for (const json& n : summary.value("notes", json::array())) out << "<li>" << Html(n.get<std::string>()) << "</li>\n";
  out << "</ul>\n</body></html>\n";
}

}  // namespace drillwave::estimation
