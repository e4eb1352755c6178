#pragma once
// A small dependency-free SVG line plot: panels stacked over a shared time axis, for the runner's quick look.
#include <ostream>
#include <string>
#include <vector>

namespace drillwave::io {

struct Series {
  std::string label;
  std::vector<double> x, y;
};
struct Panel {
  std::string y_label;
  std::vector<Series> series;
};
struct Figure {
  std::string title;
  std::string x_label;
  std::vector<Panel> panels;
};

// Long series are reduced to the minimum and maximum per pixel column, so stick–slip spikes survive; NaN breaks a
// line.
void WriteSvg(const Figure& figure, std::ostream& out);

}  // namespace drillwave::io
