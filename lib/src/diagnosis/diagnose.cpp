#include "drillwave/diagnosis/diagnose.hpp"

#include <algorithm>
#include <cmath>

#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/io/json_reader.hpp"

namespace drillwave::diagnosis {
namespace {

const FeatureDifference* Find(const Comparison& c, const std::string& name) {
  for (const FeatureDifference& d : c.features)
    if (d.feature == name) return &d;
  return nullptr;
}

}  // namespace

Diagnosis Diagnose(const Recording& recording, const cases::RunResult& model, const std::vector<ChannelMap>& maps,
                   double window_begin_s, double window_end_s) {
  Diagnosis dg;
  dg.comparison = Compare(recording, model, maps, window_begin_s, window_end_s);
  const Comparison& c = dg.comparison;
  std::vector<std::string> explained;

  // 1. The top drive lets the string's oscillation through: its speed fluctuates well beyond the sensor noise and
  //    beyond the model's.
  if (c.recording.top_drive_soft && c.recording.top_speed_fluctuation > 3 * c.model.top_speed_fluctuation) {
    dg.hypotheses.push_back({"soft_topdrive",
                             "top speed fluctuates " + Fixed(c.recording.top_speed_fluctuation_ratio, 1) +
                                 "x its sensor noise; the model's drive holds it (" +
                                 Fixed(c.model.top_speed_fluctuation, 3) + " against " +
                                 Fixed(c.recording.top_speed_fluctuation, 3) + ")",
                             std::nan(""), ""});
    explained.push_back("top_speed_fluctuation");
  }
  // 2. The recording needs more torque at the top than the model to turn the same bit: torque lost along the string
  //    (side friction in a deviated or tortuous hole). Its size is the difference of the means.
  const FeatureDifference* torque = nullptr;
  for (const char* name : {"top_torque_kNm mean", "top_torque_Nm mean"})
    if (!torque) torque = Find(c, name);
  if (torque && std::isfinite(torque->relative) && torque->relative < -0.15) {
    dg.hypotheses.push_back({"side_friction",
                             "mean top torque " + Fixed(torque->model, 3) + " in the model against " +
                                 Fixed(torque->recording, 3) + " recorded (" + Fixed(100 * torque->relative, 0) +
                                 " %): torque lost along the string",
                             torque->recording - torque->model, torque->feature.find("kNm") != std::string::npos ? "kN m" : "N m"});
    explained.push_back(torque->feature);
  }
  // 3. The bit sticks in the recording but not in the model: the model's bit friction lacks velocity weakening.
  //    Unless torque lost along the string was found: that alone moves the operating point into stick-slip, so it is
  //    the simpler explanation until a refit with it says otherwise (one effect at a time, the most evident first).
  const bool torque_lost = std::any_of(dg.hypotheses.begin(), dg.hypotheses.end(),
                                       [](const Hypothesis& h) { return h.effect == "side_friction"; });
  if (!torque_lost && c.recording.stick_fraction > 0.05 && c.model.stick_fraction < 0.01) {
    dg.hypotheses.push_back({"stribeck",
                             "the bit is stuck " + Fixed(100 * c.recording.stick_fraction, 1) +
                                 " % of the time in the recording and " + Fixed(100 * c.model.stick_fraction, 1) +
                                 " % in the model: friction that weakens with speed",
                             std::nan(""), ""});
    explained.push_back("stick_fraction");
  }
  // 4. The weight on bit barely moves in the recording while the coupled model's swings: no regenerative axial
  //    coupling (constant depth of cut, WOB held).
  const FeatureDifference* wob = nullptr;
  for (const char* name : {"wob_kN std", "wob_N std"})
    if (!wob) wob = Find(c, name);
  const FeatureDifference* wob_mean = nullptr;
  for (const char* name : {"wob_kN mean", "wob_N mean"})
    if (!wob_mean) wob_mean = Find(c, name);
  if (wob && wob_mean && wob->model > 0.05 * std::abs(wob_mean->model) && wob->recording < 0.25 * wob->model) {
    dg.hypotheses.push_back({"axial_coupling_off",
                             "WOB spread " + Fixed(wob->recording, 3) + " recorded against " + Fixed(wob->model, 3) +
                                 " in the coupled model: the axial motion does not feed back on the cut",
                             std::nan(""), ""});
    explained.push_back(wob->feature);
  }
  for (const FeatureDifference& d : c.features) {
    if (!std::isfinite(d.relative) || std::abs(d.relative) < 0.3) continue;
    if (std::find(explained.begin(), explained.end(), d.feature) != explained.end()) continue;
    if (d.feature == "top_speed_fluctuation" || d.feature.find("top_rpm std") == 0 || d.feature.find("hookload") == 0)
      continue;  // sensor noise, which the model does not carry
    dg.unexplained.push_back(d.feature + ": model " + Fixed(d.model, 3) + " against " + Fixed(d.recording, 3) + " (" +
                             Fixed(100 * d.relative, 0) + " %)");
  }
  return dg;
}

nlohmann::json DiagnosisToJson(const Diagnosis& d) {
  nlohmann::json hypotheses = nlohmann::json::array();
  for (const Hypothesis& h : d.hypotheses)
    hypotheses.push_back({{"effect", h.effect},
                          {"evidence", h.evidence},
                          {"estimate", std::isfinite(h.estimate) ? nlohmann::json(h.estimate) : nlohmann::json(nullptr)},
                          {"unit", h.unit}});
  return {{"hypotheses", hypotheses}, {"unexplained", d.unexplained}, {"comparison", ComparisonToJson(d.comparison)}};
}

nlohmann::json CaseFromSidecar(const nlohmann::json& sidecar, nlohmann::json doc, double warmup_s,
                               const std::string& source) {
  // Every value is checked here, against the sidecar's own path and value, before it is turned into case fields
  // (whose messages would name the generated case instead).
  auto where = [&](const std::string& pointer) { return source + ": " + pointer; };
  if (!sidecar.is_object())
    throw InputError(where("/"), "expected an object (a synthetic recording's sidecar), got " +
                                     ReadableText(sidecar.dump()));
  auto number = [&](const std::string& pointer, io::Range range) {
    const nlohmann::json::json_pointer ptr(pointer);
    if (!sidecar.contains(ptr)) throw InputError(where(pointer), "missing (" + range.Describe() + ")");
    const nlohmann::json& v = sidecar.at(ptr);
    const double x = v.is_number() ? v.get<double>() : std::nan("");
    if (!range.Contains(x))
      throw InputError(where(pointer), "expected " + range.Describe() + ", got " +
                                           (v.is_number() ? ReadableNumber(x) : ReadableText(v.dump())));
    return x;
  };
  const double depth = number("/well/measured_depth_m", io::Range{0, 20000, true, false});
  const double wob_kN = number("/wob_target_kN", io::Range{0, 5000, true, false});
  const double duration = number("/duration_s", io::Range{0, 86400, true, false});
  doc["model"]["string"]["length_m"] = depth;
  doc["model"]["hoist"]["weight_on_bit_N"] = 1000 * wob_kN;
  if (sidecar.at("well").contains("mud_density_kg_m3"))
    doc["model"]["string"]["mud_density_kg_m3"] = number("/well/mud_density_kg_m3", io::Range::Between(500, 3000));

  const auto schedule_it = sidecar.find("rpm_setpoint_schedule");
  if (schedule_it == sidecar.end() || !schedule_it->is_array() || schedule_it->empty())
    throw InputError(where("/rpm_setpoint_schedule"),
                     "expected a non-empty list of [time_s, rpm] pairs, got " +
                         (schedule_it == sidecar.end() ? std::string("nothing") : ReadableText(schedule_it->dump())));
  nlohmann::json knots = nlohmann::json::array();
  double previous = 0;
  for (std::size_t i = 0; i < schedule_it->size(); ++i) {
    const std::string knot = "/rpm_setpoint_schedule/" + std::to_string(i);
    if (!(*schedule_it)[i].is_array() || (*schedule_it)[i].size() != 2)
      throw InputError(where(knot), "expected a [time_s, rpm] pair, got " + ReadableText((*schedule_it)[i].dump()));
    const double t = number(knot + "/0", io::Range::Between(0, duration));
    const double rpm = number(knot + "/1", io::Range::Between(0, 1000));
    if (t < previous)
      throw InputError(where(knot + "/0"), "times must not decrease: " + ReadableNumber(t) + " s after " +
                                               ReadableNumber(previous) + " s");
    previous = t;
    if (i == 0) {  // a 5 % bump in the warm-up's first seconds, to leave the unstable equilibrium
      const double w0 = rpm * M_PI / 30;
      knots = nlohmann::json::array({{0.0, w0}, {1.0, 1.05 * w0}, {2.0, w0}});
    }
    knots.push_back({t + warmup_s, rpm * M_PI / 30});
  }
  doc["model"]["top_drive"]["speed_rad_s"] = {{"knots", knots}};
  doc["simulation"]["duration_s"] = duration + warmup_s;
  doc["statistics"]["window_s"] = {warmup_s, duration + warmup_s};
  const auto name = sidecar.find("recording");
  doc["name"] = (name != sidecar.end() && name->is_string() ? name->get<std::string>() : std::string("recording")) +
                "-baseline";
  return doc;
}

}  // namespace drillwave::diagnosis
