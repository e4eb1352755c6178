#include "drillwave/estimation/recording_estimate.hpp"

#include <cmath>
#include <sstream>

#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/validity.hpp"
#include "drillwave/estimation/estimate_report.hpp"
#include "drillwave/estimation/metrics.hpp"
#include "drillwave/io/csv.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/io/svg_plot.hpp"

namespace drillwave::estimation {
namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// SI factor of a channel by its unit suffix, and its role: 's' speed, 't' torque, 'f' force; 0 if unknown.
std::pair<char, double> RoleOf(const std::string& name) {
  if (EndsWith(name, "_rpm")) return {'s', kRadPerSecondPerRpm};
  if (EndsWith(name, "_rad_s")) return {'s', 1};
  if (EndsWith(name, "_kNm")) return {'t', 1000};
  if (EndsWith(name, "_Nm")) return {'t', 1};
  if (EndsWith(name, "_kN")) return {'f', 1000};
  if (EndsWith(name, "_N")) return {'f', 1};
  return {0, 0};
}

bool IsDownhole(const std::string& name) {
  return name.rfind("bit_", 0) == 0 || name.rfind("tob", 0) == 0 || name.rfind("wob", 0) == 0;
}

std::vector<double> Scaled(const std::vector<double>& x, double factor) {
  std::vector<double> y(x);
  for (double& v : y) v *= factor;
  return y;
}

// The first of `names` the recording holds, in SI units (empty if none).
std::pair<std::string, std::vector<double>> Downhole(const recordings::Recording& r,
                                                     const std::vector<std::string>& names) {
  for (const std::string& name : names)
    if (r.Has(name)) return {name, Scaled(r.Channel(name), RoleOf(name).second)};
  return {"", {}};
}

nlohmann::json ErrorJson(const SeriesError& e, double unit) {
  return {{"rms", e.rms / unit}, {"bias", e.bias / unit}, {"measured_mean", e.measured_mean / unit},
          {"rms_percent_of_mean", e.measured_mean != 0 ? 100 * e.rms / std::abs(e.measured_mean) : 0.0},
          {"samples", e.samples}};
}

}  // namespace

double SiFactor(const std::string& channel) { return RoleOf(channel).second; }

SurfaceChannels ParseSurfaceChannels(const std::string& from, const recordings::Recording& recording) {
  SurfaceChannels c;
  std::stringstream in(from);
  std::string name;
  while (std::getline(in, name, ',')) {
    const std::string shown = "'" + ReadableText(name) + "' in '" + ReadableText(from) + "'";
    if (name.empty()) throw ParameterError("from", "an empty channel name in '" + ReadableText(from) + "'");
    if (IsDownhole(name))
      throw ParameterError("from", shown + " is a downhole channel: the estimate is made from surface channels only "
                                         "(downhole channels are only compared with it)");
    if (!recording.Has(name)) recording.Channel(name);  // throws, naming the channels there are
    const auto [role, factor] = RoleOf(name);
    std::string* slot = role == 's' ? &c.top_speed : role == 't' ? &c.top_torque : role == 'f' ? &c.hook_load : nullptr;
    if (!slot)
      throw ParameterError("from", shown + ": cannot tell its unit; expected a name ending in _rpm or _rad_s (top "
                                         "speed), _Nm or _kNm (top torque), _N or _kN (hook load)");
    if (!slot->empty())
      throw ParameterError("from", shown + ": two channels of one kind ('" + *slot + "' already)");
    *slot = name;
  }
  if (c.top_speed.empty())
    throw ParameterError("from", "'" + ReadableText(from) + "': no top speed channel (a name ending in _rpm or _rad_s)");
  return c;
}

