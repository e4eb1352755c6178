#include "drillwave/io/csv.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "drillwave/core/error.hpp"

namespace drillwave::io {

void WriteCsv(std::ostream& out, const std::vector<std::string>& header,
              const std::vector<std::vector<double>>& columns) {
  if (header.size() != columns.size()) throw std::invalid_argument("WriteCsv: one header name per column");
  const std::size_t rows = columns.empty() ? 0 : columns.front().size();
  for (const auto& c : columns)
    if (c.size() != rows) throw std::invalid_argument("WriteCsv: columns of different lengths");
  for (std::size_t j = 0; j < header.size(); ++j) out << (j ? "," : "") << header[j];
  out << "\n";
  char buffer[32];
  std::string line;
  for (std::size_t i = 0; i < rows; ++i) {
    line.clear();
    for (std::size_t j = 0; j < columns.size(); ++j) {
      if (j) line += ',';
      const double v = columns[j][i];
      if (std::isnan(v)) line += "nan";
      else {
        std::snprintf(buffer, sizeof buffer, "%.10g", v);
        line += buffer;
      }
    }
    line += '\n';
    out << line;
  }
}

const std::vector<double>& CsvTable::Column(const std::string& name) const {
  for (std::size_t j = 0; j < header.size(); ++j)
    if (header[j] == name) return columns[j];
  throw std::out_of_range("no column named " + name);
}

CsvTable ReadCsv(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw InputError("", "cannot open CSV file " + file);
  CsvTable table;
  std::string line;
  if (!std::getline(in, line)) throw InputError("", file + ":1: empty file");
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    std::string name = line.substr(start, comma - start);
    while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
    table.header.push_back(name);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  table.columns.resize(table.header.size());
  long line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty() || line == "\r") continue;
    const char* p = line.c_str();
    for (std::size_t j = 0; j < table.header.size(); ++j) {
      double v = std::numeric_limits<double>::quiet_NaN();
      char* end = nullptr;
      if (*p != ',' && *p != '\0' && *p != '\r') {
        v = std::strtod(p, &end);
        if (end == p) throw InputError("", file + ":" + std::to_string(line_number) + ": not a number in column " + table.header[j]);
        p = end;
      }
      table.columns[j].push_back(v);
      if (j + 1 < table.header.size()) {
        if (*p != ',') throw InputError("", file + ":" + std::to_string(line_number) + ": expected " +
                                                std::to_string(table.header.size()) + " fields");
        ++p;
      }
    }
    if (*p != '\0' && *p != '\r')
      throw InputError("", file + ":" + std::to_string(line_number) + ": more fields than the header has");
  }
  return table;
}

}  // namespace drillwave::io
