// The options structs' IsValid contract (core/validity.hpp): a refused field is named by its parameter, with its value
// and what was expected; a nested struct's field by both names; an entry point turns the message into the
// ParameterError a front end names its own way.
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/core/validity.hpp"

namespace drillwave {
namespace {

// The message a check writes ("" when it passes).
template <class Check>
std::string MessageOf(const Check& check) {
  std::string error;
  return check(&error) ? "" : error;
}

TEST(Validity, AFieldCheckNamesTheParameterItsValueAndTheRange) {
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(MessageOf([](std::string* e) { return PositiveField(e, "abs_tol", 1e-8); }), "");
  EXPECT_EQ(MessageOf([](std::string* e) { return PositiveField(e, "abs_tol", 0); }),
            "abs_tol: expected a finite number > 0, got 0");
  EXPECT_EQ(MessageOf([&](std::string* e) { return PositiveField(e, "abs_tol", inf); }),
            "abs_tol: expected a finite number > 0, got inf");
  EXPECT_EQ(MessageOf([&](std::string* e) { return FiniteField(e, "model_time_offset_s", nan); }),
            "model_time_offset_s: expected a finite number, got nan");
  EXPECT_EQ(MessageOf([](std::string* e) { return NonNegativeField(e, "stuck_floor", -2); }),
            "stuck_floor: expected a finite number >= 0, got -2");
  EXPECT_EQ(MessageOf([](std::string* e) { return FractionField(e, "margin", 1); }),
            "margin: expected a fraction in [0, 1), got 1");
  EXPECT_EQ(MessageOf([](std::string* e) { return WholeField(e, "threads", 0, 1); }),
            "threads: expected a whole number >= 1, got 0");
  EXPECT_EQ(MessageOf([](std::string* e) { return WholeField(e, "draws", 21, 1, 20); }),
            "draws: expected a whole number in [1, 20], got 21");
  EXPECT_FALSE(PositiveField(nullptr, "abs_tol", -1));  // no message asked for
}

TEST(Validity, OrderedFieldsNameTheLaterOneWithBothValues) {
  const auto ordered = [](double begin, double end, bool or_equal) {
    return MessageOf([&](std::string* e) {
      return OrderedFields(e, "fit_begin_s", begin, "fit_end_s", end, "the fit window must end after it begins",
                           or_equal);
    });
  };
  EXPECT_EQ(ordered(20, 2, false), "fit_end_s: the fit window must end after it begins (fit_begin_s 20, fit_end_s 2)");
  EXPECT_NE(ordered(20, 20, false), "");
  EXPECT_EQ(ordered(20, 20, true), "");
  EXPECT_NE(ordered(std::nan(""), 20, true), "");  // NaN is in no order
}

TEST(Validity, ANestedFieldIsNamedThroughItsStruct) {
  EXPECT_EQ(MessageOf([](std::string* e) { return NestedValid(e, "integrator", PositiveField(e, "abs_tol", 0)); }),
            "integrator.abs_tol: expected a finite number > 0, got 0");
  EXPECT_EQ(MessageOf([](std::string* e) { return NestedValid(e, "integrator", PositiveField(e, "abs_tol", 1)); }), "");
}

struct Budget {
  int max_evaluations = 40;
  bool IsValid(std::string* error) const { return WholeField(error, "max_evaluations", max_evaluations, 1); }
};

TEST(Validity, ThrowIfInvalidThrowsTheParameterErrorOfTheMessage) {
  EXPECT_NO_THROW(ThrowIfInvalid(Budget{}));
  try {
    ThrowIfInvalid(Budget{0});
    FAIL() << "not refused";
  } catch (const ParameterError& e) {
    EXPECT_EQ(e.parameter(), "max_evaluations");
    EXPECT_EQ(e.message(), "expected a whole number >= 1, got 0");
    EXPECT_STREQ(e.what(), "max_evaluations: expected a whole number >= 1, got 0");
  }
}

}  // namespace
}  // namespace drillwave
