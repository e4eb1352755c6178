#pragma once
// What the fuzz targets do with a case they accepted: run it briefly, so that what the readers let through reaches the
// kinds' setup and first steps (issue 41). The document is cut to its first kShortRunS seconds and parsed again with
// at most kShortRunSamples output samples or integration steps (and ten times as many evaluations), so that one input
// stays within milliseconds of work and CI's time per target buys as many inputs as before. The run may be refused
// (InputError) or fail numerically (NumericalError, exit 3 for a user); anything else — another exception, a crash,
// an allocation beyond libFuzzer's memory limit, a hang — escapes to libFuzzer as a bug.
#include <algorithm>

#include <nlohmann/json.hpp>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"

namespace drillwave::fuzz {

constexpr double kShortRunS = 0.02;
constexpr double kShortRunSamples = 2e4;

inline void RunBriefly(nlohmann::json doc) {
  // A case the readers accepted has its duration or takes the default; either way at most kShortRunS.
  const nlohmann::json* given = doc.contains("simulation") && doc["simulation"].is_object()
                                    ? &doc["simulation"] : nullptr;
  const double duration = given && given->contains("duration_s") && (*given)["duration_s"].is_number()
                              ? std::min((*given)["duration_s"].get<double>(), kShortRunS)
                              : kShortRunS;
  doc["simulation"]["duration_s"] = duration;
  doc["statistics"]["window_s"] = {0.0, duration};
  doc.erase("expect");
  // The sample limit is process-wide: lowered for this parse only, whatever it throws.
  struct LimitFor {
    double before = cases::MaxSamples();
    explicit LimitFor(double limit) { cases::SetMaxSamples(limit); }
    ~LimitFor() { cases::SetMaxSamples(before); }
  } limit(kShortRunSamples);
  try {
    (void)cases::RunCase(cases::ParseCase(doc));
  } catch (const InputError&) {
  } catch (const NumericalError&) {
  }
}

}  // namespace drillwave::fuzz
