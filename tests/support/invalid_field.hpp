#pragma once
// What an options struct's IsValid refuses (core/validity.hpp), and what a call refuses with a ParameterError, for
// tests of the options' own checks and of the entry points that check them first. Header-only.
#include <string>

#include "drillwave/core/error.hpp"

namespace drillwave::testing {

// The parameter IsValid's message names ("" when the options are valid); the whole message in *message.
template <class Options>
std::string InvalidField(const Options& options, std::string* message = nullptr) {
  std::string error;
  if (options.IsValid(&error)) return "";
  if (message) *message = error;
  return error.substr(0, error.find(": "));
}

// The parameter IsValid names for `options` after change(options) ("" when they are still valid).
template <class Options, class Change>
std::string InvalidFieldWith(Options options, const Change& change) {
  change(options);
  return InvalidField(options);
}

// The parameter of the ParameterError that call() throws ("" when it throws none).
template <class Call>
std::string RefusedParameter(const Call& call) {
  try {
    call();
  } catch (const ParameterError& e) {
    return e.parameter();
  }
  return "";
}

}  // namespace drillwave::testing
