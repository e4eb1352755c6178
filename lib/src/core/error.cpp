#include "drillwave/core/error.hpp"

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

}  // namespace

InputError::InputError(std::string json_path, const std::string& message)
    : std::runtime_error((json_path.empty() ? std::string("/") : json_path) + ": " + message),
      json_path_(std::move(json_path)) {}

NumericalError::NumericalError(const std::string& what, double time, std::vector<double> state)
    : std::runtime_error(DescribeNumericalFailure(what, time, state)), time_(time), state_(std::move(state)) {}

}  // namespace drillwave
