#pragma once
// Numbers in reports and messages.
#include <sstream>
#include <string>

namespace drillwave {

// Fixed-point with `digits` decimals: Fixed(3.14159, 2) == "3.14".
inline std::string Fixed(double v, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

// Shortest of fixed and scientific with `digits` significant digits: Significant(0.000123456, 3) == "0.000123".
inline std::string Significant(double v, int digits) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

}  // namespace drillwave
