#pragma once
// What diagnose's and inspect's channel figures share (internal): a recorded channel whose samples masked as
// artefacts are drawn apart from its line, and a panel zoomed on the last few stick-slip cycles.
#include <string>
#include <vector>

#include "drillwave/io/svg_plot.hpp"

namespace drillwave::diagnosis::figure_internal {

inline constexpr const char* kMaskedLabel = "masked (artefact)";  // the legend of the masked samples' dots

// A recorded channel over [from_s, to_s]: a line through the samples kept, broken where one was masked as an
// artefact, and, where any were, the masked samples at their recorded values as muted dots of their own series, so
// that a masked spike is not drawn as motion while the reader still sees where, how many and how large they were.
// `masked` holds one flag per sample (1: masked), or none.
std::vector<io::Series> RecordedSeries(const std::string& label, const std::vector<double>& time_s,
                                       const std::vector<double>& values, const std::vector<char>& masked,
                                       double from_s, double to_s);

// The series' points with x in [from_s, to_s].
io::Series Within(const io::Series& series, double from_s, double to_s);

// The stretch a zoomed panel shows: the last few stick-slip periods of [begin_s, end_s].
struct Zoom {
  double from_s = 0, to_s = 0;
  std::string x_label;  // the time axis with its unit, and what the stretch is
};

// `period_s` NaN (none found) stands for a typical 5 s. `time_label` names the time axis ("time [s]"), `of_what` the
// stretch zoomed into ("held-out window").
Zoom LastCycles(double period_s, double begin_s, double end_s, const std::string& time_label,
                const std::string& of_what);

// A panel of `series` over the zoom's stretch, on a time axis of its own.
io::Panel ZoomPanel(const std::string& y_label, const std::vector<io::Series>& series, const Zoom& zoom);

}  // namespace drillwave::diagnosis::figure_internal
