#include "drillwave/io/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace drillwave::io {
namespace {

constexpr double kWidth = 1000, kPanelHeight = 260, kLeft = 80, kRight = 20, kTop = 40, kGap = 50;
const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"};

std::string Escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string Number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", std::abs(v) < 1e-12 ? 0.0 : v);
  return b;
}

// Tick values at 1-2-5 steps covering [lo, hi].
std::vector<double> Ticks(double lo, double hi) {
  const double raw = (hi - lo) / 6;
  const double mag = std::pow(10, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  std::vector<double> ticks;
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * step; t += step) ticks.push_back(t);
  return ticks;
}

void Range(const std::vector<double>& v, double& lo, double& hi) {
  for (double x : v)
    if (std::isfinite(x)) lo = std::min(lo, x), hi = std::max(hi, x);
}

void Widen(double& lo, double& hi) {
  if (!(lo <= hi)) lo = 0, hi = 1;
  if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) lo -= 0.5, hi += 0.5;
  const double pad = 0.05 * (hi - lo);
  lo -= pad, hi += pad;
}

}  // namespace

void WriteSvg(const Figure& figure, std::ostream& out) {
  const double plot_w = kWidth - kLeft - kRight;
  const double height = kTop + figure.panels.size() * (kPanelHeight + kGap) + 20;
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  for (const Panel& p : figure.panels)
    for (const Series& s : p.series) Range(s.x, x_lo, x_hi);
  if (!(x_lo < x_hi)) x_lo = 0, x_hi = 1;
  auto px = [&](double x) { return kLeft + (x - x_lo) / (x_hi - x_lo) * plot_w; };

  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out << "<text x=\"" << kWidth / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" << Escape(figure.title)
      << "</text>\n";
  for (std::size_t pi = 0; pi < figure.panels.size(); ++pi) {
    const Panel& panel = figure.panels[pi];
    const double top = kTop + pi * (kPanelHeight + kGap), bottom = top + kPanelHeight;
    double y_lo = std::numeric_limits<double>::infinity(), y_hi = -y_lo;
    for (const Series& s : panel.series) Range(s.y, y_lo, y_hi);
    Widen(y_lo, y_hi);
    auto py = [&](double y) { return bottom - (y - y_lo) / (y_hi - y_lo) * kPanelHeight; };
    out << "<rect x=\"" << kLeft << "\" y=\"" << top << "\" width=\"" << plot_w << "\" height=\"" << kPanelHeight
        << "\" fill=\"none\" stroke=\"#444\"/>\n";
    for (double t : Ticks(y_lo, y_hi)) {
      out << "<line x1=\"" << kLeft << "\" x2=\"" << kLeft + plot_w << "\" y1=\"" << py(t) << "\" y2=\"" << py(t)
          << "\" stroke=\"#ddd\"/><text x=\"" << kLeft - 5 << "\" y=\"" << py(t) + 4 << "\" text-anchor=\"end\">"
          << Number(t) << "</text>\n";
    }
    for (double t : Ticks(x_lo, x_hi)) {
      out << "<line x1=\"" << px(t) << "\" x2=\"" << px(t) << "\" y1=\"" << top << "\" y2=\"" << bottom
          << "\" stroke=\"#eee\"/><text x=\"" << px(t) << "\" y=\"" << bottom + 15 << "\" text-anchor=\"middle\">"
          << Number(t) << "</text>\n";
    }
    out << "<text transform=\"translate(18," << (top + bottom) / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
        << Escape(panel.y_label) << "</text>\n";
    if (pi + 1 == figure.panels.size())
      out << "<text x=\"" << kLeft + plot_w / 2 << "\" y=\"" << bottom + 32 << "\" text-anchor=\"middle\">"
          << Escape(figure.x_label) << "</text>\n";
    for (std::size_t si = 0; si < panel.series.size(); ++si) {
      const Series& s = panel.series[si];
      const char* colour = kColours[si % 6];
      // Min and max per pixel column, in the order they occur.
      out << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1\" points=\"";
      const std::size_t n = std::min(s.x.size(), s.y.size());
      long column = -1;
      std::size_t i_min = 0, i_max = 0;
      bool open = false;
      auto flush = [&]() {
        if (column < 0) return;
        const std::size_t a = std::min(i_min, i_max), b = std::max(i_min, i_max);
        out << px(s.x[a]) << "," << py(s.y[a]) << " ";
        if (b != a) out << px(s.x[b]) << "," << py(s.y[b]) << " ";
      };
      for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(s.y[i]) || !std::isfinite(s.x[i])) {  // a gap: close this polyline, open another
          flush();
          column = -1;
          out << "\"/>\n<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1\" points=\"";
          continue;
        }
        const long c = static_cast<long>(std::floor(px(s.x[i])));
        if (c != column) {
          flush();
          column = c;
          i_min = i_max = i;
        } else {
          if (s.y[i] < s.y[i_min]) i_min = i;
          if (s.y[i] > s.y[i_max]) i_max = i;
        }
        open = true;
      }
      flush();
      (void)open;
      out << "\"/>\n";
      out << "<rect x=\"" << kLeft + plot_w - 170 << "\" y=\"" << top + 8 + 16 * si << "\" width=\"12\" height=\"3\" fill=\""
          << colour << "\"/><text x=\"" << kLeft + plot_w - 152 << "\" y=\"" << top + 13 + 16 * si << "\">"
          << Escape(s.label) << "</text>\n";
    }
  }
  out << "</svg>\n";
}

}  // namespace drillwave::io
