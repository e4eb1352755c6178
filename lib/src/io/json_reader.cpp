#include "drillwave/io/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "drillwave/core/error.hpp"

namespace drillwave::io {
namespace {

constexpr std::size_t kMaxJsonDepth = 64;

// A bound or limit as people write it: "0", "0.01", "1e-14".
std::string FormatBound(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", v);
  return buffer;
}

std::string Shortened(const std::string& text) { return ReadableText(text, 60); }

// What was found, for "expected X, got <Found>": -3, a string "abc", true, null, an array [1,2], inf.
std::string Found(const nlohmann::json& v) {
  if (v.is_number()) {
    const double x = v.get<double>();
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    return v.dump();
  }
  if (v.is_string()) return "a string " + Shortened(v.dump());
  if (v.is_array()) return "an array " + Shortened(v.dump());
  if (v.is_object()) return "an object " + Shortened(v.dump());
  return v.dump();  // true, false, null
}

std::string JoinedList(const std::vector<std::string>& items) {
  std::string list;
  for (const auto& item : items) list += (list.empty() ? "" : ", ") + item;
  return list;
}

// nlohmann's what() is "[json.exception.parse_error.101] parse error at line 3, column 1: syntax error ..."; keep
// only the description, since the caller states the location itself.
std::string ParserDescription(const std::string& what) {
  std::size_t start = what.find("] ");
  start = start == std::string::npos ? 0 : start + 2;
  if (what.compare(start, 11, "parse error") == 0) {
    const std::size_t colon = what.find(": ", start);
    if (colon != std::string::npos) start = colon + 2;
  }
  return what.substr(start);
}

struct TextPosition {
  std::size_t line, column;
};

// Line and column (1-based) of the byte at `offset`. Columns count characters, not UTF-8 bytes, as editors do.
TextPosition PositionOf(const std::string& text, std::size_t offset) {
  TextPosition p{1, 1};
  std::size_t i = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;  // a byte order mark is not a column
  for (offset = std::min(offset, text.size()); i < offset; ++i) {
    if (text[i] == '\n') {
      ++p.line;
      p.column = 1;
    } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {
      ++p.column;
    }
  }
  return p;
}

// Offers every byte outside string literals (quotes excluded) to `visit(i)`, which may move i forward past a token it
// has read and returns true to stop there. Returns where it stopped, or npos.
template <class Visit>
std::size_t ScanOutsideStrings(const std::string& text, Visit visit) {
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (visit(i)) {
      return i;
    }
  }
  return std::string::npos;
}

// nlohmann reports a number that overflows a double (1e999) without its position. The parser stops at the first
// such number, and everything before it is valid JSON, so it is the first number token outside strings that does
// not convert to a finite double.
std::size_t FirstNonFiniteNumber(const std::string& text) {
  return ScanOutsideStrings(text, [&](std::size_t& i) {
    const char c = text[i];
    if (c != '-' && (c < '0' || c > '9')) return false;
    char* end = nullptr;
    const double v = std::strtod(text.c_str() + i, &end);
    if (!std::isfinite(v)) return true;
    i = std::max(i, static_cast<std::size_t>(end - text.c_str()) - 1);
    return false;
  });
}

std::string MalformedJson(const std::string& file, const std::string& text, std::size_t offset,
                          const std::string& description) {
  const TextPosition p = PositionOf(text, offset);
  return "malformed JSON in " + file + " at line " + std::to_string(p.line) + ", column " + std::to_string(p.column) +
         ": " + description;
}

// How deep objects and arrays nest before the first bracket beyond kMaxJsonDepth (outside strings), or npos. A cheap
// scan before nlohmann parses, whose recursion through deeply nested values (dump, copy, destruction) would overflow
// the stack; it does not need valid JSON.
std::size_t FirstTooDeep(const std::string& text) {
  std::size_t depth = 0;
  return ScanOutsideStrings(text, [&](std::size_t& i) {
    const char c = text[i];
    if (c == '[' || c == '{') return ++depth > kMaxJsonDepth;
    if ((c == ']' || c == '}') && depth > 0) --depth;
    return false;
  });
}

// JSON (RFC 8259) leaves duplicate keys to the reader, and nlohmann keeps the last one silently; a case with two
// values for one field is ambiguous, so it is an error naming the key's path and position. Runs on text nlohmann has
// accepted, so the structure is valid here. Keys are compared as written (escapes not decoded).
void CheckDuplicateKeys(const std::string& text, const std::string& source) {
  struct Level {
    bool object;
    std::size_t index = 0;  // of the next array element
    std::string key;        // the current key of an object
    std::set<std::string> keys;
  };
  std::vector<Level> stack;
  bool expect_key = false;
  auto path = [&] {
    std::string p;
    for (const Level& l : stack) p += "/" + (l.object ? l.key : std::to_string(l.index));
    return p;
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"') {
      const std::size_t start = i;
      for (++i; i < text.size() && text[i] != '"'; ++i)
        if (text[i] == '\\') ++i;
      if (!expect_key) continue;
      Level& level = stack.back();
      level.key = text.substr(start + 1, i - start - 1);
      if (!level.keys.insert(level.key).second)
        throw InputError(path(), MalformedJson(source, text, start,
                                               "duplicate key \"" + ReadableText(level.key) +
                                                   "\"; every field may appear once"));
      expect_key = false;
    } else if (c == '{') {
      stack.push_back(Level{true, 0, {}, {}});
      expect_key = true;
    } else if (c == '[') {
      stack.push_back(Level{false, 0, {}, {}});
    } else if (c == '}' || c == ']') {
      if (!stack.empty()) stack.pop_back();
      expect_key = false;
    } else if (c == ',' && !stack.empty()) {
      expect_key = stack.back().object;
      if (!expect_key) ++stack.back().index;
    }
  }
}

}  // namespace

