#pragma once
// Delayed downhole telemetry fused into the estimate from the surface (issue 34 item 2; chapter sect. 2.7: mud-pulse
// telemetry reports the bit seconds late). At time t the newest telemetry sample reports the bit at t - d: set against
// the estimate for t - d, it is the estimate's error there (the innovation). Low-passed over a time much longer than a
// stick-slip period, that error is the model's slow one (a mean bit speed off by a damping, a weight on bit off by a
// buoyancy or a hook set-point), which persists to t and is added there; the fast motion the telemetry shows late is
// not copied. The fused estimate at t reads telemetry up to t only: it runs live, at the surface estimate's latency.
#include <string>
#include <vector>

namespace drillwave::estimation {

struct TelemetryFusion {
  double telemetry_delay_s = 0;            // the telemetry's lag behind the bit
  double innovation_time_constant_s = 20;  // of the innovation's first-order low-pass

  // telemetry_delay_s finite and >= 0, innovation_time_constant_s finite and > 0 (core/validity.hpp).
  bool IsValid(std::string* error) const;
};

// estimate[i] plus the low-passed innovation telemetry[j] - estimate[j - k] over j <= i, k = delay / dt rounded, on
// the estimate's uniform grid of step dt (telemetry on the same grid). Where either side of an innovation is NaN the
// correction holds; before the first innovation it is 0. Throws ParameterError for options that are not valid.
std::vector<double> FuseDelayedTelemetry(const std::vector<double>& estimate, const std::vector<double>& telemetry,
                                         double dt, const TelemetryFusion& fusion);

}  // namespace drillwave::estimation
