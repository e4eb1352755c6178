#include "drillwave/core/validity.hpp"

#include <cmath>

namespace drillwave {

bool Invalid(std::string* error, const std::string& parameter, const std::string& message) {
  if (error) *error = parameter + ": " + message;
  return false;
}

bool FiniteField(std::string* error, const std::string& parameter, double value) {
  return std::isfinite(value) || Invalid(error, parameter, "expected a finite number, got " + ReadableNumber(value));
}

bool PositiveField(std::string* error, const std::string& parameter, double value) {
  return (std::isfinite(value) && value > 0) ||
         Invalid(error, parameter, "expected a finite number > 0, got " + ReadableNumber(value));
}

bool NonNegativeField(std::string* error, const std::string& parameter, double value) {
  return (std::isfinite(value) && value >= 0) ||
         Invalid(error, parameter, "expected a finite number >= 0, got " + ReadableNumber(value));
}

bool FractionField(std::string* error, const std::string& parameter, double value) {
  return (value >= 0 && value < 1) ||
         Invalid(error, parameter, "expected a fraction in [0, 1), got " + ReadableNumber(value));
}

bool WholeField(std::string* error, const std::string& parameter, long value, long lower, long upper) {
  if (value >= lower && value <= upper) return true;
  const std::string range = upper == kNoUpperBound
                                ? ">= " + std::to_string(lower)
                                : "in [" + std::to_string(lower) + ", " + std::to_string(upper) + "]";
  return Invalid(error, parameter, "expected a whole number " + range + ", got " + std::to_string(value));
}

bool OrderedFields(std::string* error, const std::string& lower_name, double lower, const std::string& upper_name,
                   double upper, const std::string& rule, bool or_equal) {
  return (or_equal ? upper >= lower : upper > lower) ||
         Invalid(error, upper_name, rule + " (" + lower_name + " " + ReadableNumber(lower) + ", " + upper_name + " " +
                                        ReadableNumber(upper) + ")");
}

bool NestedValid(std::string* error, const std::string& field, bool valid) {
  if (!valid && error) *error = field + "." + *error;
  return valid;
}

ParameterError ParameterErrorOf(const std::string& error) {
  const std::size_t colon = error.find(": ");
  if (colon == std::string::npos) return ParameterError("", error);
  return ParameterError(error.substr(0, colon), error.substr(colon + 2));
}

}  // namespace drillwave
