#pragma once
// Reading and validating JSON case files. Every error is an InputError naming the JSON path of the field, what was
// expected and what was found; unknown fields are errors, because a misspelt key must not be silently ignored.
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace drillwave::io {

// Case files and sidecars are small; anything larger is refused before it is read.
constexpr std::size_t kMaxJsonBytes = std::size_t{16} << 20;

// Reads and parses a JSON file. Throws InputError if the name is empty, the file cannot be opened, is larger than
// kMaxJsonBytes, or is not valid JSON; the message gives the line and column (in characters) of the problem.
// Stricter than JSON itself: numbers that overflow a double (1e999), NUL bytes, bytes that are not UTF-8, nesting
// deeper than 64 levels and duplicate keys in one object are errors too.
nlohmann::json LoadJsonFile(const std::string& file);
// The same checks on text already in memory; `source` names it in messages.
nlohmann::json ParseJsonText(const std::string& text, const std::string& source);

// The allowed values of a number field. Every Range also requires the number to be finite.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  static Range Positive() { return {0, std::numeric_limits<double>::infinity(), true, false}; }      // > 0
  static Range NonNegative() { return {0, std::numeric_limits<double>::infinity(), false, false}; }  // >= 0
  static Range Any() { return {}; }                                                                  // finite
  static Range Between(double lo, double hi) { return {lo, hi, false, false}; }                      // [lo, hi]
  static Range AtLeast(double lo) { return {lo, std::numeric_limits<double>::infinity(), false, false}; }
  static Range Fraction() { return {0, 1, false, false}; }  // [0, 1]

  bool Contains(double value) const;  // false for NaN and +-inf
  std::string Describe() const;       // "a number > 0", "a number in [0, 1]", "a finite number"
};

// One JSON object at a JSON-pointer-style path (e.g. "/model/bit"); model kinds declare and validate their fields
// through it. Every call that reads or checks a key marks that key as known, and Finish() rejects the keys nobody
// asked for. The reader refers to the JSON value it was given, which must outlive it. The accessors are const
// (the set of known keys is bookkeeping), so a const reader can be handed to code that only reads.
class JsonReader {
 public:
  // Throws InputError(path, "expected an object, got ...") if `object` is not a JSON object.
  JsonReader(const nlohmann::json& object, std::string path);

  // A required finite number in `range`; the second form returns `default_value` when the key is absent.
  double Number(const std::string& key, Range range) const;
  double Number(const std::string& key, Range range, double default_value) const;
  // A required integer in [lo, hi] (an integral float such as 3.0 is accepted).
  int Integer(const std::string& key, int lo, int hi) const;
  int Integer(const std::string& key, int lo, int hi, int default_value) const;
  bool Boolean(const std::string& key) const;
  bool Boolean(const std::string& key, bool default_value) const;
  // A string that must be one of `allowed`; an empty `allowed` accepts any string.
  std::string String(const std::string& key, const std::vector<std::string>& allowed) const;
  std::string String(const std::string& key, const std::vector<std::string>& allowed,
                     const std::string& default_value) const;
  // A required array whose elements are all finite numbers in `range` (element errors name ".../key/i").
  std::vector<double> NumberArray(const std::string& key, Range range) const;

  bool Has(const std::string& key) const;
  // A child reader at path + "/" + key; the child has its own known keys and its own Finish().
  JsonReader Object(const std::string& key) const;
  // A required array of objects, one reader per element at ".../key/0", ".../key/1", ...
  std::vector<JsonReader> ObjectArray(const std::string& key) const;
  // A required value of any type, for fields parsed elsewhere (schedules, friction laws, expectations).
  const nlohmann::json& Raw(const std::string& key) const;
  // Marks a key as known without reading it (free-text fields such as "description").
  void Allow(const std::string& key) const;
  // Throws InputError(path/old_key, "renamed: ...") if the object still has a field under a former name, so that
  // an old case file is told where its field went rather than that it is unknown.
  void RefuseRenamed(const std::string& old_key, const std::string& new_pointer) const;

  std::string PathOf(const std::string& key) const { return path_ + "/" + key; }
  const std::string& path() const { return path_; }

  // Throws InputError(path/key, "unknown field; expected one of: a, b, c") for the first key of the object that no
  // call has marked as known.
  void Finish() const;

 private:
  const nlohmann::json& Required(const std::string& key, const std::string& expected) const;

  const nlohmann::json* object_;
  std::string path_;
  mutable std::set<std::string> known_;
};

// Sets the value at a JSON pointer (parameter sweeps, fits, `--set /a/b=3`). A missing object member is added (with
// the objects on its way), so that optional fields the case leaves out can be set; a misspelt one is then refused by
// the case's reader as an unknown field. Array elements must exist. Throws InputError(pointer, "no such field in the
// case") where the pointer cannot lead (past a number, an index out of range) and leaves doc unchanged.
void SetByPointer(nlohmann::json& doc, const std::string& pointer, const nlohmann::json& value);

// Command-line text to a JSON value: "3.5" -> 3.5, "true" -> true, "[0, 5]" -> an array; text that is not JSON is
// taken as a string ("stribeck"). A number too large for a double ("1e999") becomes inf, which the readers reject
// with a clear message.
nlohmann::json ParseScalarText(const std::string& text);

// A command line's override "/json/pointer=value": the value (ParseScalarText) set at the pointer (SetByPointer).
// Throws ParameterError("set", ...) for text of any other form.
void ApplySetOption(nlohmann::json& doc, const std::string& text);

}  // namespace drillwave::io