SurfaceSignals SignalsFromRecording(const recordings::Recording& r, const SurfaceChannels& c) {
  const double dt = r.sample_interval_s;
  for (std::size_t i = 1; i < r.time_s.size(); ++i)
    if (std::abs(r.time_s[i] - r.time_s[i - 1] - dt) > 1e-3 * dt)
      throw InputError(r.source, "column time_s: the estimator needs a uniform time grid; the step at data row " +
                                     std::to_string(i + 1) + " is " + ReadableNumber(r.time_s[i] - r.time_s[i - 1]) +
                                     " s against the median " + ReadableNumber(dt) + " s");
  SurfaceSignals s;
  // The grid as uniform as the check allows: t_i = t_0 + i dt, so continuation shifts land where they should.
  for (std::size_t i = 0; i < r.time_s.size(); ++i) s.time_s.push_back(r.time_s.front() + static_cast<double>(i) * dt);
  s.top_speed_rad_s = Scaled(r.Channel(c.top_speed), RoleOf(c.top_speed).second);
  if (!c.top_torque.empty()) s.top_torque_Nm = Scaled(r.Channel(c.top_torque), RoleOf(c.top_torque).second);
  if (!c.hook_load.empty()) s.hook_load_N = Scaled(r.Channel(c.hook_load), RoleOf(c.hook_load).second);
  return s;
}

void FuseTelemetry(const recordings::Recording& r, const std::string& channels, TelemetryFusion fusion, bool read_delay,
                   BitEstimate& e) {
  ThrowIfInvalid(fusion);
  std::vector<std::pair<std::string, std::vector<double>*>> fused;
  std::stringstream in(channels);
  std::string name;
  while (std::getline(in, name, ',')) {
    const std::string shown = "'" + ReadableText(name) + "' in '" + ReadableText(channels) + "'";
    const char role = RoleOf(name).first;
    if (!IsDownhole(name) || role == 0)
      throw ParameterError("fuse", shown + ": expected a downhole channel (bit_rpm or bit_rad_s; tob_Nm, bit_torque_Nm "
                                           "or tob_kNm; wob_N or wob_kN)");
    if (!r.Has(name)) r.Channel(name);  // throws, naming the channels there are
    fused.push_back({name, role == 's' ? &e.bit_speed_rad_s : role == 't' ? &e.bit_torque_Nm : &e.wob_N});
  }
  if (fused.empty()) throw ParameterError("fuse", "no channel named in '" + ReadableText(channels) + "'");
  std::string delay_from = "given";
  if (read_delay) {
    const auto [speed_name, speed] = Downhole(r, {"bit_rpm", "bit_rad_s"});
    if (speed.empty())
      throw ParameterError("fuse", "the telemetry delay is read from a bit speed channel (bit_rpm or bit_rad_s), which "
                                   "the recording does not hold: give the delay (telemetry_delay_s)",
                           {"telemetry_delay_s"});
    const TelemetryLag lag = ReadTelemetryLag(e.time_s, e.bit_speed_rad_s, speed, -1e300, 1e300, 10.0);
    if (!lag.found)
      throw ParameterError("fuse", "no telemetry delay read from '" + speed_name + "' (correlation " +
                                       ReadableNumber(lag.correlation) + " at " + ReadableNumber(lag.lag_s) +
                                       " s): a channel without delay would be copied into the estimate, not fused; "
                                       "give the delay (telemetry_delay_s) if it is known",
                           {"telemetry_delay_s"});
    fusion.telemetry_delay_s = lag.lag_s;
    delay_from = "read from " + speed_name;
  }
  const double dt = r.sample_interval_s;
  std::ostringstream note;
  note << "downhole telemetry fused at a delay of " << Significant(fusion.telemetry_delay_s, 4) << " s (" << delay_from
       << "), its innovation low-passed over " << Significant(fusion.innovation_time_constant_s, 4) << " s:";
  for (auto& [channel, estimate] : fused) {
    const std::vector<double> telemetry = Scaled(r.Channel(channel), RoleOf(channel).second);
    const std::vector<double> before = *estimate;
    *estimate = FuseDelayedTelemetry(before, telemetry, dt, fusion);
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < before.size(); ++i)
      if (std::isfinite(before[i])) sum += (*estimate)[i] - before[i], ++count;
    note << " " << channel << " corrected by " << Significant(count ? sum / count / RoleOf(channel).second : 0.0, 3)
         << " on average;";
  }
  note << " the stuck flag is the surface estimate's";
  e.notes.push_back(note.str());
}

