#pragma once
// Recordings (DESIGN.md §5), what diagnosis and the virtual sensor read: a CSV of a time column and named channels, read as it is. Channel names
// carry their units (top_rpm, tob_Nm, wob_kN, ...), as drillwave's own trajectories do.
#include <string>
#include <vector>

namespace drillwave::recordings {

struct Recording {
  std::string source;  // the file it came from
  std::vector<double> time_s;
  std::vector<std::string> names;
  std::vector<std::vector<double>> channels;  // channels[j] belongs to names[j]
  double sample_interval_s = 0;               // median spacing of time_s

  bool Has(const std::string& name) const;
  // The channel named `name`; throws InputError naming it and listing the channels there are.
  const std::vector<double>& Channel(const std::string& name) const;
};

// Reads a CSV with a "time_s" column (strictly increasing) and at least one other column. Throws InputError for a
// missing file, a missing or non-increasing time column, or non-numeric fields (ReadCsv's messages).
Recording LoadRecording(const std::string& csv_file);

}  // namespace drillwave::recordings