nlohmann::json ParseJsonText(const std::string& text, const std::string& source) {
  if (text.size() > kMaxJsonBytes)
    throw InputError(source, "JSON text of " + std::to_string(text.size()) + " bytes; at most " +
                                 std::to_string(kMaxJsonBytes) + " bytes are read");
  const std::size_t nul = text.find('\0');
  if (nul != std::string::npos)
    throw InputError("", MalformedJson(source, text, nul, "a NUL byte; a JSON file is text"));
  std::size_t bad_byte = 0;
  if (!IsValidUtf8(text, &bad_byte))
    throw InputError("", MalformedJson(source, text, bad_byte, "a byte that is not UTF-8 (" +
                                                                   ReadableText(text.substr(bad_byte, 1)) + ")"));
  const std::size_t too_deep = FirstTooDeep(text);
  if (too_deep != std::string::npos)
    throw InputError("", MalformedJson(source, text, too_deep,
                                       "nested more than " + std::to_string(kMaxJsonDepth) + " levels deep"));
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte counts the bytes read, including the offending one.
    throw InputError("", MalformedJson(source, text, e.byte == 0 ? 0 : e.byte - 1, ParserDescription(e.what())));
  } catch (const nlohmann::json::out_of_range& e) {  // 1e999
    throw InputError("", MalformedJson(source, text, FirstNonFiniteNumber(text),
                                       ParserDescription(e.what()) + " (numbers must be finite doubles)"));
  }
  CheckDuplicateKeys(text, source);
  return doc;
}

nlohmann::json LoadJsonFile(const std::string& file) {
  if (file.empty()) throw InputError("", "empty file name; expected the path of a JSON file");
  std::ifstream in(file, std::ios::binary);
  std::error_code ignored;  // a folder opens, but then cannot be read
  if (!in || std::filesystem::is_directory(file, ignored)) throw InputError("", "cannot open case file " + file);
  // Read at most one byte more than the limit, so that a huge file (or an endless pipe) is refused, not read; in
  // chunks, so that a case of a few kB does not clear a buffer of the limit's size first.
  std::string text;
  char chunk[1 << 16];
  while (text.size() <= kMaxJsonBytes && in.read(chunk, sizeof chunk).gcount() > 0)
    text.append(chunk, static_cast<std::size_t>(std::min<std::streamsize>(
                           in.gcount(), static_cast<std::streamsize>(kMaxJsonBytes + 1 - text.size()))));
  if (in.bad()) throw InputError("", "cannot read case file " + file);
  return ParseJsonText(text, file);
}

bool Range::Contains(double v) const {
  return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
}

std::string Range::Describe() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (!has_lo && !has_hi) return "a finite number";
  if (!has_hi) return std::string("a number ") + (lo_open ? "> " : ">= ") + FormatBound(lo);
  if (!has_lo) return std::string("a number ") + (hi_open ? "< " : "<= ") + FormatBound(hi);
  return std::string("a number in ") + (lo_open ? "(" : "[") + FormatBound(lo) + ", " + FormatBound(hi) +
         (hi_open ? ")" : "]");
}

