#include "drillwave/estimation/telemetry_fusion.hpp"

#include <cmath>
#include <cstddef>

#include "drillwave/core/validity.hpp"

namespace drillwave::estimation {

bool TelemetryFusion::IsValid(std::string* error) const {
  return NonNegativeField(error, "telemetry_delay_s", telemetry_delay_s) &&
         PositiveField(error, "innovation_time_constant_s", innovation_time_constant_s);
}

std::vector<double> FuseDelayedTelemetry(const std::vector<double>& estimate, const std::vector<double>& telemetry,
                                         double dt, const TelemetryFusion& fusion) {
  ThrowIfInvalid(fusion);
  const std::size_t lag = static_cast<std::size_t>(std::lround(fusion.telemetry_delay_s / dt));
  // The exact discretization of d c / dt = (innovation - c) / T over one sample.
  const double weight = 1 - std::exp(-dt / fusion.innovation_time_constant_s);
  std::vector<double> fused(estimate.size());
  double correction = 0;
  bool started = false;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    if (i >= lag && i < telemetry.size()) {
      const double innovation = telemetry[i] - estimate[i - lag];
      if (std::isfinite(innovation)) {
        correction = started ? correction + weight * (innovation - correction) : innovation * weight;
        started = true;
      }
    }
    fused[i] = estimate[i] + correction;
  }
  return fused;
}

}  // namespace drillwave::estimation
