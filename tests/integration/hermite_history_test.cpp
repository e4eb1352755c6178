// HermiteHistory: the dense store that delayed look-ups read. Each piece is fixed by end values, end derivatives
// and the midpoint value, so it must reproduce any quartic; boundaries keep both one-sided limits; look-ups a few
// ulps off a boundary (times computed as (t + tau) - tau) must land on it.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/integration/hermite_history.hpp"

namespace drillwave::integration {
namespace {

// q(t) = 0.3 - 1.2 t + 0.7 t^2 + 2.1 t^3 - 0.9 t^4 and a second component, to check components stay apart.
double Q(double t) { return 0.3 + t * (-1.2 + t * (0.7 + t * (2.1 - 0.9 * t))); }
double DQ(double t) { return -1.2 + t * (1.4 + t * (6.3 - 3.6 * t)); }
double R(double t) { return -2.0 + t * t * t * t; }
double DR(double t) { return 4 * t * t * t; }

void AppendExact(HermiteHistory& h, double t0, double t1) {
  const double x0[] = {Q(t0), R(t0)}, d0[] = {DQ(t0), DR(t0)};
  const double x1[] = {Q(t1), R(t1)}, d1[] = {DQ(t1), DR(t1)};
  const double xm[] = {Q(0.5 * (t0 + t1)), R(0.5 * (t0 + t1))};
  h.Append(t0, x0, d0, t1, x1, d1, xm);
}

TEST(HermiteHistory, ReproducesAQuarticFromEndsAndMidpoint) {
  HermiteHistory h(2);
  AppendExact(h, 0.5, 1.75);
  double worst_value = 0, worst_derivative = 0;
  for (int i = 0; i <= 200; ++i) {
    // Beyond 1.75 the last piece is extrapolated (what vanishing delays read): still the same quartic.
    const double t = 0.5 + 1.5 * i / 200;
    double both[2];
    h.Values(t, both);
    worst_value = std::max({worst_value, std::abs(h.Value(t, 0) - Q(t)), std::abs(both[0] - Q(t)),
                            std::abs(h.Value(t, 1) - R(t)), std::abs(both[1] - R(t))});
    worst_derivative = std::max({worst_derivative, std::abs(h.Derivative(t, 0) - DQ(t)),
                                 std::abs(h.Derivative(t, 1) - DR(t))});
  }
  // Values are O(1..10) on [0.5, 2]: agreement to rounding.
  EXPECT_LE(worst_value, 1e-13);
  EXPECT_LE(worst_derivative, 1e-12);
  EXPECT_EQ(h.num_pieces(), 1u);
  EXPECT_EQ(h.begin_time(), 0.5);
  EXPECT_EQ(h.end_time(), 1.75);
}

// Two pieces with a jump in value and derivative at t = 1.
HermiteHistory JumpAtOne() {
  HermiteHistory h(1);
  const double a0 = 0, a1 = 1, da = 1, am = 0.5;  // u = t on [0, 1]
  const double b0 = 5, b1 = 6, db0 = 2, db1 = 0, bm = 5.6;
  h.Append(0, &a0, &da, 1, &a1, &da, &am);
  h.Append(1, &b0, &db0, 2, &b1, &db1, &bm);
  return h;
}

TEST(HermiteHistory, BoundaryKeepsBothOneSidedLimits) {
  const HermiteHistory h = JumpAtOne();
  EXPECT_EQ(h.Value(1, 0, Side::kLeft), 1.0);
  EXPECT_EQ(h.Value(1, 0, Side::kRight), 5.0);
  EXPECT_EQ(h.Value(1, 0), 5.0);  // right limit by default
  EXPECT_EQ(h.Derivative(1, 0, Side::kLeft), 1.0);
  EXPECT_EQ(h.Derivative(1, 0, Side::kRight), 2.0);
  // Inside a piece the side does not matter.
  EXPECT_EQ(h.Value(0.25, 0, Side::kLeft), h.Value(0.25, 0, Side::kRight));
  EXPECT_NEAR(h.Value(0.25, 0), 0.25, 1e-15);
}

TEST(HermiteHistory, QueryOneUlpOffABoundarySnapsToIt) {
  const HermiteHistory h = JumpAtOne();
  const double above = std::nextafter(1.0, 2.0), below = std::nextafter(1.0, 0.0);
  // Without snapping, `above` would be read from the right piece whatever the side asked for.
  EXPECT_EQ(h.Value(above, 0, Side::kLeft), 1.0);
  EXPECT_EQ(h.Value(above, 0, Side::kRight), 5.0);
  EXPECT_EQ(h.Value(below, 0, Side::kLeft), 1.0);
  EXPECT_EQ(h.Value(below, 0, Side::kRight), 5.0);
  EXPECT_EQ(h.Derivative(below, 0, Side::kRight), 2.0);
  // The typical case: a boundary at t reached again as (t + tau) - tau.
  const double tau = 0.1, t = (1.0 + tau) - tau;
  EXPECT_EQ(h.Value(t, 0, Side::kLeft), 1.0);
}

TEST(HermiteHistory, PrehistoryServesTimesBeforeTheFirstPiece) {
  HermiteHistory h(1, [](double t, double* x, double* d) {
    x[0] = std::sin(t);
    d[0] = std::cos(t);
  });
  EXPECT_EQ(h.Value(-0.7, 0), std::sin(-0.7));  // empty: everything is prehistory
  const double x0 = 0, d0 = 5, x1 = 5, d1 = 5, xm = 2.5;  // u = 5 t on [0, 1]: d0 differs from phi'(0) = 1
  h.Append(0, &x0, &d0, 1, &x1, &d1, &xm);
  EXPECT_EQ(h.Value(-0.7, 0), std::sin(-0.7));
  EXPECT_EQ(h.Derivative(-0.7, 0), std::cos(-0.7));
  // At the start of the history the left limit is the prehistory's, the right limit the first piece's.
  EXPECT_EQ(h.Derivative(0, 0, Side::kLeft), 1.0);
  EXPECT_EQ(h.Derivative(0, 0, Side::kRight), 5.0);
  EXPECT_NEAR(h.Value(0.5, 0), 2.5, 1e-15);
}

TEST(HermiteHistory, DiscardBeforeKeepsLaterValues) {
  // 3000 pieces of sin on [0, 30]; discarding before 25 drops more than half, which also compacts the storage.
  HermiteHistory h(1);
  const double step = 0.01;
  auto append = [&](int k) {
    const double t0 = k * step, t1 = (k + 1) * step, tm = 0.5 * (t0 + t1);
    const double x0 = std::sin(t0), d0 = std::cos(t0), x1 = std::sin(t1), d1 = std::cos(t1), xm = std::sin(tm);
    h.Append(t0, &x0, &d0, t1, &x1, &d1, &xm);
  };
  for (int k = 0; k < 3000; ++k) append(k);
  std::vector<double> times, before;
  for (int i = 0; i <= 500; ++i) times.push_back(25.0 + 5.0 * i / 500);
  times.push_back(25.003);  // inside the piece that contains the cut
  for (double t : times) before.push_back(h.Value(t, 0));

  h.DiscardBefore(25.0);
  EXPECT_LE(h.begin_time(), 25.0);
  EXPECT_GT(h.begin_time(), 24.9);
  EXPECT_LT(h.num_pieces(), 600u);
  for (std::size_t i = 0; i < times.size(); ++i) EXPECT_EQ(h.Value(times[i], 0), before[i]) << "t " << times[i];

  // Appending continues seamlessly after the compaction.
  for (int k = 3000; k < 3100; ++k) append(k);
  EXPECT_NEAR(h.Value(30.5, 0), std::sin(30.5), 1e-12);
  EXPECT_EQ(h.Value(27.0, 0), before[200]);
}

// |t - 1| + 0.1 t^2 in one component (a kink at 1 and at 2.5 after a jump of slope), smooth in the other: KinksIn
// reports exactly the knots where a component's slope or value jumps, with the jumps, and only in [a, b): the first
// piece's start against the prehistory (at rest: value and slope 0) too, while it is kept; the index survives the
// compaction of DiscardBefore.
TEST(HermiteHistory, KinksInFindsTheKnotsWhereASlopeJumps) {
  HermiteHistory h(2);
  auto slope = [](double t, bool right) { return (t > 1 || (t == 1 && right) ? 1.0 : -1.0) + 0.2 * t +
                                                 (t > 2.5 || (t == 2.5 && right) ? 3.0 : 0.0); };
  auto value = [](double t) { return std::abs(t - 1) + 0.1 * t * t + (t > 2.5 ? 3.0 * (t - 2.5) : 0.0); };
  const double step = 0.25;
  for (int k = 0; k < 2400; ++k) {
    const double t0 = k * step, t1 = t0 + step, tm = t0 + 0.5 * step;
    const double x0[] = {value(t0), std::sin(t0)}, d0[] = {slope(t0, true), std::cos(t0)};
    const double x1[] = {value(t1), std::sin(t1)}, d1[] = {slope(t1, false), std::cos(t1)};
    const double xm[] = {value(tm), std::sin(tm)};
    h.Append(t0, x0, d0, t1, x1, d1, xm);
  }
  std::vector<HermiteHistory::Kink> kinks;
  h.KinksIn(0.0, 10.0, 0, kinks);
  ASSERT_EQ(kinks.size(), 3u);
  EXPECT_EQ(kinks[0].time_s, 0.0);  // the start, out of the prehistory's rest: |0 - 1| = 1 at slope -1
  EXPECT_EQ(kinks[0].value_jump, 1.0);
  EXPECT_EQ(kinks[0].slope_jump, -1.0);
  kinks.erase(kinks.begin());
  EXPECT_EQ(kinks[0].time_s, 1.0);
  EXPECT_EQ(kinks[0].value_jump, 0.0);
  EXPECT_NEAR(kinks[0].slope_jump, 2.0, 1e-15);
  EXPECT_EQ(kinks[1].time_s, 2.5);
  EXPECT_NEAR(kinks[1].slope_jump, 3.0, 1e-15);
  kinks.clear();
  // The smooth component: the start (slope 1 out of rest); at the other component's knots nothing but the quartics'
  // own curvature mismatch (sin t in pieces of 0.25: below 1e-3).
  h.KinksIn(0.0, 10.0, 1, kinks);
  ASSERT_EQ(kinks.size(), 3u);
  EXPECT_EQ(kinks[0].value_jump, 0.0);
  EXPECT_EQ(kinks[0].slope_jump, 1.0);
  for (std::size_t k = 1; k < 3; ++k) {
    EXPECT_EQ(kinks[k].value_jump, 0.0);
    EXPECT_EQ(kinks[k].slope_jump, 0.0);
    EXPECT_LT(std::abs(kinks[k].curvature_jump), 1e-3);
  }
  kinks.clear();
  h.KinksIn(1.0, 2.5, 0, kinks);  // [a, b): the first only
  ASSERT_EQ(kinks.size(), 1u);
  EXPECT_EQ(kinks[0].time_s, 1.0);
  kinks.clear();
  h.KinksIn(1.1, 2.5, 0, kinks);
  EXPECT_TRUE(kinks.empty());

  // After a compaction past both kinks, a new one is still found, at its place, with a jump of value.
  h.DiscardBefore(400.0);
  const double t0 = 600.0, t1 = 600.25;
  const double x0[] = {value(t0) + 0.5, std::sin(t0)}, d0[] = {slope(t0, true) - 1.5, std::cos(t0)};
  const double x1[] = {value(t0) + 0.25 * d0[0], std::sin(t1)}, d1[] = {d0[0], std::cos(t1)};
  const double xm[] = {value(t0) + 0.125 * d0[0], std::sin(t0 + 0.125)};
  h.Append(t0, x0, d0, t1, x1, d1, xm);
  h.KinksIn(0.0, 1000.0, 0, kinks);
  ASSERT_EQ(kinks.size(), 1u);
  EXPECT_EQ(kinks[0].time_s, 600.0);
  EXPECT_NEAR(kinks[0].slope_jump, -1.5, 1e-12);
  EXPECT_NEAR(kinks[0].value_jump, 0.5, 1e-12);
}

// (t - 1)^2 / 2 after t = 1, 0 before: value and slope continue at 1, the curvature jumps by 1. A knot is indexed
// there only when its piece is appended as a restart (an event's), and then KinksIn gives the jump exactly (the
// quartics hold quadratics exactly).
TEST(HermiteHistory, ARestartedPieceShowsItsCurvatureJump) {
  auto value = [](double t) { return t > 1 ? 0.5 * (t - 1) * (t - 1) : 0.0; };
  auto slope = [](double t) { return t > 1 ? t - 1 : 0.0; };
  for (bool restart : {false, true}) {
    HermiteHistory h(1);
    for (int k = 0; k < 8; ++k) {
      const double t0 = 0.25 * k, t1 = t0 + 0.25, x0 = value(t0), x1 = value(t1), d0 = slope(t0), d1 = slope(t1),
                   xm = value(t0 + 0.125);
      h.Append(t0, &x0, &d0, t1, &x1, &d1, &xm, restart && t0 == 1.0);
    }
    std::vector<HermiteHistory::Kink> kinks;
    h.KinksIn(0.5, 2.0, 0, kinks);
    if (!restart) {
      EXPECT_TRUE(kinks.empty());
      continue;
    }
    ASSERT_EQ(kinks.size(), 1u);
    EXPECT_EQ(kinks[0].time_s, 1.0);
    EXPECT_EQ(kinks[0].value_jump, 0.0);
    EXPECT_EQ(kinks[0].slope_jump, 0.0);
    EXPECT_NEAR(kinks[0].curvature_jump, 1.0, 1e-12);
  }
}

}  // namespace
}  // namespace drillwave::integration
