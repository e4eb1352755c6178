#include "drillwave/io/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace drillwave::io {
namespace {

// Layout in px. Inner panels carry no x tick labels (the axis is shared), so they need only a small gap. The legends
// stand in a column right of the data, so they hide none of it.
constexpr double kLeft = 80;    // y tick labels and the rotated y label
constexpr double kPlotWidth = 900;
constexpr double kRight = 20;   // right of the legends (or of the data, without legends)
constexpr double kLegendGap = 12;
constexpr double kTitle = 40;
constexpr double kPanelHeight = 220;
constexpr double kPanelGap = 16;
constexpr double kBottom = 50;  // x tick labels and the x label
constexpr double kLegendRow = 16;
constexpr double kCharWidth = 7;  // about, at 12 px

// Light fills for spans, behind the data: alternating so that adjacent windows stay apart.
constexpr const char* kSpanColours[] = {"#fdf1c7", "#dcebfa"};

// Matplotlib's "tab10": distinct, and readable on white.
constexpr const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                                    "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
constexpr std::size_t kColourCount = sizeof kColours / sizeof kColours[0];


// A pixel coordinate: 0.01 px is finer than any screen, and short numbers keep the file small.
std::string Px(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f", v);
  return b;
}

std::string TickLabel(double v, double step) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", std::abs(v) < 1e-9 * step ? 0.0 : v);  // no "-0" or "1e-17" at zero
  return b;
}

