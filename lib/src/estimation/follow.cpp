#include "drillwave/estimation/follow.hpp"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>

#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/validity.hpp"
#include "drillwave/recordings/signals.hpp"
#include "drillwave/estimation/smoothing.hpp"

namespace drillwave::estimation {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMinWarmupS = 2;
constexpr double kWarmupLatencies = 4;
// Estimates are given out in stretches of at least this much recording time (a recomputation per stretch).
constexpr double kStretchS = 0.1;

std::vector<std::string> SplitCells(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

std::string Trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\r' || s.back() == ' ')) s.pop_back();
  std::size_t first = 0;
  while (first < s.size() && s[first] == ' ') ++first;
  return s.substr(first);
}

}  // namespace

GrowingCsv::GrowingCsv(const std::string& path) : source_(path == "-" ? "standard input" : path) {
  fd_ = path == "-" ? 0 : ::open(path.c_str(), O_RDONLY);
  stream_ = path == "-";
  if (fd_ < 0) throw InputError(path, std::string("cannot open the recording: ") + std::strerror(errno));
}

GrowingCsv::~GrowingCsv() {
  if (fd_ > 0) ::close(fd_);
}

bool GrowingCsv::Read(std::vector<std::vector<double>>& rows, double wait_s) {
  if (stream_) {  // wait for data; a regular file's end is only "nothing new yet"
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(wait_s * 1000)) <= 0) return true;
  }
  char buffer[1 << 16];
  const ssize_t got = ::read(fd_, buffer, sizeof buffer);
  if (got < 0) {
    if (errno == EINTR || errno == EAGAIN) return true;
    throw InputError(source_, std::string("cannot read the recording: ") + std::strerror(errno));
  }
  if (got == 0) {
    if (stream_ && !partial_.empty()) ParseLine(partial_, rows), partial_.clear();
    return !stream_;
  }
  partial_.append(buffer, static_cast<std::size_t>(got));
  std::size_t begin = 0, end;
  while ((end = partial_.find('\n', begin)) != std::string::npos) {
    ParseLine(partial_.substr(begin, end - begin), rows);
    begin = end + 1;
  }
  partial_.erase(0, begin);
  return true;
}

void GrowingCsv::ParseLine(const std::string& raw, std::vector<std::vector<double>>& rows) {
  ++line_;
  const std::string line = Trimmed(raw);
  if (line.empty()) return;
  const std::vector<std::string> cells = SplitCells(line);
  if (names_.empty()) {
    for (const std::string& c : cells) names_.push_back(Trimmed(c));
    if (names_.empty() || names_.front() != "time_s")
      throw InputError(source_, "line 1: the first column must be time_s; got '" + ReadableText(line) + "'");
    return;
  }
  if (cells.size() != names_.size())
    throw InputError(source_, "line " + std::to_string(line_) + ": " + std::to_string(cells.size()) +
                                  " cells where the header has " + std::to_string(names_.size()));
  std::vector<double> row;
  for (std::size_t j = 0; j < cells.size(); ++j) {
    const std::string cell = Trimmed(cells[j]);
    char* stop = nullptr;
    const double v = std::strtod(cell.c_str(), &stop);
    if (cell.empty() || *stop != '\0' || !std::isfinite(v))
      throw InputError(source_, "line " + std::to_string(line_) + ", column " + names_[j] + ": '" +
                                    ReadableText(cell) + "' is not a finite number");
    row.push_back(v);
  }
  if (row[0] <= last_time_)
    throw InputError(source_, "line " + std::to_string(line_) + ", column time_s: " + ReadableNumber(row[0]) +
                                  " s does not increase");
  last_time_ = row[0];
  rows.push_back(std::move(row));
}

LiveEstimator::LiveEstimator(EstimatorModel model, EstimateOptions options, std::vector<std::string> names,
                             SurfaceChannels channels)
    : model_(std::move(model)), options_(options), names_(std::move(names)), channels_(std::move(channels)),
      columns_(names_.size()) {
  ThrowIfInvalid(options_);
}

