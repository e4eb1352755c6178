#pragma once
// Error types shared by every module. The command-line tool maps them to exit codes:
// InputError -> 2 (the case is wrong), NumericalError -> 3 (the integration failed).
#include <stdexcept>
#include <string>
#include <vector>

namespace drillwave {

// Bad input: names the JSON path (e.g. "/model/sections/0/length_m") and what was expected.
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

}  // namespace drillwave
