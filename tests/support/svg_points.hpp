#pragma once
// Reading an SVG the plot writer made, for tests: the pixel points of its polylines.
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace drillwave::testing {

// The "points" attributes of all polylines, as (x, y) pixel pairs.
inline std::vector<std::pair<double, double>> PolylinePoints(const std::string& svg) {
  std::vector<std::pair<double, double>> points;
  const std::string key = "points=\"";
  for (std::size_t at = svg.find(key); at != std::string::npos; at = svg.find(key, at + 1)) {
    const char* p = svg.c_str() + at + key.size();
    while (*p != '"') {
      char* end = nullptr;
      const double x = std::strtod(p, &end);
      const double y = std::strtod(end + 1, &end);  // past ','
      points.emplace_back(x, y);
      p = end;
      while (*p == ' ') ++p;
    }
  }
  return points;
}

}  // namespace drillwave::testing
