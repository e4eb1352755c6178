#pragma once
// The virtual sensor on a recording: which of its channels are the surface signals (--from), the estimate, its errors
// against the downhole channels the recording may hold (read only for the scores, after the estimate), and the
// output folder (estimate.csv, estimate.json, plot.svg).
#include <string>

#include <nlohmann/json.hpp>

#include "drillwave/estimation/estimate.hpp"
#include "drillwave/estimation/telemetry_fusion.hpp"
#include "drillwave/recordings/recording.hpp"

namespace drillwave::estimation {

// Channels named in --from, by role. A channel's unit is read from its name's suffix: _rpm or _rad_s a speed, _Nm or
// _kNm a torque, _N or _kN a force (the hook load).
struct SurfaceChannels {
  std::string top_speed, top_torque, hook_load;
};

// Parses "top_rpm,top_torque_kNm,hookload_kN". Throws ParameterError("from", ...) naming the value for an unknown
// channel, a unit it cannot read, two channels of one role, a missing speed, or a downhole channel (a name starting
// with bit_, tob or wob: the estimate never reads them).
SurfaceChannels ParseSurfaceChannels(const std::string& from, const recordings::Recording& recording);

// The factor to SI units of a channel by its name's suffix (_rpm, _rad_s, _kNm, _Nm, _kN, _N); 0 if unknown.
double SiFactor(const std::string& channel);

// The named channels in SI units on the recording's grid (InputError naming time_s if it is not uniform).
SurfaceSignals SignalsFromRecording(const recordings::Recording& recording, const SurfaceChannels& channels);

// Downhole telemetry fused into the estimate (telemetry_fusion.hpp): each channel named in `channels`
// ("bit_rpm,wob_kN": a bit speed, torque on bit or weight on bit channel the recording holds) into its estimate. The
// delay is fusion.telemetry_delay_s, or, with read_delay, the lag ReadTelemetryLag finds between the estimate and the
// recording's bit speed channel (up to 10 s). The stuck flag stays the surface estimate's. Adds a note to the
// estimate's notes. Throws ParameterError("fuse", ...) naming the channel where it is not a downhole one or not in the
// recording, or where no delay is found; ParameterError for fusion options that are not valid.
void FuseTelemetry(const recordings::Recording& recording, const std::string& channels, TelemetryFusion fusion,
                   bool read_delay, BitEstimate& estimate);

struct ScoreWindow {
  double begin_s = -1e300, end_s = 1e300;
};

// estimate.json's content: method, latency, stuck threshold, notes, stick-slip events, severity windows, and, for
// each downhole channel the recording holds (bit_rpm or bit_rad_s; tob_Nm, bit_torque_Nm or tob_kNm; wob_N or
// wob_kN), the error over `window` (RMS, bias, measured mean; for the bit speed in rpm and stuck precision, recall
// and F1 with the same threshold on the measurement).
nlohmann::json EstimateSummary(const recordings::Recording& recording, const BitEstimate& estimate,
                               const ScoreWindow& window);

// estimate.csv (time_s, bit_rpm, bit_rpm_band, bit_torque_Nm, bit_torque_Nm_band, wob_N, wob_N_band, bit_stuck),
// estimate.json, plot.svg (estimate against the measured downhole channels where present) and report.html (the
// figure with estimate.json's errors, events and severity: estimate_report.hpp) into `dir`, all or nothing.
void WriteEstimate(const recordings::Recording& recording, const BitEstimate& estimate, const nlohmann::json& summary,
                   const std::string& dir);

}  // namespace drillwave::estimation