namespace {

double CheckedNumber(const nlohmann::json& v, const std::string& path, const Range& range) {
  if (!v.is_number()) throw InputError(path, "expected " + range.Describe() + ", got " + Found(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw InputError(path, "expected a finite number, got " + Found(v));
  if (!range.Contains(x)) throw InputError(path, "expected " + range.Describe() + ", got " + Found(v));
  return x;
}

}  // namespace

JsonReader::JsonReader(const nlohmann::json& object, std::string path) : object_(&object), path_(std::move(path)) {
  if (!object.is_object()) throw InputError(path_, "expected an object, got " + Found(object));
}

bool JsonReader::Has(const std::string& key) const {
  known_.insert(key);
  return object_->contains(key);
}

void JsonReader::Allow(const std::string& key) const { known_.insert(key); }

void JsonReader::RefuseRenamed(const std::string& old_key, const std::string& new_pointer) const {
  if (object_->contains(old_key))
    throw InputError(PathOf(old_key), "this field was renamed to " + new_pointer + " (one name for one quantity in "
                                                                                   "every kind)");
}

const nlohmann::json& JsonReader::Required(const std::string& key, const std::string& expected) const {
  known_.insert(key);
  const auto it = object_->find(key);
  if (it == object_->end()) throw InputError(PathOf(key), "missing required field (" + expected + ")");
  return *it;
}

const nlohmann::json& JsonReader::Raw(const std::string& key) const { return Required(key, "a value"); }

double JsonReader::Number(const std::string& key, Range range) const {
  return CheckedNumber(Required(key, range.Describe()), PathOf(key), range);
}

double JsonReader::Number(const std::string& key, Range range, double default_value) const {
  return Has(key) ? Number(key, range) : default_value;
}

int JsonReader::Integer(const std::string& key, int lo, int hi) const {
  const std::string expected = "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  const nlohmann::json& v = Required(key, expected);
  // Compared as doubles: exact for every int, and no wrap-around for huge unsigned values.
  const double x = v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN();
  if (!std::isfinite(x) || x != std::floor(x) || x < lo || x > hi)
    throw InputError(PathOf(key), "expected " + expected + ", got " + Found(v));
  return static_cast<int>(x);
}

int JsonReader::Integer(const std::string& key, int lo, int hi, int default_value) const {
  return Has(key) ? Integer(key, lo, hi) : default_value;
}

bool JsonReader::Boolean(const std::string& key) const {
  const nlohmann::json& v = Required(key, "true or false");
  if (!v.is_boolean()) throw InputError(PathOf(key), "expected true or false, got " + Found(v));
  return v.get<bool>();
}

bool JsonReader::Boolean(const std::string& key, bool default_value) const {
  return Has(key) ? Boolean(key) : default_value;
}

std::string JsonReader::String(const std::string& key, const std::vector<std::string>& allowed) const {
  const std::string expected = allowed.empty() ? "a string" : "one of: " + JoinedList(allowed);
  const nlohmann::json& v = Required(key, expected);
  if (!v.is_string()) throw InputError(PathOf(key), "expected " + expected + ", got " + Found(v));
  std::string s = v.get<std::string>();
  if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), s) == allowed.end())
    throw InputError(PathOf(key), "expected " + expected + ", got " + Shortened(v.dump()));
  return s;
}

std::string JsonReader::String(const std::string& key, const std::vector<std::string>& allowed,
                               const std::string& default_value) const {
  return Has(key) ? String(key, allowed) : default_value;
}

std::vector<double> JsonReader::NumberArray(const std::string& key, Range range) const {
  const std::string expected = "a list of numbers (each " + range.Describe() + ")";
  const nlohmann::json& v = Required(key, expected);
  if (!v.is_array()) throw InputError(PathOf(key), "expected " + expected + ", got " + Found(v));
  std::vector<double> values;
  values.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    values.push_back(CheckedNumber(v[i], PathOf(key) + "/" + std::to_string(i), range));
  return values;
}

JsonReader JsonReader::Object(const std::string& key) const {
  return JsonReader(Required(key, "an object"), PathOf(key));
}

