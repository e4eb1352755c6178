#include "drillwave/io/json_reader.hpp"

#include <cmath>
#include <algorithm>
#include <fstream>
#include <sstream>

#include "drillwave/core/error.hpp"

namespace drillwave::io {
namespace {

std::string Found(const nlohmann::json& v) {
  if (v.is_string()) return "a string " + v.dump();
  if (v.is_number()) return v.dump();
  return std::string(v.type_name()) + " " + v.dump().substr(0, 60);
}

std::string Format(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

nlohmann::json LoadJsonFile(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("", "cannot open case file " + file);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    throw InputError("", "malformed JSON in " + file + " at line " + std::to_string(line) + ", column " +
                             std::to_string(column) + ": " + e.what());
  } catch (const nlohmann::json::exception& e) {  // e.g. 1e999: a number that is not finite
    throw InputError("", "invalid JSON in " + file + ": " + e.what() + " (numbers must be finite)");
  }
}

bool Range::Contains(double v) const {
  return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
}

std::string Range::Describe() const {
  if (std::isinf(lo) && std::isinf(hi)) return "a finite number";
  if (std::isinf(hi)) return std::string("a number ") + (lo_open ? "> " : ">= ") + Format(lo);
  if (std::isinf(lo)) return std::string("a number ") + (hi_open ? "< " : "<= ") + Format(hi);
  return "a number in " + std::string(lo_open ? "(" : "[") + Format(lo) + ", " + Format(hi) + (hi_open ? ")" : "]");
}

JsonReader::JsonReader(const nlohmann::json& object, std::string path) : object_(&object), path_(std::move(path)) {
  if (!object.is_object()) throw InputError(path_, "expected an object, got " + Found(object));
}

bool JsonReader::Has(const std::string& key) const {
  known_.insert(key);
  return object_->contains(key);
}

void JsonReader::Allow(const std::string& key) const { known_.insert(key); }

const nlohmann::json& JsonReader::Required(const std::string& key, const std::string& expected) const {
  known_.insert(key);
  if (!object_->contains(key)) throw InputError(PathOf(key), "missing required field (" + expected + ")");
  return object_->at(key);
}

const nlohmann::json& JsonReader::Raw(const std::string& key) const { return Required(key, "a value"); }

double JsonReader::CheckNumber(const nlohmann::json& v, const std::string& key, Range range) const {
  if (!v.is_number()) throw InputError(PathOf(key), "expected " + range.Describe() + ", got " + Found(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw InputError(PathOf(key), "expected a finite number, got " + Format(x));
  if (!range.Contains(x)) throw InputError(PathOf(key), "expected " + range.Describe() + ", got " + Format(x));
  return x;
}

double JsonReader::Number(const std::string& key, Range range) const {
  return CheckNumber(Required(key, range.Describe()), key, range);
}

double JsonReader::Number(const std::string& key, Range range, double default_value) const {
  return Has(key) ? CheckNumber(object_->at(key), key, range) : default_value;
}

int JsonReader::Integer(const std::string& key, int lo, int hi) const {
  const std::string expected = "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  const auto& v = Required(key, expected);
  if (!v.is_number_integer() || v.get<long long>() < lo || v.get<long long>() > hi)
    throw InputError(PathOf(key), "expected " + expected + ", got " + Found(v));
  return v.get<int>();
}

int JsonReader::Integer(const std::string& key, int lo, int hi, int default_value) const {
  return Has(key) ? Integer(key, lo, hi) : default_value;
}

bool JsonReader::Boolean(const std::string& key) const {
  const auto& v = Required(key, "true or false");
  if (!v.is_boolean()) throw InputError(PathOf(key), "expected true or false, got " + Found(v));
  return v.get<bool>();
}

bool JsonReader::Boolean(const std::string& key, bool default_value) const {
  return Has(key) ? Boolean(key) : default_value;
}

std::string JsonReader::String(const std::string& key, const std::vector<std::string>& allowed) const {
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
  const std::string expected = allowed.empty() ? "a string" : "one of: " + list;
  const auto& v = Required(key, expected);
  if (!v.is_string()) throw InputError(PathOf(key), "expected " + expected + ", got " + Found(v));
  const std::string s = v.get<std::string>();
  if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), s) == allowed.end())
    throw InputError(PathOf(key), "expected " + expected + ", got \"" + s + "\"");
  return s;
}

std::string JsonReader::String(const std::string& key, const std::vector<std::string>& allowed,
                               const std::string& default_value) const {
  return Has(key) ? String(key, allowed) : default_value;
}

std::vector<double> JsonReader::NumberArray(const std::string& key, Range range) const {
  const auto& v = Required(key, "a list of numbers");
  if (!v.is_array()) throw InputError(PathOf(key), "expected a list of numbers, got " + Found(v));
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) out.push_back(CheckNumber(v[i], key + "/" + std::to_string(i), range));
  return out;
}

JsonReader JsonReader::Object(const std::string& key) const {
  return JsonReader(Required(key, "an object"), PathOf(key));
}

std::vector<JsonReader> JsonReader::ObjectArray(const std::string& key) const {
  const auto& v = Required(key, "a list of objects");
  if (!v.is_array()) throw InputError(PathOf(key), "expected a list of objects, got " + Found(v));
  std::vector<JsonReader> out;
  for (std::size_t i = 0; i < v.size(); ++i) out.emplace_back(v[i], PathOf(key) + "/" + std::to_string(i));
  return out;
}

void JsonReader::Finish() const {
  for (const auto& item : object_->items()) {
    if (known_.count(item.key())) continue;
    std::string list;
    for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
    throw InputError(PathOf(item.key()), "unknown field; expected one of: " + list);
  }
}

void SetByPointer(nlohmann::json& doc, const std::string& pointer, const nlohmann::json& value) {
  try {
    const nlohmann::json::json_pointer p(pointer);
    if (!doc.contains(p)) throw InputError(pointer, "no such field in the case");
    doc[p] = value;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(pointer, std::string("not a valid JSON pointer into the case: ") + e.what());
  }
}

nlohmann::json ParseScalarText(const std::string& text) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error&) {
    return text;
  }
}

}  // namespace drillwave::io
