// The cut delay t_n of bitrock::CutProfile: Phi(t) - Phi(t - t_n) = 2 pi / n on a stored bit angle with a known
// closed form, through rotation that speeds up and slows down, and through a stuck interval (where the Newton start
// has no slope and the bracketing search takes over); and the depth of cut n (U(t) - U(t - t_n)) with it.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/bitrock/rgd.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/integration/options.hpp"

namespace drillwave::bitrock {
namespace {

constexpr int kBlades = 5;
constexpr double kOmega = 2 * kPi, kRop = 0.01;  // 60 rpm, 36 m/h

// Bit angle: steady rotation with a 30 % speed oscillation, stuck over [2.0, 2.3] s (the angle held there).
constexpr double kStickBegin = 2.0, kStickEnd = 2.3;
double MovingAngle(double t) { return kOmega * t + 0.3 * kOmega / 3.0 * std::sin(3.0 * t); }
double Angle(double t) {
  if (t < kStickBegin) return MovingAngle(t);
  if (t < kStickEnd) return MovingAngle(kStickBegin);
  return MovingAngle(t - (kStickEnd - kStickBegin));
}
double AngleRate(double t) {
  if (t >= kStickBegin && t < kStickEnd) return 0.0;
  const double s = t < kStickBegin ? t : t - (kStickEnd - kStickBegin);
  return kOmega * (1 + 0.3 * std::cos(3.0 * s));
}
double Position(double t) { return kRop * t + 1e-4 * std::sin(7.0 * t); }
double PositionRate(double t) { return kRop + 7e-4 * std::cos(7.0 * t); }

// Time at which the angle stood `back` behind Angle(t), by bisection on the closed form (the angle never decreases).
double ExactTimeBehind(double t, double back) {
  const double target = Angle(t) - back;
  double lo = t - 10.0, hi = t;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (Angle(mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(CutProfile, CutDelayAndDepthFollowTheStoredAngleThroughSpeedChangesAndAStick) {
  CutProfile profile(kBlades, kOmega, kRop);
  const double h = 1e-3;
  int checked = 0;
  double worst_tn = 0, worst_depth = 0;
  for (int k = 0; k < 4000; ++k) {
    // Steps that end on the stick's ends, as the integrator's events make them.
    const double t0 = k * h, t1 = (k + 1) * h, tm = 0.5 * (t0 + t1);
    const std::vector<double> x0{Angle(t0), Position(t0)}, x1{Angle(t1), Position(t1)}, xm{Angle(tm), Position(tm)};
    const std::vector<double> f0{AngleRate(t0), PositionRate(t0)}, f1{AngleRate(t1 - 1e-15), PositionRate(t1)};
    profile.Commit(integration::Piece{t0, t1, x0, f0, x1, f1, xm}, 0, 1, true, -1e9, 10.0);
    if (t1 < 1.0 || k % 7 != 0) continue;
    // Within the next step, as the integrator's stages ask.
    const double t = t1 + 0.37 * h;
    double tn = 0;
    const double depth = profile.DepthOfCut(Angle(t), Position(t), t, integration::Side::kLeft, true, -1e9, &tn);
    const double exact_behind = ExactTimeBehind(t, 2 * kPi / kBlades);
    worst_tn = std::max(worst_tn, std::abs((t - tn) - exact_behind));
    worst_depth = std::max(worst_depth, std::abs(depth - kBlades * (Position(t) - Position(exact_behind))));
    ++checked;
  }
  std::printf("[ measured ] %d look-ups: t_n within %.2e s, depth of cut within %.2e m\n", checked, worst_tn,
              worst_depth);
  EXPECT_GT(checked, 400);
  // The stored quartics of 1 ms pieces miss the closed form by ~1e-13 rad; over the stick's ends (a kink in the
  // angle) by more, and t_n is the angle's error over the speed.
  EXPECT_LT(worst_tn, 1e-9);
  EXPECT_LT(worst_depth, 1e-10);
}

}  // namespace
}  // namespace drillwave::bitrock
