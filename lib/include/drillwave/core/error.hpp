#pragma once
// Error types shared by every module. The command-line tool maps them to exit codes:
// InputError -> 2 (the input is wrong), NumericalError -> 3 (the integration failed), io::OutputError -> 5 (the
// outputs could not be written), MemoryError (core/memory.hpp) and std::bad_alloc -> 6, anything else -> 4.
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace drillwave {

// Bad input: names where (a JSON path such as "/model/sections/0/length_m", a file, a command-line option) and what
// was expected. With an empty location the message stands alone.
class InputError : public std::runtime_error {
 public:
  InputError(std::string json_path, const std::string& message);
  const std::string& json_path() const { return json_path_; }

 private:
  std::string json_path_;
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
