#include "drillwave/cases/friction_json.hpp"

#include <cstdio>

#include "drillwave/core/error.hpp"

namespace drillwave::cases {
namespace {

using nlohmann::json;

// What was found, for messages: a number as written, a string quoted, anything else by its type.
std::string Found(const json& v) {
  if (v.is_string()) return "a string " + v.dump();
  if (v.is_number()) {
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", v.get<double>());
    return text;
  }
  return std::string(v.type_name()) + " " + v.dump().substr(0, 60);
}

std::string KindList() {
  std::string list;
  for (const std::string& k : bitrock::FrictionLaw::Kinds()) list += (list.empty() ? "" : ", ") + k;
  return list;
}

}  // namespace

bitrock::FrictionLaw ReadFrictionLaw(const json& j, const std::string& json_path) {
  if (!j.is_object())
    throw InputError(json_path, "expected a friction law, an object {\"law\": \"<kind>\", ...}, got " + Found(j));
  const auto kind = j.find("law");
  if (kind == j.end()) throw InputError(json_path + "/law", "missing required field (one of: " + KindList() + ")");
  if (!kind->is_string())
    throw InputError(json_path + "/law", "expected one of: " + KindList() + ", got " + Found(*kind));
  bitrock::FrictionLaw::FieldSource source;
  for (const auto& item : j.items()) source.keys.push_back(item.key());
  source.find = [&j](const std::string& key) {
    bitrock::FrictionLaw::Found found;
    const auto it = j.find(key);
    if (it == j.end()) return found;
    found.absent = false;
    if (it->is_number()) found.number = it->get<double>();
    found.text = Found(*it);
    return found;
  };
  try {
    return bitrock::FrictionLaw::Read(kind->get_ref<const std::string&>(), source);
  } catch (const bitrock::FrictionFieldError& e) {
    throw InputError(json_path + "/" + e.key(), e.what());
  }
}

json FrictionLawJson(const bitrock::FrictionLaw& law) {
  json j = {{"law", law.Kind()}};
  for (const auto& [key, value] : law.Values()) j[key] = value;
  return j;
}

json FrictionLawSchema() {
  json schema = json::object();
  for (const bitrock::FrictionLaw::Description& d : bitrock::FrictionLaw::Describe()) {
    json fields = json::object();
    for (const auto& [key, text] : d.fields) fields[key] = text;
    json s = {{"set_valued", d.set_valued}, {"torque", d.torque}, {"source", d.source}, {"fields", fields}};
    if (d.set_valued) s["static"] = d.static_range;
    schema[d.kind] = s;
  }
  return schema;
}

}  // namespace drillwave::cases
