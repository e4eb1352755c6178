// The top-drive laws' envelopes: a stability map per law (stability_map.cpp does the work), what is counted on it and
// its outputs.
#include "drillwave/cases/controller_envelope.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "drillwave/core/format.hpp"
#include "drillwave/core/progress.hpp"
#include "drillwave/io/svg_heatmap.hpp"

namespace drillwave::cases {
namespace {

std::string Number(double v) { return std::isfinite(v) ? Significant(v, 6) : "nan"; }

// Whether each grid point's class (free of stick-slip or not, by `free`) differs from a neighbour's along an axis.
template <class Free>
std::vector<bool> BoundaryPoints(const StabilityMapResult& map, std::size_t nx, std::size_t ny, const Free& free) {
  std::vector<bool> boundary(map.cells.size(), false);
  auto compare = [&](std::size_t a, std::size_t b) {
    if (free(map.cells[a]) == free(map.cells[b])) return;
    boundary[a] = boundary[b] = true;
  };
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      if (i + 1 < nx) compare(j * nx + i, j * nx + i + 1);
      if (j + 1 < ny) compare(j * nx + i, (j + 1) * nx + i);
    }
  return boundary;
}

bool SimulatedFree(const StabilityMapCell& cell) { return cell.regime == Regime::kSmooth; }
std::vector<bool> LinearBoundary(const StabilityMapResult& map, std::size_t nx, std::size_t ny) {
  return BoundaryPoints(map, nx, ny, LinearlySteady);
}
std::vector<bool> SimulatedBoundary(const StabilityMapResult& map, std::size_t nx, std::size_t ny) {
  return BoundaryPoints(map, nx, ny, SimulatedFree);
}

void Count(std::size_t nx, std::size_t ny, LawEnvelope& e) {
  const std::vector<bool> boundary = LinearBoundary(e.map, nx, ny), simulated = SimulatedBoundary(e.map, nx, ny);
  for (std::size_t k = 0; k < e.map.cells.size(); ++k) {
    const StabilityMapCell& c = e.map.cells[k];
    e.simulated_boundary += simulated[k];
    e.linear_free += LinearlySteady(c);
    e.marginal += c.steady_states > 0 && c.verdict == analysis::Spectrum::Verdict::kMarginal;
    e.simulated_free += SimulatedFree(c);
    if (!boundary[k]) continue;
    ++e.boundary;
    e.boundary_agreeing += LinearlySteady(c) == SimulatedFree(c);
  }
}

// The width and height a standalone SVG of WriteHeatMapSvg declares on its first element.
std::pair<double, double> SvgSize(const std::string& svg) {
  auto attribute = [&](const char* name) {
    const std::size_t at = svg.find(std::string(" ") + name + "=\"");
    return at == std::string::npos ? 0.0 : std::stod(svg.substr(at + std::char_traits<char>::length(name) + 3));
  };
  return {attribute("width"), attribute("height")};
}

}  // namespace

ControllerEnvelopes MapControllerEnvelopes(const ControllerComparison& nominal, const MapAxis& x, const MapAxis& y,
                                           int jobs) {
  ControllerEnvelopes out{x, y, {}};
  Progress progress("compare-controllers envelopes");
  for (const ControllerResult& r : nominal.laws) {
    progress.Count(r.law + ": linear verdicts and runs of " + std::to_string(x.values.size() * y.values.size()) +
                       " grid points", out.laws.size(), nominal.laws.size(), "laws");
    LawEnvelope e{r.law, StabilityMap2D(r.document, {x, y, jobs, true})};
    Count(x.values.size(), y.values.size(), e);
    out.laws.push_back(std::move(e));
  }
  return out;
}

void WriteEnvelopeCsv(const ControllerEnvelopes& envelopes, std::ostream& out) {
  out << "law,p1,p2,verdict,rightmost_re_per_s,regime,stick_fraction,severity,boundary,simulated_boundary\n";
  const std::size_t nx = envelopes.x.values.size(), ny = envelopes.y.values.size();
  for (const LawEnvelope& e : envelopes.laws) {
    const std::vector<bool> boundary = LinearBoundary(e.map, nx, ny), simulated = SimulatedBoundary(e.map, nx, ny);
    for (std::size_t k = 0; k < e.map.cells.size(); ++k) {
      const StabilityMapCell& c = e.map.cells[k];
      out << e.law << "," << Number(c.x) << "," << Number(c.y) << "," << CellVerdictName(c) << ","
          << Number(c.spectral_abscissa) << "," << RegimeName(c.regime) << "," << Number(c.stick_fraction) << ","
          << Number(c.severity) << "," << (boundary[k] ? 1 : 0) << "," << (simulated[k] ? 1 : 0) << "\n";
    }
  }
}

void WriteEnvelopeSvg(const std::string& name, const ControllerEnvelopes& envelopes, std::ostream& out) {
  std::vector<std::string> panels;
  double width = 0, height = 0;
  for (const LawEnvelope& e : envelopes.laws) {
    io::HeatMap map = StabilityHeatMap({envelopes.x, envelopes.y, 1, true}, e.map);
    map.title = name + ", " + e.law + ": linear verdict (colour), regime after the handover (marker)";
    std::ostringstream panel;
    io::WriteHeatMapSvg(map, panel);
    panels.push_back(panel.str());
    const auto [w, h] = SvgSize(panels.back());
    width = std::max(width, w), height += h;
  }
  // The panels are nested SVG documents, stacked.
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << " " << height << "\">\n";
  double top = 0;
  for (const std::string& panel : panels) {
    out << "<g transform=\"translate(0," << top << ")\">\n" << panel << "</g>\n";
    top += SvgSize(panel).second;
  }
  out << "</svg>\n";
}

void WriteEnvelopeMarkdown(const ControllerEnvelopes& envelopes, std::ostream& out) {
  const MapAxis &x = envelopes.x, &y = envelopes.y;
  const std::size_t points = x.values.size() * y.values.size();
  out << "\n## Stick-slip-free envelopes\n\n"
      << "Every law as tuned above, held fixed over " << x.pointer << " (" << x.values.size() << " values, "
      << Number(x.values.front()) << " to " << Number(x.values.back()) << ") x " << y.pointer << " ("
      << y.values.size() << " values, " << Number(y.values.front()) << " to " << Number(y.values.back())
      << "): at each of the " << points << " grid points the linear verdict (free of stick-slip: a stable or "
      << "marginal steady state) and a run under the comparison's protocol, classified over the window after the "
      << "handover (free: smooth). Boundary points: those whose linear verdict differs from a neighbour's; agreeing: "
      << "the run is smooth where the verdict is free and not where it is not; simulated boundary: the points "
      << "whose run is smooth where a neighbour's is not, or the reverse (envelopes.csv, envelopes.svg).\n\n"
      << "| law | free area, linear | of it marginal | free area, simulated | boundary points | simulation agrees "
         "at | linear [s] | runs [s] | simulated boundary |\n|---|---|---|---|---|---|---|---|---|\n";
  auto fraction = [&](int count) { return Significant(double(count) / points, 3); };
  for (const LawEnvelope& e : envelopes.laws)
    out << "| " << e.law << " | " << fraction(e.linear_free) << " | " << fraction(e.marginal) << " | "
        << fraction(e.simulated_free) << " | " << e.boundary << " | " << e.boundary_agreeing << " | "
        << Significant(e.map.linear_wall_time_s, 3) << " | " << Significant(e.map.simulation_wall_time_s, 3) << " | "
        << e.simulated_boundary << " |\n";
}

}  // namespace drillwave::cases
