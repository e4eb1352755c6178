#pragma once
// Mathematical constants and the unit conversions every part of drillwave shares, so that no file defines its own
// (M_PI is POSIX, not standard C++; C++20's std::numbers would serve once the project moves to it).
namespace drillwave {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kRadPerSecondPerRpm = kPi / 30;  // one revolution per minute in rad/s

}  // namespace drillwave
