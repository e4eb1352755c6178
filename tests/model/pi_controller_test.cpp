// The PI speed controller shared by every kind's top drive.
#include "drillwave/model/pi_controller.hpp"

#include <gtest/gtest.h>

namespace drillwave::model {
namespace {

TEST(PiController, OutputIsProportionalToTheErrorPlusTheIntegralPart) {
  const PiController pi{2000, 500};
  EXPECT_DOUBLE_EQ(pi.Proportional(10, 8), 4000);
  EXPECT_DOUBLE_EQ(pi.Output(10, 8, 3), 4000 + 1500);
  EXPECT_DOUBLE_EQ(pi.Output(10, 12, 0), -4000);  // overspeed brakes
}

TEST(PiController, TheHoldingIntegralKeepsTheOutputAtZeroError) {
  const PiController pi{2000, 500};
  EXPECT_DOUBLE_EQ(pi.Output(10, 10, pi.IntegralHolding(12000)), 12000);
  // Without integral action no integral holds an output; the start then carries none.
  const PiController proportional{2000, 0};
  EXPECT_EQ(proportional.IntegralHolding(12000), 0.0);
  EXPECT_DOUBLE_EQ(proportional.Output(10, 10, 7), 0.0);
}

}  // namespace
}  // namespace drillwave::model
