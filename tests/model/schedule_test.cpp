// model::Schedule: piecewise-linear inputs and the breakpoints they put into a run.
#include "drillwave/model/schedule.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace drillwave::model {
namespace {

TEST(Schedule, ValuesAndLeftLimitsAtAJump) {
  const Schedule s({{0.0, 1.0}, {1.0, 3.0}, {1.0, 5.0}, {2.0, 5.0}});
  EXPECT_DOUBLE_EQ(s.Value(0.5), 2.0);
  EXPECT_DOUBLE_EQ(s.ValueBefore(1.0), 3.0);
  EXPECT_DOUBLE_EQ(s.Value(1.0), 5.0);
  EXPECT_DOUBLE_EQ(s.Slope(0.5), 2.0);
  EXPECT_DOUBLE_EQ(s.Value(-1.0), 1.0);  // constant before the first knot and after the last
  EXPECT_DOUBLE_EQ(s.Value(9.0), 5.0);
}

TEST(Schedule, NextKnotAfterIsTheFirstKnotLaterThanTheTime) {
  const Schedule s({{0.0, 1.0}, {1.0, 3.0}, {1.0, 5.0}, {2.5, 5.0}});
  EXPECT_DOUBLE_EQ(s.NextKnotAfter(-1.0), 0.0);
  EXPECT_DOUBLE_EQ(s.NextKnotAfter(0.0), 1.0);  // strictly later: a run standing on a knot moves on to the next
  EXPECT_DOUBLE_EQ(s.NextKnotAfter(0.3), 1.0);
  EXPECT_DOUBLE_EQ(s.NextKnotAfter(1.0), 2.5);  // past both knots of the jump
  EXPECT_TRUE(std::isinf(s.NextKnotAfter(2.5)));
  EXPECT_TRUE(std::isinf(Schedule(4.0).NextKnotAfter(1.0)));  // a constant's only knot is at 0
  EXPECT_DOUBLE_EQ(Schedule(4.0).NextKnotAfter(-1.0), 0.0);
}

}  // namespace
}  // namespace drillwave::model
