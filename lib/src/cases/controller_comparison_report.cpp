// compare-controllers' outputs: the table as CSV and Markdown, and the figure of every law around the handover.
#include <cmath>
#include <iterator>
#include <ostream>
#include <string>

#include "drillwave/cases/controller_comparison.hpp"
#include "drillwave/cases/statistics.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/io/svg_plot.hpp"

namespace drillwave::cases {
namespace {

std::string Number(double v, int digits = 4) { return std::isfinite(v) ? Significant(v, digits) : "nan"; }
std::string Suppression(const ControllerResult& r) {
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

void WriteCsvTable(const ControllerComparison& c, std::ostream& out) {
  for (const Column& column : kColumns) out << (&column == kColumns ? "" : ",") << column.csv;
  out << "\n";
  for (const ControllerResult& r : c.laws) {
    for (const Column& column : kColumns) out << (&column == kColumns ? "" : ",") << column.value(r);
    out << "\n";
  }
}

void WriteMarkdown(const std::string& name, const ControllerComparison& c, std::ostream& out) {
  out << "# Top-drive laws against stick-slip: " << name << "\n\n"
      << "Each law takes over from the stiff PI at " << Number(c.handover_s) << " s, in the stick-slip the stiff PI "
      << "keeps up from the case's start (the same state for every law; the integral torque carries over), and runs "
      << "to " << Number(c.end_s) << " s; the stiff PI runs on unchanged. SoftSpeed: a soft_torque top tuned to the "
      << "stiff PI's period P = " << Number(c.tuning_period_s) << " s (kp = Z of the top section, ki = J (2 pi / P)^2);"
      << " "
      << "Z-Torque: the stiff PI tracking the set-point less the string torque over Z, high-passed with tau_f = "
      << Number(c.feedback_time_constant_s) << " s. Severity (max - min) / (2 mean) of the bit speed and the top "
      << "torque's standard deviation are medians over the " << Number(kSeverityWindowS) << "-s windows after the "
      << "handover (top torque: the kind's top_torque_Nm, the torque the top feeds into the string in torsional_wave, "
      << "the drive's torque, which also turns the top drive's inertia, in axial_torsional); the time to suppress "
      << "runs from the handover to the end of the last stick (0: the bit does not stick after it; not suppressed: it "
      << "still sticks in the last " << Number(kSeverityWindowS) << " s). The linear verdict is the rightmost "
      << "characteristic root at the operating point (in the coupled kind it may be the axial regenerative mode, "
      << "which no top-drive law moves).\n\n|";
  for (const Column& column : kColumns) out << " " << column.markdown << " |";
  out << "\n|";
  for (std::size_t k = 0; k < std::size(kColumns); ++k) out << "---|";
  out << "\n";
  for (const ControllerResult& r : c.laws) {
    out << "|";
    for (const Column& column : kColumns) out << " " << column.value(r) << " |";
    out << "\n";
  }
  out << "\nThe tops as run (/model/top):\n\n";
  for (const ControllerResult& r : c.laws) out << "- " << r.law << ": `" << r.top.dump() << "`\n";
}

void WriteFigure(const std::string& name, const ControllerComparison& c, std::ostream& out) {
  io::Figure figure{name + ": top-drive laws from the stiff PI's stick-slip", "time [s]",
                    {{"bit speed [rpm]", {}}, {"top torque [N m]", {}}}};
  figure.spans.push_back({"laws in the loop", c.handover_s, c.end_s});
  for (const ControllerResult& r : c.laws) {
    figure.panels[0].series.push_back({r.law, r.time_s, r.bit_rpm});
    figure.panels[1].series.push_back({r.law, r.time_s, r.top_torque_Nm});
  }
  io::WriteSvg(figure, out);
}

}  // namespace

void WriteControllerComparison(const nlohmann::json& document, const ControllerComparison& comparison,
                               const std::string& out_dir) {
  const std::string name = document.value("name", std::string("case"));
  io::OutputDirectory out(out_dir);
  WriteCsvTable(comparison, out.Open("controllers.csv"));
  WriteMarkdown(name, comparison, out.Open("controllers.md"));
  WriteFigure(name, comparison, out.Open("controllers.svg"));
  out.Open("case.json") << document.dump(2) << "\n";
  out.Commit();
}

}  // namespace drillwave::cases
