// The stick/slip component every kind uses (bit of the coupled kind, nodes of the wave network, lumped inertias):
// the regime at rest, the witnesses' signs and zeros, and the agreement between "breaks free through witness k" and
// "the regime at rest just past the limit".
#include "drillwave/bitrock/stick_slip.hpp"

#include <gtest/gtest.h>

namespace drillwave::bitrock {
namespace {

constexpr StaticRange kRange{3.0, 2.0};  // holds drive in [-2, 3]

TEST(StickSlip, AContactAtRestSticksInsideTheStaticRangeIncludingItsEnds) {
  EXPECT_EQ(TurnAtRest({0.0, kRange}), Turn::kStuck);
  EXPECT_EQ(TurnAtRest({3.0, kRange}), Turn::kStuck);
  EXPECT_EQ(TurnAtRest({-2.0, kRange}), Turn::kStuck);
  EXPECT_EQ(TurnAtRest({3.0000001, kRange}), Turn::kForward);
  EXPECT_EQ(TurnAtRest({-2.0000001, kRange}), Turn::kBackward);
  // An empty range (frictionless contact) never holds a non-zero torque.
  EXPECT_EQ(TurnAtRest({1e-12, {0.0, 0.0}}), Turn::kForward);
  EXPECT_EQ(TurnAtRest({0.0, {0.0, 0.0}}), Turn::kStuck);
}

TEST(StickSlip, TheIntegerValueOfARegimeIsItsSlipDirection) {
  EXPECT_EQ(static_cast<int>(Turn::kForward), 1);
  EXPECT_EQ(static_cast<int>(Turn::kStuck), 0);
  EXPECT_EQ(static_cast<int>(Turn::kBackward), -1);
}

TEST(StickSlip, ASlippingContactsWitnessIsItsSpeedInTheSlipDirectionAndNeedsNoForces) {
  int evaluations = 0;
  const auto at_rest = [&] { return ++evaluations, AtRest{0.0, kRange}; };
  EXPECT_EQ(TurnWitness(Turn::kForward, 0, 2.5, at_rest), 2.5);
  EXPECT_EQ(TurnWitness(Turn::kForward, 0, -0.5, at_rest), -0.5);  // overshot: the event lies behind
  EXPECT_EQ(TurnWitness(Turn::kBackward, 0, -2.5, at_rest), 2.5);
  EXPECT_GT(TurnWitness(Turn::kForward, 1, 0.0, at_rest), 0.0);
  EXPECT_GT(TurnWitness(Turn::kBackward, 1, 0.0, at_rest), 0.0);
  EXPECT_EQ(evaluations, 0);
}

TEST(StickSlip, AStuckContactsWitnessesAreTheMarginsToTheStaticLimits) {
  for (const double drive : {-2.5, -2.0, -1.0, 0.0, 2.0, 3.0, 3.5}) {
    const auto at_rest = [&] { return AtRest{drive, kRange}; };
    EXPECT_DOUBLE_EQ(TurnWitness(Turn::kStuck, 0, 0.0, at_rest), 3.0 - drive) << drive;
    EXPECT_DOUBLE_EQ(TurnWitness(Turn::kStuck, 1, 0.0, at_rest), drive + 2.0) << drive;
  }
}

// Sweeping the drive across both limits: the witness that turns negative first, broken free through, gives the
// regime that TurnAtRest gives just past that limit; inside the range both witnesses stay non-negative.
TEST(StickSlip, BreakingFreeThroughAWitnessAgreesWithTheRegimeAtRestPastItsLimit) {
  for (int j = -400; j <= 400; ++j) {
    const double drive = 0.01 * j;
    const auto at_rest = [&] { return AtRest{drive, kRange}; };
    const double w0 = TurnWitness(Turn::kStuck, 0, 0.0, at_rest), w1 = TurnWitness(Turn::kStuck, 1, 0.0, at_rest);
    const Turn at_rest_turn = TurnAtRest(at_rest());
    if (w0 >= 0 && w1 >= 0) {
      EXPECT_EQ(at_rest_turn, Turn::kStuck) << drive;
    } else {
      ASSERT_TRUE((w0 < 0) != (w1 < 0)) << drive;  // a range of positive width: one limit at a time
      EXPECT_EQ(TurnBreakingFree(w0 < 0 ? 0 : 1), at_rest_turn) << drive;
    }
  }
}

// After an event: a stuck contact breaks free without the forces being evaluated; a slipping one is held first and
// then stays (inside the range) or reverses (beyond it).
TEST(StickSlip, AfterAnEventAStuckContactBreaksFreeAndASlippingOneIsHeldThenStaysOrReverses) {
  int holds = 0;
  double drive = 0;
  const auto hold = [&] { return ++holds, AtRest{drive, kRange}; };
  EXPECT_EQ(TurnAfterEvent(Turn::kStuck, 0, hold), Turn::kForward);
  EXPECT_EQ(TurnAfterEvent(Turn::kStuck, 1, hold), Turn::kBackward);
  EXPECT_EQ(holds, 0);
  EXPECT_EQ(TurnAfterEvent(Turn::kForward, 0, hold), Turn::kStuck);
  drive = -2.5;
  EXPECT_EQ(TurnAfterEvent(Turn::kForward, 0, hold), Turn::kBackward);
  drive = 3.5;
  EXPECT_EQ(TurnAfterEvent(Turn::kBackward, 0, hold), Turn::kForward);
  EXPECT_EQ(holds, 3);
}

}  // namespace
}  // namespace drillwave::bitrock
