#pragma once
// Error types shared by every module. The command-line tool maps them to exit codes:
// InputError -> 2 (the input is wrong), NumericalError -> 3 (the integration failed), io::OutputError -> 5 (the
// outputs could not be written), MemoryError (core/memory.hpp) and std::bad_alloc -> 6, anything else -> 4.
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace drillwave {

// Bad input: names where (a JSON path such as "/model/sections/0/length_m", a file, a library parameter) and what was
// expected. With an empty location the message stands alone. A message that advises another parameter (raise
// max_samples) lists it in `mentioned_parameters`, so that a front end can name it its own way.
class InputError : public std::runtime_error {
 public:
  InputError(std::string json_path, const std::string& message, std::vector<std::string> mentioned_parameters = {});
  const std::string& json_path() const { return json_path_; }
  const std::string& message() const { return message_; }  // what() without the location
  const std::vector<std::string>& mentioned_parameters() const { return mentioned_parameters_; }

 private:
  std::string json_path_, message_;
  std::vector<std::string> mentioned_parameters_;
};

// Bad value of a parameter of a library call (an options struct's field or a function's argument), named as the
// library names it: snake_case, as Python's keywords ("max_samples", "draw_count"; "map /model/bit/inertia_kgm2" for
// one of several). A front end names its own way of setting it: the command-line tool the flag (--max-samples), so
// that no library message speaks of flags.
class ParameterError : public InputError {
 public:
  ParameterError(std::string parameter, const std::string& message, std::vector<std::string> mentioned_parameters = {})
      : InputError(std::move(parameter), message, std::move(mentioned_parameters)) {}
  const std::string& parameter() const { return json_path(); }
};

// Numerical failure (step-size underflow, non-finite state): where in time it happened and the state there.
class NumericalError : public std::runtime_error {
 public:
  NumericalError(const std::string& what, double time, std::vector<double> state);
  double time() const { return time_; }
  const std::vector<double>& state() const { return state_; }

 private:
  double time_;
  std::vector<double> state_;
};

// Text from an input, fit for a message: at most `max_chars` bytes (then "..." and the total length), control
// characters and bytes that are not UTF-8 shown as \xNN, so a message never carries raw binary.
std::string ReadableText(std::string_view text, std::size_t max_chars = 60);

// A number from an input, fit for a message: at most 10 significant digits ("1e+308", "-120", "0.000123"), "nan",
// "inf"; never the 300 digits of a fixed-point 1e300.
std::string ReadableNumber(double value);

// Whether `text` is valid UTF-8 (no overlong forms, no surrogates); `bad_offset` receives the first bad byte.
bool IsValidUtf8(std::string_view text, std::size_t* bad_offset = nullptr);

}  // namespace drillwave
