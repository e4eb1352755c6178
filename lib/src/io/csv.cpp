#include "drillwave/io/csv.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>

#include "drillwave/core/error.hpp"
#include "drillwave/core/progress.hpp"
#include "drillwave/core/validity.hpp"

namespace drillwave::io {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// [begin, end) without surrounding blanks.
void Trim(const char*& begin, const char*& end) {
  while (begin < end && IsBlank(*begin)) ++begin;
  while (end > begin && IsBlank(end[-1])) --end;
}

}  // namespace

void AppendCsvNumber(std::string& text, double v) {
  if (std::isnan(v)) {
    text += "nan";  // not "-nan", which some readers reject
    return;
  }
  // to_chars with a precision is specified as printf's "%.10g" in the C locale, so the text is the same, and it is
  // 3 to 4 times faster (printf was half of a long run's time). The longest text, "-1.234567891e-308", has 17 chars.
  char number[32];
  const std::to_chars_result end = std::to_chars(number, number + sizeof number, v, std::chars_format::general, 10);
  text.append(number, end.ptr);
}

void WriteCsv(std::ostream& out, const std::vector<std::string>& header,
              const std::vector<std::vector<double>>& columns) {
  if (header.size() != columns.size())
    throw std::invalid_argument("WriteCsv: " + std::to_string(header.size()) + " header names for " +
                                std::to_string(columns.size()) + " columns");
  const std::size_t rows = columns.empty() ? 0 : columns.front().size();
  for (std::size_t j = 0; j < columns.size(); ++j)
    if (columns[j].size() != rows)
      throw std::invalid_argument("WriteCsv: column " + header[j] + " has " + std::to_string(columns[j].size()) +
                                  " values, the first column " + std::to_string(rows));
  for (const std::string& name : header)
    if (name.find_first_of(",\r\n\"") != std::string::npos)
      throw std::invalid_argument("WriteCsv: column name " + name + " would need CSV quoting");
  for (std::size_t j = 0; j < header.size(); ++j) out << (j ? "," : "") << header[j];
  out << '\n';
  // One string per row: several times faster than streaming each double.
  std::string line;
  for (std::size_t i = 0; i < rows; ++i) {
    line.clear();
    for (std::size_t j = 0; j < columns.size(); ++j) {
      if (j) line += ',';
      AppendCsvNumber(line, columns[j][i]);
    }
    line += '\n';
    out.write(line.data(), static_cast<std::streamsize>(line.size()));
  }
}

const std::vector<double>& CsvTable::Column(const std::string& name) const {
  const auto it = std::find(header.begin(), header.end(), name);
  if (it == header.end()) throw std::out_of_range("no CSV column named " + name);
  return columns[static_cast<std::size_t>(it - header.begin())];
}