nlohmann::json EstimateSummary(const recordings::Recording& r, const BitEstimate& e, const ScoreWindow& w) {
  nlohmann::json j;
  j["method"] = e.method;
  j["latency_s"] = e.latency_s;
  j["stuck_threshold_rpm"] = e.stuck_threshold_rad_s / kRadPerSecondPerRpm;
  j["stuck_rule"] =
      "the measured bit stuck where |bit speed| is below 5 % of the median top speed; the estimate where it does not "
      "turn forward by more than that and its band (a string), or where its friction regime holds it or |speed| is "
      "below that (a two-mass model)";
  j["notes"] = e.notes;
  nlohmann::json events = nlohmann::json::array();
  for (const StuckEvent& ev : StuckEvents(e.time_s, e.stuck))
    events.push_back({{"stick_begin_s", ev.begin_s}, {"stick_end_s", ev.end_s}});
  j["stuck_events"] = events;
  nlohmann::json windows = nlohmann::json::array();
  for (const SeverityWindow& s : SeverityIndex(e.time_s, e.bit_speed_rad_s, e.stuck, 5.0))
    windows.push_back({{"begin_s", s.begin_s}, {"end_s", s.end_s}, {"severity", s.severity},
                       {"stuck_fraction", s.stuck_fraction}});
  j["severity_windows"] = windows;
  j["severity_definition"] = "(max - min) / (2 mean) of the estimated bit speed over 5-s windows";
  nlohmann::json m = nlohmann::json::object();
  const auto [speed_name, speed] = Downhole(r, {"bit_rpm", "bit_rad_s"});
  if (!speed.empty()) {
    m["bit_rpm"] = ErrorJson(CompareSeries(e.time_s, e.bit_speed_rad_s, speed, w.begin_s, w.end_s), kRadPerSecondPerRpm);
    m["bit_rpm"]["channel"] = speed_name;
    const StuckScore s = ScoreStuck(e.time_s, e.bit_speed_rad_s, e.stuck, speed, e.stuck_threshold_rad_s, w.begin_s,
                                    w.end_s);
    m["stuck"] = {{"precision", s.precision}, {"recall", s.recall}, {"f1", s.f1},
                  {"measured_stuck_fraction",
                   s.samples ? static_cast<double>(s.measured_stuck) / static_cast<double>(s.samples) : 0.0},
                  {"samples", s.samples}};
    // A delayed downhole channel (telemetry) scores the estimate late: the error at the delay it shows, besides.
    const TelemetryLag lag = ReadTelemetryLag(e.time_s, e.bit_speed_rad_s, speed, w.begin_s, w.end_s, 10.0);
    if (lag.found) {
      const double delay = lag.lag_s;
      const std::size_t shift = static_cast<std::size_t>(std::lround(delay / r.sample_interval_s));
      const std::vector<double> aligned = Advanced(speed, shift);
      nlohmann::json a = ErrorJson(CompareSeries(e.time_s, e.bit_speed_rad_s, aligned, w.begin_s, w.end_s), kRadPerSecondPerRpm);
      const StuckScore sa = ScoreStuck(e.time_s, e.bit_speed_rad_s, e.stuck, aligned, e.stuck_threshold_rad_s,
                                       w.begin_s, w.end_s);
      a["stuck_f1"] = sa.f1;
      a["delay_s"] = delay;
      a["correlation"] = lag.correlation;
      a["correlation_at_zero"] = lag.correlation_at_zero;
      m["bit_rpm_at_downhole_delay"] = a;
    }
  }
  const auto [torque_name, torque] = Downhole(r, {"tob_Nm", "bit_torque_Nm", "tob_kNm"});
  if (!torque.empty()) {
    m["bit_torque_Nm"] = ErrorJson(CompareSeries(e.time_s, e.bit_torque_Nm, torque, w.begin_s, w.end_s), 1);
    m["bit_torque_Nm"]["channel"] = torque_name;
  }
  const auto [wob_name, wob] = Downhole(r, {"wob_N", "wob_kN"});
  if (!wob.empty()) {
    m["wob_N"] = ErrorJson(CompareSeries(e.time_s, e.wob_N, wob, w.begin_s, w.end_s), 1);
    m["wob_N"]["channel"] = wob_name;
    if (m.contains("bit_rpm_at_downhole_delay")) {  // the same telemetry delays every downhole channel
      const double delay = m["bit_rpm_at_downhole_delay"]["delay_s"].get<double>();
      const std::size_t shift = static_cast<std::size_t>(std::lround(delay / r.sample_interval_s));
      m["wob_N_at_downhole_delay"] = ErrorJson(CompareSeries(e.time_s, e.wob_N, Advanced(wob, shift), w.begin_s,
                                                             w.end_s), 1);
      m["wob_N_at_downhole_delay"]["delay_s"] = delay;
    }
  }
  if (!m.empty()) {
    m["window_s"] = {std::max(w.begin_s, r.time_s.front()), std::min(w.end_s, r.time_s.back())};
    m["note"] = "downhole channels read only here, after the estimate, to score it";
  }
  j["errors"] = m;
  return j;
}