std::vector<EstimateRow> LiveEstimator::Push(const std::vector<std::vector<double>>& rows) {
  for (const std::vector<double>& row : rows)
    for (std::size_t j = 0; j < columns_.size(); ++j) columns_[j].push_back(row[j]);
  const std::vector<double>& t = columns_[0];
  if (t.size() < 8) return {};
  if (latency_s_ < 0) {  // the first warm-up: the threshold and the latency are read off it
    if (t.back() - t.front() < kMinWarmupS) return {};
    return Estimate(false);
  }
  // A new stretch once kStretchS more of the recording has passed its latency.
  const double ready_until = t.back() - latency_s_;
  if (given_out_ >= t.size() || ready_until < t[given_out_] + kStretchS) return {};
  return Estimate(false);
}

std::vector<EstimateRow> LiveEstimator::Finish() {
  if (columns_[0].size() < 8) return {};
  return Estimate(true);
}

std::vector<EstimateRow> LiveEstimator::Estimate(bool final_stretch) {
  const std::vector<double>& t = columns_[0];
  const std::size_t n = t.size();
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(names_.begin(), names_.end(), name) - names_.begin());
  };
  if (options_.stuck_threshold_rad_s <= 0)
    options_.stuck_threshold_rad_s =
        options_.stuck_fraction * MedianAbs(columns_[column(channels_.top_speed)]) * SiFactor(channels_.top_speed);
  // The window: a warm-up before the first row not given out yet.
  std::size_t start = 0;
  if (given_out_ > 0) {
    const double from = t[given_out_] - warmup_s_;
    start = static_cast<std::size_t>(std::lower_bound(t.begin(), t.end(), from) - t.begin());
  }
  SurfaceSignals s;
  const double dt = (t.back() - t[start]) / static_cast<double>(n - 1 - start);
  for (std::size_t i = start; i < n; ++i) s.time_s.push_back(t[start] + static_cast<double>(i - start) * dt);
  auto slice = [&](const std::string& name) {
    std::vector<double> x;
    if (name.empty()) return x;
    const std::vector<double>& c = columns_[column(name)];
    const double f = SiFactor(name);
    for (std::size_t i = start; i < n; ++i) x.push_back(c[i] * f);
    return x;
  };
  s.top_speed_rad_s = slice(channels_.top_speed);
  s.top_torque_Nm = slice(channels_.top_torque);
  s.hook_load_N = slice(channels_.hook_load);
  const BitEstimate e = EstimateBit(model_, s, options_);
  if (latency_s_ < 0) {
    latency_s_ = e.latency_s;
    warmup_s_ = std::max(kMinWarmupS, kWarmupLatencies * latency_s_);
  }
  method_ = e.method;
  notes_ = e.notes;
  std::vector<EstimateRow> out;
  const double ready_until = final_stretch ? INFINITY : t.back() - latency_s_;
  for (; given_out_ < n && t[given_out_] <= ready_until; ++given_out_) {
    const std::size_t k = given_out_ - start;
    out.push_back({t[given_out_], e.bit_speed_rad_s[k], e.bit_speed_band_rad_s[k], e.bit_torque_Nm[k],
                   e.bit_torque_band_Nm[k], e.wob_N[k], e.wob_band_N[k], e.stuck[k] != 0});
  }
  return out;
}

recordings::Recording LiveEstimator::Recording() const {
  recordings::Recording r;
  r.source = "live";
  r.time_s = columns_[0];
  r.names.assign(names_.begin() + 1, names_.end());
  r.channels.assign(columns_.begin() + 1, columns_.end());
  r.sample_interval_s =
      r.time_s.size() > 1 ? (r.time_s.back() - r.time_s.front()) / static_cast<double>(r.time_s.size() - 1) : 0.0;
  return r;
}

BitEstimate FromRows(const std::vector<EstimateRow>& rows, double stuck_threshold_rad_s, double latency_s,
                     std::string method, std::vector<std::string> notes) {
  BitEstimate e;
  for (const EstimateRow& r : rows) {
    e.time_s.push_back(r.time_s);
    e.bit_speed_rad_s.push_back(r.bit_speed_rad_s);
    e.bit_speed_band_rad_s.push_back(r.bit_speed_band_rad_s);
    e.bit_torque_Nm.push_back(r.bit_torque_Nm);
    e.bit_torque_band_Nm.push_back(r.bit_torque_band_Nm);
    e.wob_N.push_back(r.wob_N);
    e.wob_band_N.push_back(r.wob_band_N);
    e.stuck.push_back(r.stuck);
  }
  e.stuck_threshold_rad_s = stuck_threshold_rad_s;
  e.latency_s = latency_s;
  e.method = std::move(method);
  e.notes = std::move(notes);
  return e;
}

}  // namespace drillwave::estimation
