#pragma once
// Reading and validating JSON case files. Every error names the JSON path of the field, what was expected and
// what was found; unknown fields are errors (a misspelt key must not be silently ignored).
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace drillwave::io {

// Throws InputError("", ...) if the file cannot be read or is not valid JSON (with line and column).
nlohmann::json LoadJsonFile(const std::string& file);

// Allowed values of a number.
struct Range {
  double lo, hi;
  bool lo_open, hi_open;
  static Range Positive() { return {0, INFINITY, true, false}; }
  static Range NonNegative() { return {0, INFINITY, false, false}; }
  static Range Any() { return {-INFINITY, INFINITY, false, false}; }
  static Range Between(double lo, double hi) { return {lo, hi, false, false}; }
  static Range AtLeast(double lo) { return {lo, INFINITY, false, false}; }
  static Range Fraction() { return {0, 1, false, false}; }
  bool Contains(double v) const;
  std::string Describe() const;  // "a number > 0", "a number in [0, 1]"
};

// One JSON object at a path; kinds declare their fields through it. Reading or checking a key marks it known;
// Finish() rejects the keys nobody asked for.
class JsonReader {
 public:
  JsonReader(const nlohmann::json& object, std::string path);

  double Number(const std::string& key, Range range) const;
  double Number(const std::string& key, Range range, double default_value) const;
  int Integer(const std::string& key, int lo, int hi) const;
  int Integer(const std::string& key, int lo, int hi, int default_value) const;
  bool Boolean(const std::string& key) const;
  bool Boolean(const std::string& key, bool default_value) const;
  std::string String(const std::string& key, const std::vector<std::string>& allowed) const;
  std::string String(const std::string& key, const std::vector<std::string>& allowed,
                     const std::string& default_value) const;
  std::vector<double> NumberArray(const std::string& key, Range range) const;
  bool Has(const std::string& key) const;
  JsonReader Object(const std::string& key) const;
  std::vector<JsonReader> ObjectArray(const std::string& key) const;
  const nlohmann::json& Raw(const std::string& key) const;  // required
  void Allow(const std::string& key) const;
  std::string PathOf(const std::string& key) const { return path_ + "/" + key; }
  const std::string& path() const { return path_; }
  void Finish() const;

 private:
  const nlohmann::json& Required(const std::string& key, const std::string& expected) const;
  double CheckNumber(const nlohmann::json& v, const std::string& key, Range range) const;

  const nlohmann::json* object_;
  std::string path_;
  mutable std::set<std::string> known_;
};

// Replaces the value at an existing JSON pointer (sweeps, fits, --set); InputError if the path does not exist.
void SetByPointer(nlohmann::json& doc, const std::string& pointer, const nlohmann::json& value);
// "3.5" -> number, "true" -> bool, valid JSON -> that, otherwise the text as a string.
nlohmann::json ParseScalarText(const std::string& text);

}  // namespace drillwave::io
