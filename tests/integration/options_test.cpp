// IntegratorOptions::IsValid: the defaults pass, each field out of its range is named (SolveDelayProblem refuses them
// with a ParameterError: delay_solver_test.cpp).
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/integration/options.hpp"
#include "invalid_field.hpp"

namespace drillwave::integration {
namespace {

using testing::InvalidField;
using testing::InvalidFieldWith;

TEST(IntegratorOptions, TheDefaultsAreValidAndEachBadFieldIsNamed) {
  const IntegratorOptions o;
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(InvalidField(o), "");
  EXPECT_EQ(InvalidFieldWith(o, [&](auto& b) { b.max_step = b.max_planned_steps = inf; }), "");  // no limits
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.abs_tol = 0; }), "abs_tol");
  EXPECT_EQ(InvalidFieldWith(o, [&](auto& b) { b.rel_tol = nan; }), "rel_tol");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.initial_step = -1e-4; }), "initial_step");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.max_step = 0; }), "max_step");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.event_time_tol = 0; }), "event_time_tol");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.max_events_at_one_instant = 0; }), "max_events_at_one_instant");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.history_step_floor = -1; }), "history_step_floor");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.max_steps = -1; }), "max_steps");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.max_evaluations = -1; }), "max_evaluations");
  EXPECT_EQ(InvalidFieldWith(o, [&](auto& b) { b.max_planned_steps = nan; }), "max_planned_steps");
  IntegratorOptions negative;
  negative.abs_tol = -1e-8;
  std::string message;
  InvalidField(negative, &message);
  EXPECT_EQ(message, "abs_tol: expected a finite number > 0, got -1e-08");
}

}  // namespace
}  // namespace drillwave::integration
