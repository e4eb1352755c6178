#pragma once
// A case of json-cases/ by its name, as the tests read it (with its expect block).
#include <string>

#include <nlohmann/json.hpp>

#include "drillwave/io/json_reader.hpp"

namespace drillwave::testing {

inline nlohmann::json LoadCase(const std::string& name) {
  return io::LoadJsonFile(std::string(DRILLWAVE_SOURCE_DIR) + "/json-cases/" + name + ".json");
}

}  // namespace drillwave::testing
