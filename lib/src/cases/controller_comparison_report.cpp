// compare-controllers' outputs: the table as CSV and Markdown, and the figure of every law around the handover.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <ostream>
#include <string>

#include "drillwave/cases/controller_comparison.hpp"
#include "drillwave/cases/controller_envelope.hpp"
#include "drillwave/cases/statistics.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/io/svg_plot.hpp"

namespace drillwave::cases {
namespace {

std::string Number(double v, int digits = 4) { return std::isfinite(v) ? Significant(v, digits) : "nan"; }
std::string Suppression(const ControllerResult& r) {
  if (!r.run_failure.empty())  // a run over its step budget did not blow up: it was stopped as too costly
    return r.run_failure.find("step budget exhausted") != std::string::npos ? "run stopped (step budget)" : "run blew up";
  return r.suppressed_after_s ? Number(*r.suppressed_after_s, 3) : "not suppressed";
}

// One line per law; the same columns in the CSV and the Markdown table.
struct Column {
  const char* csv;
  const char* markdown;
  std::string (*value)(const ControllerResult&);
};
const Column kColumns[] = {
    {"law", "law", [](const ControllerResult& r) { return r.law; }},
    {"verdict", "linear verdict", [](const ControllerResult& r) { return r.verdict; }},
    {"rightmost_re_per_s", "rightmost root Re s [1/s]",
     [](const ControllerResult& r) { return Number(r.rightmost_re); }},
    {"rightmost_im_rad_s", "its Im s [rad/s]", [](const ControllerResult& r) { return Number(r.rightmost_im); }},
    {"severity", "median severity", [](const ControllerResult& r) { return Number(r.severity, 3); }},
    {"stick_fraction", "stick fraction", [](const ControllerResult& r) { return Number(r.stick_fraction, 3); }},
    {"period_s", "period [s]", [](const ControllerResult& r) { return Number(r.period_s); }},
    {"top_torque_std_Nm", "top torque std [N m]", [](const ControllerResult& r) { return Number(r.torque_std_Nm); }},
    {"torque_std_reduction_pct", "reduction vs stiff PI [%]",
     [](const ControllerResult& r) { return Number(r.torque_reduction_pct, 3); }},
    {"time_to_suppress_s", "time to suppress [s]", Suppression},
};

// `lead` goes before the law's columns in every line (the delay's column of the delay table, with its separator).
void WriteCsvHeader(const std::string& lead, std::ostream& out) {
  out << lead;
  for (const Column& column : kColumns) out << (&column == kColumns ? "" : ",") << column.csv;
  out << "\n";
}
void WriteCsvRow(const std::string& lead, const ControllerResult& r, std::ostream& out) {
  out << lead;
  for (const Column& column : kColumns) out << (&column == kColumns ? "" : ",") << column.value(r);
  out << "\n";
}

void WriteCsvTable(const ControllerComparison& c, std::ostream& out) {
  WriteCsvHeader("", out);
  for (const ControllerResult& r : c.laws) WriteCsvRow("", r, out);
}

void WriteDelayCsv(const std::vector<ControllerComparison>& delays, std::ostream& out) {
  WriteCsvHeader("actuator_delay_s,", out);
  for (const ControllerComparison& c : delays)
    for (const ControllerResult& r : c.laws) WriteCsvRow(Number(c.actuator_delay_s) + ",", r, out);
}

// Markdown: `lead` holds the leading cells with their separators ("| 0.1 " before "| law |").
void WriteMarkdownHeader(const std::string& lead, std::ostream& out) {
  out << lead << "|";
  for (const Column& column : kColumns) out << " " << column.markdown << " |";
  out << "\n|";
  const auto leading = static_cast<std::size_t>(std::count(lead.begin(), lead.end(), '|'));
  for (std::size_t k = 0; k < leading + std::size(kColumns); ++k) out << "---|";
  out << "\n";
}
void WriteMarkdownRow(const std::string& lead, const ControllerResult& r, std::ostream& out) {
  out << lead << "|";
  for (const Column& column : kColumns) out << " " << column.value(r) << " |";
  out << "\n";
}

void WriteMarkdown(const std::string& name, const ControllerComparison& c, std::ostream& out) {
  out << "# Top-drive laws against stick-slip: " << name << "\n\n"
      << "Each law takes over from the stiff PI at " << Number(c.handover_s) << " s, in the stick-slip the stiff PI "
      << "keeps up from the case's start (the same state for every law; the integral torque carries over), and runs "
      << "to " << Number(c.end_s) << " s; the stiff PI runs on unchanged. SoftSpeed: a soft_torque top tuned to the "
      << "stiff PI's period P = " << Number(c.tuning_period_s) << " s (kp = Z of the top section, ki = J (2 pi / P)^2);"
      << " "
      << "Z-Torque: the stiff PI tracking the set-point less the string torque over Z, high-passed with tau_f = "
      << Number(c.feedback_time_constant_s) << " s; wave cancellation: the top absorbing the arriving torsional wave "
      << "exactly and injecting a down-going one, with the stiff PI's kp and a slow speed loop of corner k = "
      << Number(c.wave_corner_rad_s) << " rad/s (2 pi / 10 P); filtered wave cancellation: the same law reading the "
      << "arriving wave through a low-pass of time constant t_f = " << Number(c.wave_filter_time_constant_s)
      << " s (P / 5 pi: its corner at 2.5 times the stick-slip frequency), so that behind a delay it absorbs the "
      << "stick-slip mode and reflects faster waves as a stiff top does; sliding mode: the surface s = e + k I on "
      << "Z-Torque's speed error e (I its integral), the torque J (k e + eta sat(s / phi)), its reaching torque J eta "
      << "= " << Number(c.sliding_reaching_torque_Nm) << " N m (1.5 times the stiff PI's largest torque) and a layer "
      << "phi = " << Number(c.sliding_boundary_layer_rad_s) << " rad/s whose gain J eta / phi is ten times the stiff "
      << "PI's kp. Severity (max - min) / (2 mean) of the bit "
         "speed and "
      << "the top torque's standard deviation are medians over the " << Number(kSeverityWindowS) << "-s windows after "
      << "the handover (top torque: the kind's top_torque_Nm, the torque the top feeds into the string in "
      << "torsional_wave, the drive's torque, which also turns the top drive's inertia, in axial_torsional); the time "
      << "to suppress runs from the handover to the end of the last stick (0: the bit does not stick after it; not "
      << "suppressed: it still sticks in the last " << Number(kSeverityWindowS) << " s). The linear verdict is the "
      << "rightmost characteristic root at the operating point (in the coupled kind it may be the axial regenerative "
      << "mode, which no top-drive law moves).\n\n";
  WriteMarkdownHeader("", out);
  for (const ControllerResult& r : c.laws) WriteMarkdownRow("", r, out);
  out << "\nThe tops as run (/model/top):\n\n";
  for (const ControllerResult& r : c.laws)
    out << "- " << r.law << ": `" << r.document.at("model").at("top").dump() << "`\n";
}

// A law has the benefit of its tuning at a delay where its median severity is below the stiff PI's at that delay; a
// severity that is not a number (the bit turned backwards, the run blew up) is worse than any.
bool Benefits(const ControllerComparison& c, const ControllerResult& r) {
  const double stiff = c.laws.front().severity;
  return std::isfinite(r.severity) && (!std::isfinite(stiff) || r.severity < stiff);
}

void WriteDelayMarkdown(const std::vector<ControllerComparison>& delays, std::ostream& out) {
  out << "\n## Actuator delay\n\n"
      << "Every law with the drive's torque acting the delay after its controller computes it (the stiff PI too, "
      << "before and after the handover), SoftSpeed, Z-Torque and both wave cancellations tuned as above (at the "
      << "nominal delay) and held; the "
      << "reduction is against the stiff PI at the same delay; benefit: a median severity below the stiff PI's at the "
      << "same delay (nan, the bit turned backwards, the run blew up or took more than " << kDelayedWorkFactor
      << " times the costliest nominal run's steps, is worse than any). The linear verdict "
      << "includes the delay (retarded terms of the drive's speed and string torque in the linearization).\n\n";
  WriteMarkdownHeader("| actuator delay [s] ", out);
  for (const ControllerComparison& c : delays)
    for (const ControllerResult& r : c.laws)
      WriteMarkdownRow("| " + Number(c.actuator_delay_s) + " ", r, out);
  out << "\n";
  for (const ControllerComparison& c : delays)
    for (const ControllerResult& r : c.laws)
      if (!r.run_failure.empty())
        out << "- " << r.law << " at " << Number(c.actuator_delay_s) << " s delay: " << r.run_failure << "\n";
  for (std::size_t law = 1; law < delays.front().laws.size(); ++law) {
    const auto lost = std::find_if(delays.begin(), delays.end(), [&](const ControllerComparison& c) {
      return !Benefits(c, c.laws[law]);
    });
    out << "- " << delays.front().laws[law].law << ": "
        << (lost == delays.end() ? "keeps its benefit at every delay studied"
                                 : "no benefit at " + Number(lost->actuator_delay_s) + " s delay")
        << "\n";
  }
}

void WriteFigure(const std::string& name, const ControllerComparison& c, std::ostream& out) {
  io::Figure figure{name + ": top-drive laws from the stiff PI's stick-slip", "time [s]",
                    {{"bit speed [rpm]", {}}, {"top torque [N m]", {}}}};
  figure.spans.push_back({"laws in the loop", c.handover_s, c.end_s});
  for (const ControllerResult& r : c.laws) {
    if (!r.run_failure.empty()) continue;
    figure.panels[0].series.push_back({r.law, r.time_s, r.bit_rpm});
    figure.panels[1].series.push_back({r.law, r.time_s, r.top_torque_Nm});
  }
  io::WriteSvg(figure, out);
}

}  // namespace

void WriteControllerComparison(const nlohmann::json& document, const ControllerComparison& comparison,
                               const std::string& out_dir, const ControllerStudies& studies) {
  const std::string name = document.value("name", std::string("case"));
  io::OutputDirectory out(out_dir);
  WriteCsvTable(comparison, out.Open("controllers.csv"));
  std::ostream& markdown = out.Open("controllers.md");
  WriteMarkdown(name, comparison, markdown);
  if (studies.envelopes) {
    WriteEnvelopeMarkdown(*studies.envelopes, markdown);
    WriteEnvelopeCsv(*studies.envelopes, out.Open("envelopes.csv"));
    WriteEnvelopeSvg(name, *studies.envelopes, out.Open("envelopes.svg"));
  }
  if (!studies.delays.empty()) {
    WriteDelayMarkdown(studies.delays, markdown);
    WriteDelayCsv(studies.delays, out.Open("delays.csv"));
  }
  WriteFigure(name, comparison, out.Open("controllers.svg"));
  out.Open("case.json") << document.dump(2) << "\n";
  out.Commit();
}

}  // namespace drillwave::cases
