#pragma once
// A dependency-free SVG heat map: a grid of coloured cells over two parameters, with an optional marker per cell and
// a legend of named colours and markers (stability maps: the linear verdict as colour, the simulated regime as
// marker).
#include <ostream>
#include <string>
#include <vector>

namespace drillwave::io {

enum class Marker { kNone, kFilledCircle, kOpenCircle, kTriangle, kCross };

struct LegendEntry {
  std::string label;
  std::string colour;            // a cell colour ("#rrggbb"), or empty for a marker entry
  Marker marker = Marker::kNone;
};

struct HeatMap {
  std::string title, x_label, y_label;
  std::vector<double> x, y;             // cell centres, increasing (or decreasing) along each axis
  std::vector<std::string> colours;     // x.size() * y.size(), x fastest: colours[j * nx + i] is (x[i], y[j])
  std::vector<Marker> markers;          // empty, or one per cell
  std::vector<LegendEntry> legend;
};

// Writes a standalone SVG about 900 px wide. Throws std::invalid_argument if the sizes disagree or an axis is empty.
void WriteHeatMapSvg(const HeatMap& map, std::ostream& out);

}  // namespace drillwave::io
