#include "drillwave/core/error.hpp"

#include <cmath>
#include <cstdio>
#include <utility>
#include <sstream>

namespace drillwave {
namespace {

std::string DescribeNumericalFailure(const std::string& what, double time, const std::vector<double>& state) {
  std::ostringstream out;
  out.precision(10);
  out << what << " at t = " << time << " s; state = [";
  for (std::size_t i = 0; i < state.size(); ++i) out << (i ? ", " : "") << state[i];
  out << "]";
  return out.str();
}

// Length of the UTF-8 sequence starting at text[i], or 0 if it is not a valid one.
std::size_t Utf8SequenceLength(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char c = byte(i);
  if (c < 0x80) return 1;
  std::size_t n;
  unsigned lo = 0x80, hi = 0xBF;  // allowed range of the second byte
  if (c >= 0xC2 && c <= 0xDF) n = 2;
  else if (c == 0xE0) n = 3, lo = 0xA0;
  else if (c == 0xED) n = 3, hi = 0x9F;  // no surrogates
  else if (c >= 0xE1 && c <= 0xEF) n = 3;
  else if (c == 0xF0) n = 4, lo = 0x90;
  else if (c >= 0xF1 && c <= 0xF3) n = 4;
  else if (c == 0xF4) n = 4, hi = 0x8F;
  else return 0;
  if (i + n > text.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  return n;
}

}  // namespace

InputError::InputError(std::string json_path, const std::string& message, std::vector<std::string> mentioned_parameters)
    : std::runtime_error(json_path.empty() ? message : json_path + ": " + message),
      json_path_(std::move(json_path)),
      message_(message),
      mentioned_parameters_(std::move(mentioned_parameters)) {}

NumericalError::NumericalError(const std::string& what, double time, std::vector<double> state)
    : std::runtime_error(DescribeNumericalFailure(what, time, state)), time_(time), state_(std::move(state)) {}

bool IsValidUtf8(std::string_view text, std::size_t* bad_offset) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = Utf8SequenceLength(text, i);
    if (n == 0) {
      if (bad_offset) *bad_offset = i;
      return false;
    }
    i += n;
  }
  return true;
}

std::string ReadableText(std::string_view text, std::size_t max_chars) {
  std::string out;
  std::size_t i = 0;
  for (; i < text.size() && out.size() < max_chars;) {
    const std::size_t n = Utf8SequenceLength(text, i);
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (n == 0 || c < 0x20 || c == 0x7F) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
      ++i;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
  }
  if (i < text.size()) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

std::string ReadableNumber(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

}  // namespace drillwave