void WriteEstimate(const recordings::Recording& r, const BitEstimate& e, const nlohmann::json& summary,
                   const std::string& dir) {
  io::OutputDirectory out(dir);
  std::vector<double> stuck(e.stuck.begin(), e.stuck.end());
  io::WriteCsv(out.Open("estimate.csv"),
               {"time_s", "bit_rpm", "bit_rpm_band", "bit_torque_Nm", "bit_torque_Nm_band", "wob_N", "wob_N_band",
                "bit_stuck"},
               {e.time_s, Scaled(e.bit_speed_rad_s, 1 / kRadPerSecondPerRpm), Scaled(e.bit_speed_band_rad_s, 1 / kRadPerSecondPerRpm),
                e.bit_torque_Nm, e.bit_torque_band_Nm, e.wob_N, e.wob_band_N, stuck});
  out.Open("estimate.json") << summary.dump(2) << "\n";
  io::Figure figure;
  figure.title = "Bit estimated from the surface (" + e.method + ")";
  figure.x_label = "time [s]";
  // The band's two edges as one series (a NaN between them breaks the line), so that both wear its legend colour;
  // the measurement first, the estimate drawn last, on top.
  auto band = [&](const std::vector<double>& x, const std::vector<double>& b, double unit) {
    io::Series s{"band (2 sigma)", {}, {}};
    for (double sign : {1.0, -1.0}) {
      for (std::size_t i = 0; i < x.size(); ++i) s.x.push_back(e.time_s[i]), s.y.push_back((x[i] + sign * b[i]) / unit);
      s.x.push_back(std::nan("")), s.y.push_back(std::nan(""));
    }
    return s;
  };
  auto panel = [&](const std::string& label, const std::vector<double>& est, const std::vector<double>& b,
                   double unit, const std::vector<std::string>& measured_names) {
    io::Panel p{label, {}};
    const auto [name, measured] = Downhole(r, measured_names);
    if (!measured.empty()) p.series.push_back({"measured " + name, r.time_s, Scaled(measured, 1 / unit)});
    p.series.push_back(band(est, b, unit));
    p.series.push_back({"estimate", e.time_s, Scaled(est, 1 / unit)});
    figure.panels.push_back(p);
  };
  panel("bit speed [rpm]", e.bit_speed_rad_s, e.bit_speed_band_rad_s, kRadPerSecondPerRpm, {"bit_rpm", "bit_rad_s"});
  panel("torque on bit [N m]", e.bit_torque_Nm, e.bit_torque_band_Nm, 1, {"tob_Nm", "bit_torque_Nm", "tob_kNm"});
  panel("weight on bit [N]", e.wob_N, e.wob_band_N, 1, {"wob_N", "wob_kN"});
  figure.panels.push_back({"bit stuck", {{"estimated stuck", e.time_s, stuck}}});
  io::WriteSvg(figure, out.Open("plot.svg"));
  WriteEstimateHtml(r.source, summary, figure, out.Open("report.html"));
  out.Commit();
}

}  // namespace drillwave::estimation
