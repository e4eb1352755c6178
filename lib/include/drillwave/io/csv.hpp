#pragma once
// CSV tables of named numeric columns: trajectories out, recordings in.
#include <ostream>
#include <string>
#include <vector>

namespace drillwave::io {

// A header line, then one row per sample; numbers with 10 significant digits, NaN as "nan". Nothing is quoted:
// throws std::invalid_argument if a name contains ',', '"' or a line break, if the header and the columns differ
// in number, or if the columns differ in length.
void WriteCsv(std::ostream& out, const std::vector<std::string>& header,
              const std::vector<std::vector<double>>& columns);

struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<double>> columns;  // columns[j] belongs to header[j]

  // The column named `name`; std::out_of_range if there is none.
  const std::vector<double>& Column(const std::string& name) const;
};

// Reads a header line and rows of comma-separated numbers. Empty fields and "nan" read as NaN; blank lines are
// skipped; "\r\n" line ends are accepted. Throws InputError("", "cannot open CSV file <file>"), or
// InputError("", "<file>:<line>: ...") if a row has a different number of fields than the header or a field is
// not a number.
CsvTable ReadCsv(const std::string& file);

}  // namespace drillwave::io