struct Interval {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void Include(const std::vector<double>& values) {
    for (double v : values) {
      if (!std::isfinite(v)) continue;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  void IncludeX(const Panel& panel) {  // the x values of its series
    for (const Series& s : panel.series) Include(s.x);
  }
  // A usable axis even for no data or constant data.
  void MakeNonEmpty() {
    if (!(lo <= hi)) {
      lo = 0;
      hi = 1;
    }
    if (hi - lo <= 1e-12 * std::max(std::abs(lo), std::abs(hi))) {
      const double half = hi != 0 ? 0.05 * std::abs(hi) : 0.5;
      lo -= half;
      hi += half;
    }
  }
};

// Maps data to pixels for one panel.
struct Axes {
  double x_lo, x_hi, y_lo, y_hi, top, bottom;
  double X(double x) const { return kLeft + (x - x_lo) / (x_hi - x_lo) * kPlotWidth; }
  double Y(double y) const { return bottom - (y - y_lo) / (y_hi - y_lo) * (bottom - top); }
};

// Each series' colour: its own, or the palette's next, so that a series set apart in a colour of its own (masked
// samples in grey) leaves the others the colours they have without it.
std::vector<std::string> Colours(const Panel& panel) {
  std::vector<std::string> colours;
  std::size_t next = 0;
  for (const Series& s : panel.series) colours.push_back(s.colour.empty() ? kColours[next++ % kColourCount] : s.colour);
  return colours;
}

// Dots are small beside the 1.2-px line, so that a burst of them marks its samples without hiding the line.
constexpr double kDotRadius = 2;

void WriteDots(const Series& series, const Axes& axes, const std::string& colour, std::ostream& out) {
  const std::size_t n = std::min(series.x.size(), series.y.size());
  out << "<g class=\"dots\" fill=\"" << colour << "\">";
  for (std::size_t i : DecimateMinMax(series.x, series.y, axes.x_lo, axes.x_hi, static_cast<int>(kPlotWidth))) {
    if (i >= n) break;
    if (!std::isfinite(series.x[i]) || !std::isfinite(series.y[i])) continue;
    out << "<circle cx=\"" << Px(axes.X(series.x[i])) << "\" cy=\"" << Px(axes.Y(series.y[i])) << "\" r=\""
        << kDotRadius << "\"/>";
  }
  out << "</g>\n";
}

void WriteLine(const Series& series, const Axes& axes, const std::string& colour, std::ostream& out) {
  const std::size_t n = std::min(series.x.size(), series.y.size());
  std::string points;  // "x,y x,y ..." of the current unbroken stretch
  double lone_x = 0, lone_y = 0;
  std::size_t count = 0;
  auto flush = [&]() {
    if (count >= 2) {
      out << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.2\" stroke-linejoin=\"round\" "
          << "points=\"" << points << "\"/>\n";
    } else if (count == 1) {  // a lone point between gaps would otherwise vanish
      out << "<circle cx=\"" << Px(lone_x) << "\" cy=\"" << Px(lone_y) << "\" r=\"1.5\" fill=\"" << colour << "\"/>\n";
    }
    points.clear();
    count = 0;
  };
  for (std::size_t i : DecimateMinMax(series.x, series.y, axes.x_lo, axes.x_hi, static_cast<int>(kPlotWidth))) {
    if (i >= n) break;
    if (!std::isfinite(series.x[i]) || !std::isfinite(series.y[i])) {
      flush();
      continue;
    }
    lone_x = axes.X(series.x[i]);
    lone_y = axes.Y(series.y[i]);
    if (count++) points += ' ';
    points += Px(lone_x) + "," + Px(lone_y);
  }
  flush();
}

// The legend box's width for a panel's labelled series, 0 without any.
double LegendWidth(const Panel& panel) {
  std::size_t longest = 0;
  bool any = false;
  for (const Series& s : panel.series)
    if (!s.label.empty()) longest = std::max(longest, s.label.size()), any = true;
  return any ? 34 + kCharWidth * static_cast<double>(longest) : 0;
}

double FigureWidth(const Figure& figure) {
  double legends = 0;
  for (const Panel& panel : figure.panels) legends = std::max(legends, LegendWidth(panel));
  return kLeft + kPlotWidth + (legends > 0 ? kLegendGap + legends : 0) + kRight;
}

// The legend, right of the panel's data area and level with its top.
void WriteLegend(const Panel& panel, const Axes& axes, std::ostream& out) {
  const double width = LegendWidth(panel);
  if (width == 0) return;
  std::size_t entries = 0;
  for (const Series& s : panel.series) entries += s.label.empty() ? 0 : 1;
  const double left = kLeft + kPlotWidth + kLegendGap, top = axes.top;
  out << "<g class=\"legend\"><rect x=\"" << Px(left) << "\" y=\"" << Px(top) << "\" width=\"" << Px(width)
      << "\" height=\"" << Px(kLegendRow * static_cast<double>(entries) + 6) << "\" fill=\"white\" stroke=\"#bbb\"/>\n";
  const std::vector<std::string> colours = Colours(panel);
  std::size_t k = 0;
  for (std::size_t si = 0; si < panel.series.size(); ++si) {
    const Series& series = panel.series[si];
    if (series.label.empty()) continue;
    const double y = top + 3 + kLegendRow * (static_cast<double>(k++) + 0.5);
    if (series.mark == Mark::kDots)
      out << "<circle cx=\"" << Px(left + 15) << "\" cy=\"" << Px(y) << "\" r=\"" << kDotRadius + 1 << "\" fill=\""
          << colours[si] << "\"/>";
    else
      out << "<line x1=\"" << Px(left + 6) << "\" x2=\"" << Px(left + 24) << "\" y1=\"" << Px(y) << "\" y2=\""
          << Px(y) << "\" stroke=\"" << colours[si] << "\" stroke-width=\"2\"/>";
    out << "<text x=\"" << Px(left + 30) << "\" y=\"" << Px(y + 4) << "\">" << EscapeXml(series.label) << "</text>\n";
  }
  out << "</g>\n";
}

// The spans' shading (behind everything else of the panel), with their labels where asked (one panel of a figure).
void WriteSpans(const std::vector<Span>& spans, const Axes& axes, bool labels, std::ostream& out) {
  for (std::size_t k = 0; k < spans.size(); ++k) {
    const double from = std::max(std::min(spans[k].from, spans[k].to), axes.x_lo);
    const double to = std::min(std::max(spans[k].from, spans[k].to), axes.x_hi);
    if (!(from < to)) continue;  // outside the data, or not finite
    out << "<rect class=\"span\" x=\"" << Px(axes.X(from)) << "\" y=\"" << Px(axes.top) << "\" width=\""
        << Px(axes.X(to) - axes.X(from)) << "\" height=\"" << kPanelHeight << "\" fill=\"" << kSpanColours[k % 2]
        << "\"/>\n";
    if (labels && !spans[k].label.empty())
      out << "<text x=\"" << Px(axes.X((from + to) / 2)) << "\" y=\"" << Px(axes.top + 14)
          << "\" text-anchor=\"middle\" fill=\"#555\">" << EscapeXml(spans[k].label) << "</text>\n";
  }
}

// The last panel on the figure's shared x axis, under which that axis is labelled (panels.size() where none shares it).
std::size_t LastSharing(const Figure& figure) {
  for (std::size_t pi = figure.panels.size(); pi-- > 0;)
    if (figure.panels[pi].x_label.empty()) return pi;
  return figure.panels.size();
}

struct Layout {
  std::vector<double> tops;  // of each panel's data area
  double height = 0;         // of the whole picture
};

// Panels stack from the title down; under a panel whose x axis is labelled there (the shared axis under the last
// panel on it, an own axis under its panel) stand the tick labels and the axis label, which need the bottom's room.
Layout Arrange(const Figure& figure, std::size_t last_sharing) {
  Layout layout;
  double top = kTitle;
  for (std::size_t pi = 0; pi < figure.panels.size(); ++pi) {
    layout.tops.push_back(top);
    const bool labelled = pi == last_sharing || !figure.panels[pi].x_label.empty();
    top += kPanelHeight + (pi + 1 == figure.panels.size() ? 0 : labelled ? kBottom + kPanelGap : kPanelGap);
  }
  layout.height = top + kBottom;
  return layout;
}

// One panel: spans (their labels too where asked), grid, frame, y axis, data and legend; and where `x_label` is given,
// the x tick labels and that label under it.
void WritePanel(const Panel& panel, const Interval& x_range, double top, const std::string* x_label,
                const std::vector<Span>& spans, bool label_spans, std::ostream& out) {
  Interval y_range;
  for (const Series& s : panel.series) y_range.Include(s.y);
  y_range.MakeNonEmpty();
  const double pad = 0.05 * (y_range.hi - y_range.lo);  // lines do not touch the frame
  const Axes axes{x_range.lo, x_range.hi, y_range.lo - pad, y_range.hi + pad, top, top + kPanelHeight};
  const std::vector<double> x_ticks = NiceTicks(x_range.lo, x_range.hi, 10);
  const double x_step = x_ticks.size() >= 2 ? x_ticks[1] - x_ticks[0] : 1;

  out << "<g>\n";
  WriteSpans(spans, axes, label_spans, out);
  const std::vector<double> y_ticks = NiceTicks(axes.y_lo, axes.y_hi, 5);
  const double y_step = y_ticks.size() >= 2 ? y_ticks[1] - y_ticks[0] : 1;
  for (double t : y_ticks) {
    out << "<line x1=\"" << kLeft << "\" x2=\"" << kLeft + kPlotWidth << "\" y1=\"" << Px(axes.Y(t)) << "\" y2=\""
        << Px(axes.Y(t)) << "\" stroke=\"#e0e0e0\"/><text x=\"" << kLeft - 6 << "\" y=\"" << Px(axes.Y(t) + 4)
        << "\" text-anchor=\"end\">" << TickLabel(t, y_step) << "</text>\n";
  }
  for (double t : x_ticks) {
    out << "<line x1=\"" << Px(axes.X(t)) << "\" x2=\"" << Px(axes.X(t)) << "\" y1=\"" << Px(axes.top)
        << "\" y2=\"" << Px(axes.bottom) << "\" stroke=\"#e0e0e0\"/>";
    if (x_label)
      out << "<text x=\"" << Px(axes.X(t)) << "\" y=\"" << Px(axes.bottom + 16) << "\" text-anchor=\"middle\">"
          << TickLabel(t, x_step) << "</text>";
    out << "\n";
  }
  out << "<rect x=\"" << kLeft << "\" y=\"" << Px(axes.top) << "\" width=\"" << kPlotWidth << "\" height=\""
      << kPanelHeight << "\" fill=\"none\" stroke=\"#444\"/>\n";
  out << "<text transform=\"translate(18," << Px((axes.top + axes.bottom) / 2)
      << ") rotate(-90)\" text-anchor=\"middle\">" << EscapeXml(panel.y_label) << "</text>\n";
  if (x_label)
    out << "<text x=\"" << kLeft + kPlotWidth / 2 << "\" y=\"" << Px(axes.bottom + 38) << "\" text-anchor=\"middle\">"
        << EscapeXml(*x_label) << "</text>\n";
  const std::vector<std::string> colours = Colours(panel);
  for (std::size_t si = 0; si < panel.series.size(); ++si) {
    const Series& series = panel.series[si];
    if (series.mark == Mark::kDots)
      WriteDots(series, axes, colours[si], out);
    else
      WriteLine(series, axes, colours[si], out);
  }
  WriteLegend(panel, axes, out);
  out << "</g>\n";
}

}  // namespace

std::string EscapeXml(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // Control characters other than tab and line ends are not allowed in XML 1.0 at all.
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\t' || c == '\n' || c == '\r') out += c;
    }
  }
  return out;
}

