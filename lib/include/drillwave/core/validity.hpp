#pragma once
// Options structs check their own fields with `bool IsValid(std::string* error) const` (Ceres' habit): true, or false
// with *error = "<parameter>: <what is wrong>", the field named as the library names its parameters (snake_case,
// error.hpp) and a field of a nested struct as "<struct>.<field>" ("integrator.abs_tol"). IsValid decides only what the
// struct alone can; what needs the case or the recording is checked where they meet. The helpers below write such
// messages, and ThrowIfInvalid is what an entry point taking options calls first.
#include <limits>
#include <string>

#include "drillwave/core/error.hpp"

namespace drillwave {

// Writes "<parameter>: <message>" to *error (when error is not null) and returns false.
bool Invalid(std::string* error, const std::string& parameter, const std::string& message);

// One field's check: true, or Invalid(error, parameter, "expected <what>, got <value>").
bool FiniteField(std::string* error, const std::string& parameter, double value);
bool PositiveField(std::string* error, const std::string& parameter, double value);     // finite and > 0
bool NonNegativeField(std::string* error, const std::string& parameter, double value);  // finite and >= 0
bool FractionField(std::string* error, const std::string& parameter, double value);     // in [0, 1)
inline constexpr long kNoUpperBound = std::numeric_limits<long>::max();
bool WholeField(std::string* error, const std::string& parameter, long value, long lower, long upper = kNoUpperBound);

// Two fields in order, upper > lower (or_equal: >=), or Invalid naming the upper one with `rule` and both values:
// "fit_end_s: the fit window must end after it begins (fit_begin_s 20, fit_end_s 2)".
bool OrderedFields(std::string* error, const std::string& lower_name, double lower, const std::string& upper_name,
                   double upper, const std::string& rule, bool or_equal = false);

// A nested struct's IsValid result, its message's parameter prefixed with `field` ("integrator" + "abs_tol").
bool NestedValid(std::string* error, const std::string& field, bool valid);

// The ParameterError an IsValid message "<parameter>: <message>" stands for.
ParameterError ParameterErrorOf(const std::string& error);

// Throws ParameterErrorOf(IsValid's message) unless `options` is valid.
template <class Options>
void ThrowIfInvalid(const Options& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ParameterErrorOf(error);
}

}  // namespace drillwave
