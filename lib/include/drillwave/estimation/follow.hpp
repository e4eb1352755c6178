#pragma once
// The virtual sensor live (issue 34, --follow): a recording read while it is being written (a CSV file growing on
// disk, or standard input), each estimate given out as soon as the estimator's latency allows.
//
// The estimate of a stretch is recomputed over a sliding window that reaches a warm-up before the first sample not
// yet given out: the estimators are either stateless over a bounded reach (the wave continuation: one travel time
// each way) or forget their start within a fraction of a second (the observers), so two seconds of warm-up, or four
// latencies if more, make the live estimate the batch one up to that forgotten start. The stuck threshold, which the
// batch estimate reads off the whole recording, is read once off the first warm-up and then held.
#include <limits>
#include <string>
#include <vector>

#include "drillwave/recordings/recording.hpp"
#include "drillwave/estimation/estimate.hpp"
#include "drillwave/estimation/recording_estimate.hpp"

namespace drillwave::estimation {

// Complete lines of a CSV that is still being written: a file read on from where the last call stopped, or a
// stream (standard input). A line without its newline yet is kept for the next call.
class GrowingCsv {
 public:
  explicit GrowingCsv(const std::string& path);  // "-": standard input; InputError if the file cannot be opened
  ~GrowingCsv();
  GrowingCsv(const GrowingCsv&) = delete;
  GrowingCsv& operator=(const GrowingCsv&) = delete;
  // Appends the rows complete now (standard input: waiting up to wait_s for them); false when no more can come (the
  // stream's end; a file never ends by itself: the caller decides how long it may stay idle). The first line is the
  // header (time_s first). Throws InputError naming the source and line (and column) for a cell that is no finite
  // number, a row of the wrong width or a time that does not increase.
  bool Read(std::vector<std::vector<double>>& rows, double wait_s);
  const std::vector<std::string>& names() const { return names_; }
  const std::string& source() const { return source_; }

 private:
  void ParseLine(const std::string& line, std::vector<std::vector<double>>& rows);

  std::string source_;
  int fd_ = -1;
  bool stream_ = false;  // standard input: its end is the recording's end
  std::string partial_;
  std::vector<std::string> names_;
  long line_ = 0;
  double last_time_ = -std::numeric_limits<double>::infinity();
};

// One row of estimate.csv.
struct EstimateRow {
  double time_s, bit_speed_rad_s, bit_speed_band_rad_s, bit_torque_Nm, bit_torque_band_Nm, wob_N, wob_band_N;
  bool stuck;
};

class LiveEstimator {
 public:
  // Throws ParameterError for options that are not valid.
  LiveEstimator(EstimatorModel model, EstimateOptions options, std::vector<std::string> names,
                SurfaceChannels channels);
  // Adds rows (the recording's columns in `names` order) and returns the estimates that became final.
  std::vector<EstimateRow> Push(const std::vector<std::vector<double>>& rows);
  // The input has ended: the estimates of the rest.
  std::vector<EstimateRow> Finish();

  // Everything read so far as a recording (to score the estimate against its downhole channels at the end).
  recordings::Recording Recording() const;
  double latency_s() const { return latency_s_; }
  double stuck_threshold_rad_s() const { return options_.stuck_threshold_rad_s; }
  const std::string& method() const { return method_; }
  const std::vector<std::string>& notes() const { return notes_; }

 private:
  std::vector<EstimateRow> Estimate(bool final_stretch);

  EstimatorModel model_;
  EstimateOptions options_;
  std::vector<std::string> names_;
  SurfaceChannels channels_;
  std::vector<std::vector<double>> columns_;
  std::size_t given_out_ = 0;  // rows whose estimate was given out
  double latency_s_ = -1, warmup_s_ = 0;
  std::string method_;
  std::vector<std::string> notes_;
};

// All rows as a BitEstimate (for estimate.json and plot.svg at the end).
BitEstimate FromRows(const std::vector<EstimateRow>& rows, double stuck_threshold_rad_s, double latency_s,
                     std::string method, std::vector<std::string> notes);

}  // namespace drillwave::estimation