std::vector<double> NiceTicks(double lo, double hi, int target_count) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo) || target_count < 1) return {};
  const double raw = (hi - lo) / target_count;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double residual = raw / magnitude;  // in [1, 10)
  // The nearest of 1, 2, 5, 10 (Heckbert's rounding), so the count stays within about 0.7 to 1.5 times the target.
  const double step = magnitude * (residual < 1.5 ? 1 : residual < 3 ? 2 : residual < 7 ? 5 : 10);
  // k * step rather than repeated addition, so 0.3 is 3 * 0.1 and not 0.1 + 0.1 + 0.1.
  std::vector<double> ticks;
  const double tolerance = 1e-9;
  for (double k = std::ceil(lo / step - tolerance); k <= std::floor(hi / step + tolerance); ++k)
    ticks.push_back(k * step);
  return ticks;
}

std::vector<std::size_t> DecimateMinMax(const std::vector<double>& x, const std::vector<double>& y, double x_lo,
                                        double x_hi, int columns) {
  const std::size_t n = std::min(x.size(), y.size());
  std::vector<std::size_t> kept;
  const double scale = x_hi > x_lo ? columns / (x_hi - x_lo) : 0.0;
  // The run of finite points in the current pixel column.
  bool in_run = false, after_gap = false;
  long long column = 0;
  std::size_t first = 0, last = 0, lowest = 0, highest = 0;
  auto flush = [&]() {
    if (!in_run) return;
    std::size_t picks[4] = {first, lowest, highest, last};
    std::sort(picks, picks + 4);
    for (std::size_t k = 0; k < 4; ++k)
      if (k == 0 || picks[k] != picks[k - 1]) kept.push_back(picks[k]);
    in_run = false;
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) {
      flush();
      if (!after_gap) kept.push_back(i);
      after_gap = true;
      continue;
    }
    after_gap = false;
    // Clamped so that a wild x cannot overflow the conversion; such points just share an edge column.
    const long long c = static_cast<long long>(std::floor(std::clamp((x[i] - x_lo) * scale, -1e9, 1e9)));
    if (in_run && c == column) {
      last = i;
      if (y[i] < y[lowest]) lowest = i;
      if (y[i] > y[highest]) highest = i;
    } else {
      flush();
      in_run = true;
      column = c;
      first = last = lowest = highest = i;
    }
  }
  flush();
  return kept;
}

