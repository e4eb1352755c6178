#pragma once
// The JSON path that a case document is refused with (InputError), for tests of bad input. Header-only.
#include <string>

#include <nlohmann/json.hpp>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"

namespace drillwave::testing {

// The path of the InputError that parsing the case (and, with linearize, linearizing its model) raises; "" if none.
inline std::string RefusedPath(const nlohmann::json& doc, bool linearize = false) {
  try {
    const cases::Case c = cases::ParseCase(doc);
    if (linearize) c.model->Linearize();
  } catch (const InputError& e) {
    return e.json_path();
  }
  return "";
}

}  // namespace drillwave::testing
