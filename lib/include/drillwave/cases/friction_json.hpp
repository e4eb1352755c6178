#pragma once
// Friction laws in a case's JSON: {"law": "<kind>", "<field>": number, ...} read into bitrock::FrictionLaw, written
// back, and listed for `drillwave kinds`. The physics (bitrock/friction.hpp) knows its fields and their ranges; this
// is where they meet the input format and its paths.
#include <nlohmann/json.hpp>
#include <string>

#include "drillwave/bitrock/friction.hpp"

namespace drillwave::cases {

// Throws InputError at json_path + "/<field>" for a missing, unknown, non-numeric, non-finite or out-of-range field
// (with the value found and the range expected), at json_path + "/law" for a missing or unknown kind, and at json_path
// for anything but an object.
bitrock::FrictionLaw ReadFrictionLaw(const nlohmann::json& j, const std::string& json_path);
// {"law": kind, every field with its value, defaults included}: ReadFrictionLaw of it reproduces the law.
nlohmann::json FrictionLawJson(const bitrock::FrictionLaw& law);
// {"<kind>": {"set_valued", "torque", "static" (set-valued laws), "source", "fields": {"<key>": "meaning [unit];
// range[; optional, default ...]"}}} for every law.
nlohmann::json FrictionLawSchema();

}  // namespace drillwave::cases
