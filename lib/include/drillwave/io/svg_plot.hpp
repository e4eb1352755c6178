#pragma once
// A small dependency-free SVG line plot for the runner's quick-look figure: panels stacked vertically over a shared
// x axis, each with its own y axis and legend; a panel may have an x axis of its own (a zoom on a few cycles).
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

namespace drillwave::io {

// How a series is drawn.
enum class Mark {
  kLine,  // a line through the points
  kDots,  // a small dot at each point, unjoined: samples set apart from a line (e.g. those masked as artefacts)
};

struct Series {
  std::string label;         // legend text
  std::vector<double> x, y;  // same length; a non-finite x or y breaks the line (and has no dot)
  Mark mark = Mark::kLine;
  std::string colour = {};  // an SVG colour; empty: the palette's next (a series with its own colour takes none)
};

struct Panel {
  std::string y_label;
  std::vector<Series> series;
  // Empty: the panel shares the figure's x axis. Otherwise the panel has an x axis of its own, labelled so, over its
  // own series' x range, with its tick labels and this label under it, and no spans (e.g. a zoom on a few cycles).
  std::string x_label = {};
};

// An interval of x marked in every panel on the shared x axis (shaded behind the data), e.g. a fit window and a
// held-out window.
struct Span {
  std::string label;  // written at the top of the first panel on the shared x axis
  double from, to;
};

struct Figure {
  std::string title;
  std::string x_label;        // the shared x axis: its quantity and unit, e.g. "time [s]" (see axis_label.hpp)
  std::vector<Panel> panels;  // top to bottom; the shared x axis is labelled under the last panel that shares it
  std::vector<Span> spans = {};  // optional: figures written as {title, x_label, panels} have none
};

// Writes the figure as a standalone SVG document: a data area 900 px wide, and right of it, outside the data, each
// panel's legend (<g class="legend">). Each series becomes one <polyline> per unbroken stretch of finite points,
// reduced by DecimateMinMax so that a million samples still make a small file in which stick-slip spikes survive.
// A series of dots becomes <g class="dots"> of <circle>s, reduced alike. Spans are <rect class="span"> in each panel.
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