std::vector<JsonReader> JsonReader::ObjectArray(const std::string& key) const {
  const nlohmann::json& v = Required(key, "a list of objects");
  if (!v.is_array()) throw InputError(PathOf(key), "expected a list of objects, got " + Found(v));
  std::vector<JsonReader> readers;
  readers.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) readers.emplace_back(v[i], PathOf(key) + "/" + std::to_string(i));
  return readers;
}

void JsonReader::Finish() const {
  for (const auto& item : object_->items()) {
    if (known_.count(item.key())) continue;
    if (known_.empty()) throw InputError(PathOf(item.key()), "unknown field; this object takes no fields");
    throw InputError(PathOf(item.key()),
                     "unknown field; expected one of: " + JoinedList({known_.begin(), known_.end()}));
  }
}

void SetByPointer(nlohmann::json& doc, const std::string& pointer, const nlohmann::json& value) {
  if (pointer.empty() || pointer[0] != '/')
    throw InputError(pointer, "expected a JSON pointer such as /simulation/duration_s");
  // Walked by hand rather than with nlohmann::json_pointer, whose operator[] would create missing fields and
  // whose errors for bad array indices are not about the case.
  nlohmann::json* node = &doc;
  std::size_t start = 1;
  while (true) {
    const std::size_t slash = pointer.find('/', start);
    std::string token = pointer.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    // RFC 6901 escapes: "~1" is '/', "~0" is '~' (in that order).
    for (std::size_t i = 0; (i = token.find("~1", i)) != std::string::npos; ++i) token.replace(i, 2, "/");
    for (std::size_t i = 0; (i = token.find("~0", i)) != std::string::npos; ++i) token.replace(i, 2, "~");
    nlohmann::json* child = nullptr;
    if (node->is_object()) {
      const auto it = node->find(token);
      if (it != node->end()) {
        child = &*it;
      } else {
        // A documented optional field the case leaves out: add it (and the objects on its way). A misspelt one is
        // refused by the case's own reader as an unknown field, with its path, before anything runs.
        // (Once a member is added, everything below it is added too: a failure can only come before.)
        child = &(*node)[token];
        if (slash != std::string::npos) *child = nlohmann::json::object();
      }
    } else if (node->is_array()) {
      const bool is_index = !token.empty() && token.size() <= 9 &&
                            token.find_first_not_of("0123456789") == std::string::npos &&
                            (token == "0" || token[0] != '0');
      if (is_index && std::stoul(token) < node->size()) child = &(*node)[std::stoul(token)];
    }
    if (child == nullptr) throw InputError(pointer, "no such field in the case");
    node = child;
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  *node = value;
}

nlohmann::json ParseScalarText(const std::string& text) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error&) {
    return text;
  } catch (const nlohmann::json::out_of_range&) {  // number syntax, but beyond a double: 1e999 (or inside [1e999])
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    while (*end == ' ' || *end == '\t' || *end == '\n' || *end == '\r') ++end;
    if (*end == '\0') return v;
    return text;
  }
}

void ApplySetOption(nlohmann::json& doc, const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || text.empty() || text[0] != '/')
    throw ParameterError("set", "'" + ReadableText(text) + "': expected /json/pointer=value");
  // The value joins the case, so it gets the checks a case file's text gets: bytes that are not UTF-8 would pass the
  // readers and only fail when case.json is written (after the run), deep nesting would overflow the stack.
  std::size_t bad_byte = 0;
  if (!IsValidUtf8(text, &bad_byte))
    throw ParameterError("set", "'" + ReadableText(text) + "': byte " + std::to_string(bad_byte + 1) +
                                  " is not UTF-8 (" + ReadableText(text.substr(bad_byte, 1)) + ")");
  const std::string value = text.substr(eq + 1);
  if (FirstTooDeep(value) != std::string::npos)
    throw ParameterError("set", "'" + ReadableText(text) + "': the value is nested more than " +
                                  std::to_string(kMaxJsonDepth) + " levels deep");
  const nlohmann::json parsed = ParseScalarText(value);
  if (parsed.is_structured()) {
    try {
      CheckDuplicateKeys(value, "the value");
    } catch (const InputError& e) {
      throw ParameterError("set", "'" + ReadableText(text) + "': " + e.what());
    }
  }
  SetByPointer(doc, text.substr(0, eq), parsed);
}

}  // namespace drillwave::io
