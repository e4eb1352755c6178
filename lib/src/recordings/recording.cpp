#include "drillwave/recordings/recording.hpp"

#include <algorithm>
#include <cmath>

#include "drillwave/core/error.hpp"
#include "drillwave/io/csv.hpp"

namespace drillwave::recordings {

bool Recording::Has(const std::string& name) const {
  return std::find(names.begin(), names.end(), name) != names.end();
}

const std::vector<double>& Recording::Channel(const std::string& name) const {
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    std::string list;
    for (std::size_t j = 0; j < names.size() && j < 20; ++j) list += (list.empty() ? "" : ", ") + names[j];
    if (names.size() > 20) list += ", ... (" + std::to_string(names.size()) + " in all)";
    throw InputError(ReadableText(name), "no such channel in " + source + " (channels: " + list + ")");
  }
  return channels[static_cast<std::size_t>(it - names.begin())];
}

Recording LoadRecording(const std::string& csv_file) {
  const io::CsvTable table = io::ReadCsv(csv_file, io::CsvOptions{true});
  Recording r;
  r.source = csv_file;
  bool has_time = false;
  for (std::size_t j = 0; j < table.header.size(); ++j) {
    if (table.header[j] == "time_s") {
      r.time_s = table.columns[j];
      has_time = true;
    } else {
      r.names.push_back(table.header[j]);
      r.channels.push_back(table.columns[j]);
    }
  }
  if (!has_time) throw InputError(csv_file, "expected a column named time_s");
  if (r.names.empty()) throw InputError(csv_file, "no channel besides time_s");
  if (r.time_s.size() < 3)
    throw InputError(csv_file, "column time_s: " + std::to_string(r.time_s.size()) + " samples; at least 3 needed");
  std::vector<double> spacing;
  for (std::size_t i = 1; i < r.time_s.size(); ++i) {
    const double dt = r.time_s[i] - r.time_s[i - 1];
    if (!(dt > 0))
      throw InputError(csv_file, "column time_s: time does not increase at data row " + std::to_string(i + 1) + " (" +
                                     ReadableNumber(r.time_s[i]) + " s after " + ReadableNumber(r.time_s[i - 1]) +
                                     " s)");
    spacing.push_back(dt);
  }
  std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());
  r.sample_interval_s = spacing[spacing.size() / 2];
  return r;
}

}  // namespace drillwave::recordings
