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

// Appends one number as WriteCsv writes it: printf's "%.10g" text ("0.1", "-0", "1e-300", "1.234567891e+300", "inf",
// "-inf"), any NaN as "nan".
void AppendCsvNumber(std::string& text, double v);

struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<double>> columns;  // columns[j] belongs to header[j]

  // The column named `name`; std::out_of_range if there is none.
  const std::vector<double>& Column(const std::string& name) const;
};

struct CsvOptions {
  // Recordings: every cell must be a finite number (no blank cells, nan, inf or 1e999), and there must be a row.
  bool finite_only = false;

  // Nothing of a flag to check: always true. There for the options structs' common contract (core/validity.hpp).
  bool IsValid(std::string* /*error*/) const { return true; }
};

// Reads a header line and rows of comma-separated numbers. Unless options.finite_only, empty fields and "nan" read
// as NaN. Blank lines are skipped; "\r\n" line ends are accepted. Throws InputError("", "cannot open CSV file
// <file>"), or InputError("", "<file>:<line>: ...") naming the column if a row has a different number of fields than
// the header, a field is not a number, or (finite_only) a cell is blank or not finite; and for a header with an
// empty, duplicate or non-UTF-8 name.
CsvTable ReadCsv(const std::string& file, const CsvOptions& options = {});

}  // namespace drillwave::io
