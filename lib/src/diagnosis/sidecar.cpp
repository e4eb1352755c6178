#include "drillwave/diagnosis/sidecar.hpp"

#include <algorithm>
#include <cmath>

#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/io/json_reader.hpp"

namespace drillwave::diagnosis {

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
    if (i == 0) knots.push_back({0.0, rpm * kPi / 30});
    knots.push_back({t + warmup_s, rpm * kPi / 30});
  }
  doc["model"]["top"]["speed_rad_s"] = {{"knots", knots}};
  // BASELINE.md's start: the exact steady state plus a tiny bottom-hole roughness (unless the case brings its own).
  nlohmann::json& rock = doc["model"]["rock"];
  if (!rock.contains("bottom_roughness"))
    rock["bottom_roughness"] = {{"rms_m", kSidecarStartRoughnessM}, {"seed", kSidecarStartSeed}};
  doc["simulation"]["duration_s"] = duration + warmup_s;
  doc["statistics"]["window_s"] = {warmup_s, duration + warmup_s};
  const auto name = sidecar.find("recording");
  doc["name"] = (name != sidecar.end() && name->is_string() ? name->get<std::string>() : std::string("recording")) +
                "-baseline";
  return doc;
}

}  // namespace drillwave::diagnosis
