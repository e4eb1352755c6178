#pragma once
// A linearization's rows of a drive's own states against the component the simulation runs (dynamics::TopDrive):
// its rates differentiated by central differences.
#include <algorithm>
#include <cmath>
#include <vector>

#include "drillwave/analysis/spectrum.hpp"
#include "drillwave/dynamics/top_drive.hpp"

namespace drillwave::testing {

// The largest difference, relative to each row's largest entry, between sys.a0's rows of the drive's states (its
// slots: the PI's integral, a DC current, four fluxes, a gear's motor speed and twist) and the drive's rates
// differentiated about the state x, over the columns of those states and of the node's speed (index `speed`); the
// entries compared are added to `compared`. The drive reads no string torque or wave (laws without feedback).
inline double WorstDriveRowDifference(const analysis::LinearDelaySystem& sys, const dynamics::TopDrive& drive,
                                      const dynamics::TopDrive::Slots& slots, int speed, const std::vector<double>& x,
                                      int& compared) {
  auto rate = [&](std::vector<double> state, int c, double h, int r) {
    state[c] += h;
    const auto no_torque = [](double, double) { return 0.0; };
    const auto no_wave = [](double, double) { return dynamics::PiTopDrive::TopWave{}; };
    const auto side = integration::Side::kRight;
    const auto in = drive.Read(state, drive.DriveSpeed(state, state[speed]), 0.0, side, no_torque, no_wave);
    std::vector<double> dx(state.size(), 0.0);
    drive.Rates(state, state[speed], 0.0, side, in, dx);
    return dx[r];
  };
  std::vector<int> rows;
  for (int first : {slots.integral, slots.current, slots.flux, slots.motor_speed})
    for (int k = 0; first >= 0 && k < (first == slots.flux ? 4 : first == slots.motor_speed ? 2 : 1); ++k)
      rows.push_back(first + k);
  std::vector<int> columns = rows;
  columns.push_back(speed);
  double worst = 0;
  for (int r : rows) {
    double scale = 0;
    for (int c : columns) scale = std::max(scale, std::abs(sys.a0(r, c)));
    for (int c : columns) {
      const double h = 1e-6 * (1 + std::abs(x[c]));
      const double fd = (rate(x, c, h, r) - rate(x, c, -h, r)) / (2 * h);
      worst = std::max(worst, std::abs(fd - sys.a0(r, c)) / scale);
      ++compared;
    }
  }
  return worst;
}

}  // namespace drillwave::testing
