#pragma once
// A small dependency-free SVG line plot for the runner's quick-look figure: panels stacked vertically over a shared
// x axis, each with its own y axis and legend.
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

namespace drillwave::io {

struct Series {
  std::string label;         // legend text
  std::vector<double> x, y;  // same length; a non-finite x or y breaks the line
};

struct Panel {
  std::string y_label;
  std::vector<Series> series;
};

// An interval of x marked in every panel (shaded behind the data), e.g. a fit window and a held-out window.
struct Span {
  std::string label;  // written at the top of the top panel
  double from, to;
};

struct Figure {
  std::string title;
  std::string x_label;        // the quantity and its unit, e.g. "time [s]" (see axis_label.hpp)
  std::vector<Panel> panels;  // top to bottom
  std::vector<Span> spans = {};  // optional: figures written as {title, x_label, panels} have none
};

// Writes the figure as a standalone SVG document: a data area 900 px wide, and right of it, outside the data, each
// panel's legend (<g class="legend">). Each series becomes one <polyline> per unbroken stretch of finite points,
// reduced by DecimateMinMax so that a million samples still make a small file in which stick-slip spikes survive.
// Spans are <rect class="span"> in each panel.
void WriteSvg(const Figure& figure, std::ostream& out);

// Text as XML (and HTML) character data or attribute value: markup characters escaped, characters XML 1.0 forbids
// dropped.
std::string EscapeXml(const std::string& text);

// The building blocks of WriteSvg, exposed for testing.

// Indices (increasing) of the points to draw when [x_lo, x_hi] spans `columns` pixel columns: in each run of
// consecutive finite points falling in the same column, the first, the lowest, the highest and the last, so the
// drawn line covers the same vertical extent as the full one. Non-finite points are kept (one per run of them) so
// the caller still sees the breaks. At most about 4 * columns indices for x increasing.
std::vector<std::size_t> DecimateMinMax(const std::vector<double>& x, const std::vector<double>& y, double x_lo,
                                        double x_hi, int columns);

// Tick values k * step inside [lo, hi], with step 1, 2 or 5 times a power of ten chosen to give about
// `target_count` ticks. Empty if the interval is empty or not finite.
std::vector<double> NiceTicks(double lo, double hi, int target_count);

}  // namespace drillwave::io