CsvTable ReadCsv(const std::string& file, const CsvOptions& options) {
  ThrowIfInvalid(options);
  if (file.empty()) throw InputError("", "empty file name; expected the path of a CSV file");
  Progress progress("reading " + ReadableText(file, 200));
  progress.Step("loading the file");
  // The whole file in one string, parsed in place with strtod; no stream formatting per cell.
  std::string text;
  {
    std::ifstream in(file, std::ios::binary | std::ios::ate);
    std::error_code ignored;  // a folder opens, but then cannot be read
    if (!in || std::filesystem::is_directory(file, ignored)) throw InputError("", "cannot open CSV file " + file);
    const std::streamoff size = in.tellg();
    if (size >= 0) {
      text.resize(static_cast<std::size_t>(size));
      in.seekg(0);
      in.read(text.data(), static_cast<std::streamsize>(size));
    } else {  // not seekable (a pipe): read it piece by piece
      in.clear();
      text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    if (in.bad() || (size >= 0 && !in)) throw InputError("", "cannot read CSV file " + file);
  }
  const char* p = text.c_str();
  const char* const text_end = p + text.size();
  if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) p += 3;  // byte order mark written by spreadsheet programs

  auto fail = [&](std::size_t line, const std::string& message) {
    return InputError("", file + ":" + std::to_string(line) + ": " + message);
  };
  auto line_end = [&](const char* from) {
    const void* newline = std::memchr(from, '\n', static_cast<std::size_t>(text_end - from));
    return newline ? static_cast<const char*>(newline) : text_end;
  };

  CsvTable table;
  const char* end = line_end(p);
  for (const char* field = p;;) {
    const char* comma = std::find(field, end, ',');
    const char *name_begin = field, *name_end = comma;
    Trim(name_begin, name_end);
    table.header.emplace_back(name_begin, name_end);
    if (comma == end) break;
    field = comma + 1;
  }
  if (table.header.size() == 1 && table.header[0].empty()) throw fail(1, "no header line");
  const std::size_t width = table.header.size();
  for (std::size_t j = 0; j < width; ++j) {
    const std::string& name = table.header[j];
    const std::string column = "column " + std::to_string(j + 1) + " of the header";
    std::size_t bad = 0;
    if (name.empty()) throw fail(1, column + " has no name");
    if (!IsValidUtf8(name, &bad))
      throw fail(1, column + " (\"" + ReadableText(name) + "\") has a byte that is not UTF-8 at byte " +
                        std::to_string(bad + 1) + "; channel names must be UTF-8 text");
    if (std::any_of(name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; }))
      throw fail(1, column + " (\"" + ReadableText(name) + "\") has a control character");
    for (std::size_t k = 0; k < j; ++k)
      if (table.header[k] == name)
        throw fail(1, "columns " + std::to_string(k + 1) + " and " + std::to_string(j + 1) + " are both named \"" +
                          ReadableText(name) + "\"; names must be unique");
  }
  table.columns.resize(width);
  const auto rows = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
  for (auto& column : table.columns) column.reserve(rows);

  std::size_t line = 1;
  for (p = end; p < text_end;) {
    ++p;  // past '\n'
    ++line;
    if (line % 4096 == 0) progress.Count("parsing", static_cast<double>(line), static_cast<double>(rows), "lines");
    end = line_end(p);
    const char *row_begin = p, *row_end = end;
    Trim(row_begin, row_end);
    if (row_begin == row_end) {  // a blank line
      p = end;
      continue;
    }
    std::size_t j = 0;
    for (const char* field = p;; ++j) {
      const char* comma = std::find(field, end, ',');
      if (j < width) {
        const char *begin = field, *stop = comma;
        Trim(begin, stop);
        double v = std::numeric_limits<double>::quiet_NaN();
        const auto column = [&] { return "column " + ReadableText(table.header[j]) + " (" + std::to_string(j + 1) + ")"; };
        if (begin != stop) {
          // strtod stops at the ',' or '\n' after the field at the latest, so it never reads past the row.
          char* parsed_end = nullptr;
          v = std::strtod(begin, &parsed_end);
          if (parsed_end != stop)
            throw fail(line, column() + ": \"" + ReadableText(std::string_view(begin, stop - begin)) +
                                 "\" is not a number");
          if (options.finite_only && !std::isfinite(v))
            throw fail(line, column() + ": \"" + ReadableText(std::string_view(begin, stop - begin)) +
                                 "\" is not a finite number");
        } else if (options.finite_only) {
          throw fail(line, column() + ": blank cell; every cell must hold a finite number");
        }
        table.columns[j].push_back(v);
      }
      if (comma == end) break;
      field = comma + 1;
    }
    if (j + 1 != width)
      throw fail(line, std::to_string(j + 1) + " fields, but the header has " + std::to_string(width));
    p = end;
  }
  if (options.finite_only && !table.columns.empty() && table.columns.front().empty())
    throw fail(line, "no data rows below the header");
  return table;
}

}  // namespace drillwave::io
