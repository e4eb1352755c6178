#pragma once
// The bit of a two-mass pendulum seen from the top speed alone: an extended Kalman filter on the pendulum (twist,
// top speed, bit speed, the PI drive's integral) with its set-valued bit friction, followed by a fixed-lag
// Rauch-Tung-Striebel smoother.
//
// What makes the bit observable from the top: the drive law. The top's equation J_t w_t' = T_drive(w_t) - T_shaft
// turns the measured top speed into the shaft torque, and its changes into the twist rate w_t - w_b; the bit's own
// equation (shaft torque against the friction law) carries the estimate between measurements. The filter weighs the
// two by their uncertainties: the drive's and the friction's torques are each taken as uncertain by a fifth of the
// friction's static level (the friction law fitted on another stretch, the weight on bit varying), with the
// correlation time of the shaft-and-bit oscillation. A wrong initial state decays at the rate of the filter's
// closed loop; the information about the bit at t reaches the top over about one shaft-and-bit period, so the
// estimate is smoothed over that lag (its latency).
#include <string>
#include <vector>

#include "drillwave/estimation/estimate.hpp"

namespace drillwave::estimation {

struct LumpedObserverOptions {
  double smoothing_lag_s = -1;  // < 0: one period of the bit on the shaft, 2 pi sqrt(J_b / k)
  double model_time_offset_s = 0;  // recording time of the model's time 0
  // Initial state (left at -1e300: the first measured speed for both discs, no twist): tests start the filter wrong.
  double initial_bit_speed_rad_s = -1e300;
  double initial_twist_rad = -1e300;
  bool despike = true;  // Hampel-filter the top speed first (encoder glitches)

  // The lag, offset and initial state finite (core/validity.hpp).
  bool IsValid(std::string* error) const;
};

// Throws ParameterError("from", ...) if the top speed is missing, ParameterError for options that are not valid.
BitEstimate EstimateLumped(const LumpedModel& model, const SurfaceSignals& signals, double stuck_threshold_rad_s,
                           const LumpedObserverOptions& options);

}  // namespace drillwave::estimation
