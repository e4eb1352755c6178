#include "channel_figure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "drillwave/core/format.hpp"

namespace drillwave::diagnosis::figure_internal {
namespace {

// Grey: the masked samples are what the analysis left out, so they stay behind the channels' colours.
constexpr const char* kMaskedColour = "#9a9a9a";
// A few cycles: enough to compare their shape, few enough to see each stick and slip in 900 px.
constexpr double kZoomPeriods = 4;
constexpr double kTypicalPeriodS = 5;  // a drill string's stick-slip period, where the recording's is unknown

}  // namespace

std::vector<io::Series> RecordedSeries(const std::string& label, const std::vector<double>& time_s,
                                       const std::vector<double>& values, const std::vector<char>& masked,
                                       double from_s, double to_s) {
  io::Series line{label, {}, {}};
  io::Series dots{kMaskedLabel, {}, {}, io::Mark::kDots, kMaskedColour};
  const double gap = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < time_s.size() && i < values.size(); ++i) {
    if (!(time_s[i] >= from_s && time_s[i] <= to_s)) continue;
    const bool is_masked = i < masked.size() && masked[i];
    line.x.push_back(time_s[i]), line.y.push_back(is_masked ? gap : values[i]);
    if (is_masked) dots.x.push_back(time_s[i]), dots.y.push_back(values[i]);
  }
  if (dots.x.empty()) return {line};
  dots.label += ": " + std::to_string(dots.x.size()) + (dots.x.size() == 1 ? " sample" : " samples");
  return {line, dots};
}

io::Series Within(const io::Series& series, double from_s, double to_s) {
  io::Series cut = series;
  cut.x.clear(), cut.y.clear();
  for (std::size_t i = 0; i < series.x.size() && i < series.y.size(); ++i)
    if (series.x[i] >= from_s && series.x[i] <= to_s) cut.x.push_back(series.x[i]), cut.y.push_back(series.y[i]);
  return cut;
}

Zoom LastCycles(double period_s, double begin_s, double end_s, const std::string& time_label,
                const std::string& of_what) {
  const bool known = std::isfinite(period_s) && period_s > 0;
  const double period = known ? period_s : kTypicalPeriodS;
  Zoom zoom{std::max(begin_s, end_s - kZoomPeriods * period), end_s, {}};
  const double shown = zoom.to_s - zoom.from_s;
  zoom.x_label = time_label + ", zoomed on the " + of_what + "'s last " +
                 (known ? Significant(shown / period, 2) + " stick-slip periods (" + Significant(period, 3) + " s each)"
                        : Significant(shown, 3) + " s (no stick-slip period found)");
  return zoom;
}

io::Panel ZoomPanel(const std::string& y_label, const std::vector<io::Series>& series, const Zoom& zoom) {
  io::Panel panel{y_label, {}, zoom.x_label};
  for (const io::Series& s : series) panel.series.push_back(Within(s, zoom.from_s, zoom.to_s));
  return panel;
}

}  // namespace drillwave::diagnosis::figure_internal
