#include "drillwave/io/svg_heatmap.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "drillwave/io/svg_plot.hpp"

namespace drillwave::io {
namespace {

constexpr double kLeft = 90, kTop = 40, kPlot = 600, kBottom = 60;

std::string Px(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f", v);
  return b;
}

std::string Label(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

// Cell edges along an axis: midway between centres, half a spacing beyond the ends.
std::vector<double> Edges(const std::vector<double>& c) {
  std::vector<double> e(c.size() + 1);
  if (c.size() == 1) {
    const double half = c[0] != 0 ? 0.05 * std::abs(c[0]) : 0.5;
    return {c[0] - half, c[0] + half};
  }
  for (std::size_t i = 1; i < c.size(); ++i) e[i] = 0.5 * (c[i - 1] + c[i]);
  e.front() = c.front() - (e[1] - c.front());
  e.back() = c.back() + (c.back() - e[c.size() - 1]);
  return e;
}

void WriteMarker(Marker m, double cx, double cy, double r, std::ostream& out) {
  switch (m) {
    case Marker::kNone: return;
    case Marker::kFilledCircle:
      out << "<circle cx=\"" << Px(cx) << "\" cy=\"" << Px(cy) << "\" r=\"" << Px(r) << "\" fill=\"#000\"/>\n";
      return;
    case Marker::kOpenCircle:
      out << "<circle cx=\"" << Px(cx) << "\" cy=\"" << Px(cy) << "\" r=\"" << Px(r)
          << "\" fill=\"none\" stroke=\"#000\" stroke-width=\"1\"/>\n";
      return;
    case Marker::kTriangle:
      out << "<polygon points=\"" << Px(cx) << "," << Px(cy - r) << " " << Px(cx - r) << "," << Px(cy + r) << " "
          << Px(cx + r) << "," << Px(cy + r) << "\" fill=\"#000\"/>\n";
      return;
    case Marker::kCross:
      out << "<path d=\"M" << Px(cx - r) << " " << Px(cy - r) << "L" << Px(cx + r) << " " << Px(cy + r) << "M"
          << Px(cx - r) << " " << Px(cy + r) << "L" << Px(cx + r) << " " << Px(cy - r)
          << "\" stroke=\"#000\" stroke-width=\"1.2\"/>\n";
      return;
  }
}

// The legend column right of the map, wide enough for its longest label (about 7 px a character at 12 px), so that
// no label is cut off at the picture's edge.
double LegendWidth(const HeatMap& map) {
  std::size_t longest = 0;
  for (const LegendEntry& e : map.legend) longest = std::max(longest, e.label.size());
  return 20 + 22 + 7 * static_cast<double>(longest) + 20;
}

}  // namespace

void WriteHeatMapSvg(const HeatMap& map, std::ostream& out) {
  const std::size_t nx = map.x.size(), ny = map.y.size();
  if (nx == 0 || ny == 0) throw std::invalid_argument("a heat map needs at least one x and one y value");
  if (map.colours.size() != nx * ny || (!map.markers.empty() && map.markers.size() != nx * ny))
    throw std::invalid_argument("a heat map needs one colour (and marker) per cell");
  const std::vector<double> ex = Edges(map.x), ey = Edges(map.y);
  const double x_lo = std::min(ex.front(), ex.back()), x_hi = std::max(ex.front(), ex.back());
  const double y_lo = std::min(ey.front(), ey.back()), y_hi = std::max(ey.front(), ey.back());
  auto px = [&](double x) { return kLeft + (x - x_lo) / (x_hi - x_lo) * kPlot; };
  auto py = [&](double y) { return kTop + kPlot - (y - y_lo) / (y_hi - y_lo) * kPlot; };
  const double width = kLeft + kPlot + LegendWidth(map), height = kTop + kPlot + kBottom;
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << " " << height << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n"
      << "<text x=\"" << Px(kLeft) << "\" y=\"24\" font-size=\"14\">" << EscapeXml(map.title) << "</text>\n";
  // Cells without gaps: each spans its edges (rounded outwards by a hair so no seams show).
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      const double x0 = std::min(px(ex[i]), px(ex[i + 1])), x1 = std::max(px(ex[i]), px(ex[i + 1]));
      const double y0 = std::min(py(ey[j]), py(ey[j + 1])), y1 = std::max(py(ey[j]), py(ey[j + 1]));
      out << "<rect x=\"" << Px(x0) << "\" y=\"" << Px(y0) << "\" width=\"" << Px(x1 - x0 + 0.3) << "\" height=\""
          << Px(y1 - y0 + 0.3) << "\" fill=\"" << map.colours[j * nx + i] << "\"/>\n";
    }
  if (!map.markers.empty())
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        const double r = std::max(1.0, 0.3 * std::min(kPlot / nx, kPlot / ny));
        WriteMarker(map.markers[j * nx + i], px(map.x[i]), py(map.y[j]), std::min(r, 6.0), out);
      }
  // Frame, ticks, labels.
  out << "<rect x=\"" << Px(kLeft) << "\" y=\"" << Px(kTop) << "\" width=\"" << Px(kPlot) << "\" height=\"" << Px(kPlot)
      << "\" fill=\"none\" stroke=\"#000\"/>\n";
  for (double t : NiceTicks(x_lo, x_hi, 8))
    out << "<line x1=\"" << Px(px(t)) << "\" y1=\"" << Px(kTop + kPlot) << "\" x2=\"" << Px(px(t)) << "\" y2=\""
        << Px(kTop + kPlot + 5) << "\" stroke=\"#000\"/>\n<text x=\"" << Px(px(t)) << "\" y=\"" << Px(kTop + kPlot + 18)
        << "\" text-anchor=\"middle\">" << Label(t) << "</text>\n";
  for (double t : NiceTicks(y_lo, y_hi, 8))
    out << "<line x1=\"" << Px(kLeft - 5) << "\" y1=\"" << Px(py(t)) << "\" x2=\"" << Px(kLeft) << "\" y2=\""
        << Px(py(t)) << "\" stroke=\"#000\"/>\n<text x=\"" << Px(kLeft - 8) << "\" y=\"" << Px(py(t) + 4)
        << "\" text-anchor=\"end\">" << Label(t) << "</text>\n";
  out << "<text x=\"" << Px(kLeft + kPlot / 2) << "\" y=\"" << Px(kTop + kPlot + 40) << "\" text-anchor=\"middle\">"
      << EscapeXml(map.x_label) << "</text>\n<text transform=\"translate(18," << Px(kTop + kPlot / 2)
      << ") rotate(-90)\" text-anchor=\"middle\">" << EscapeXml(map.y_label) << "</text>\n";
  // Legend.
  double ly = kTop + 10;
  for (const LegendEntry& e : map.legend) {
    const double lx = kLeft + kPlot + 20;
    if (!e.colour.empty())
      out << "<rect x=\"" << Px(lx) << "\" y=\"" << Px(ly - 10) << "\" width=\"14\" height=\"14\" fill=\"" << e.colour
          << "\" stroke=\"#000\" stroke-width=\"0.5\"/>\n";
    else
      WriteMarker(e.marker, lx + 7, ly - 3, 5, out);
    out << "<text x=\"" << Px(lx + 22) << "\" y=\"" << Px(ly + 2) << "\">" << EscapeXml(e.label) << "</text>\n";
    ly += 22;
  }
  out << "</svg>\n";
}

}  // namespace drillwave::io