void WriteSvg(const Figure& figure, std::ostream& out) {
  const std::size_t last_sharing = LastSharing(figure);
  Interval shared_x;
  for (const Panel& panel : figure.panels)
    if (panel.x_label.empty()) shared_x.IncludeX(panel);
  shared_x.MakeNonEmpty();
  const Layout layout = Arrange(figure, last_sharing);
  const double width = FigureWidth(figure);
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << Px(width) << "\" height=\"" << Px(layout.height)
      << "\" viewBox=\"0 0 " << Px(width) << " " << Px(layout.height)
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << Px(kLeft + kPlotWidth / 2) << "\" y=\"25\" text-anchor=\"middle\" font-size=\"15\">"
      << EscapeXml(figure.title) << "</text>\n";
  bool spans_labelled = false;  // in the first panel on the shared axis
  for (std::size_t pi = 0; pi < figure.panels.size(); ++pi) {
    const Panel& panel = figure.panels[pi];
    if (panel.x_label.empty()) {
      WritePanel(panel, shared_x, layout.tops[pi], pi == last_sharing ? &figure.x_label : nullptr, figure.spans,
                 !spans_labelled, out);
      spans_labelled = true;
    } else {
      Interval own_x;
      own_x.IncludeX(panel);
      own_x.MakeNonEmpty();
      WritePanel(panel, own_x, layout.tops[pi], &panel.x_label, {}, false, out);
    }
  }
  out << "</svg>\n";
}

}  // namespace drillwave::io
