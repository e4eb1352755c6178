#pragma once
// The quartic every stored piece of solution or history is: the cubic Hermite interpolant of the ends' values and
// derivatives, plus a bubble b s^2 (1 - s)^2 that puts it through the midpoint value (s = (t - t0) / h in [0, 1]).
// One formula for the simulator's output sampling (Piece), HermiteHistory and the error checks.
namespace drillwave::integration {

// How far the cubic Hermite interpolant misses the midpoint value: the error of a stored cubic, which the simulator
// checks on the state.
inline double CubicMidpointMiss(double h, double x0, double x1, double d0, double d1, double x_mid) {
  const double cubic_mid = 0.5 * (x0 + x1) + 0.125 * h * (d0 - d1);
  return x_mid - cubic_mid;
}

// The bubble's weight that makes the quartic pass through x_mid at s = 1/2 (s^2 (1-s)^2 = 1/16 there).
inline double BubbleWeight(double h, double x0, double x1, double d0, double d1, double x_mid) {
  return 16.0 * CubicMidpointMiss(h, x0, x1, d0, d1, x_mid);
}

inline double QuarticValue(double s, double h, double x0, double x1, double d0, double d1, double b) {
  const double s2 = s * s, s3 = s2 * s, r = 1 - s;
  return (2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * h * d0 + (-2 * s3 + 3 * s2) * x1 + (s3 - s2) * h * d1 +
         b * s2 * r * r;
}

inline double QuarticDerivative(double s, double h, double x0, double x1, double d0, double d1, double b) {
  const double s2 = s * s;
  return ((6 * s2 - 6 * s) * x0 + (-6 * s2 + 6 * s) * x1 + b * 2 * s * (1 - s) * (1 - 2 * s)) / h +
         (3 * s2 - 4 * s + 1) * d0 + (3 * s2 - 2 * s) * d1;
}

inline double QuarticSecondDerivative(double s, double h, double x0, double x1, double d0, double d1, double b) {
  return ((12 * s - 6) * (x0 - x1) / h + (6 * s - 4) * d0 + (6 * s - 2) * d1) / h +
         b * (2 - 12 * s + 12 * s * s) / (h * h);
}

}  // namespace drillwave::integration
