#pragma once
// CSV tables of named columns: trajectories out, recordings in.
#include <ostream>
#include <string>
#include <vector>

namespace drillwave::io {

// Header line, then one row per sample; 10 significant digits; NaN as "nan".
void WriteCsv(std::ostream& out, const std::vector<std::string>& header,
              const std::vector<std::vector<double>>& columns);

struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<double>> columns;
  const std::vector<double>& Column(const std::string& name) const;  // std::out_of_range if absent
};

// Empty fields and "nan" read as NaN; InputError("", "file:line: ...") on ragged rows or bad numbers.
CsvTable ReadCsv(const std::string& file);

}  // namespace drillwave::io
