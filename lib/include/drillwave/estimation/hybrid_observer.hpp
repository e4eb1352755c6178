#pragma once
// The bit of a two-mass pendulum seen from the top speed alone through the drive law, with the bit's stick-slip
// regimes (a hybrid observer). For a drive whose torque is a known function of its speed (a droop drive: kp (w0 -
// w_t); a torque-driven top: the set-point), the top's own equation J_t w_t' = T_drive(w_t) - c_t w_t - T_shaft turns
// the measured top speed into the shaft torque, the shaft's T_shaft = k phi + c phi' into the twist phi, and the twist's
// rate into the bit speed w_b = w_t - phi': a drive-law inversion that needs no friction law. What it cannot do is
// reach and hold zero: the top's speed carries the bit's stops only through its low-pass, so the inverted speed rounds
// the stops off. The regime does that: a copy of the bit's equation J_b w_b' = T_shaft - T_friction(w_b), pulled
// towards the inverted speed at three times the bit's natural frequency on the shaft, stops with the set-valued
// friction as the simulation does (bitrock/stick_slip.hpp: stuck while the shaft's torque stays inside the static
// range); it is released when the torque leaves that range and the inverted speed says the bit does move (so that a
// friction law fitted elsewhere cannot release a bit the measurement shows still). The output is the inverted speed
// while slipping and exactly zero while stuck.
//
// The top speed is cleaned first: encoder glitches (lone spikes, each about one encoder step of angle) are masked by
// the inspection's Hampel filter; a burst of them (three or more within 0.2 s: the encoder dithering around a stalled
// drive) is kept, because there the raw mean is the motion; then a low-pass (three boxes of an eighth of the bit's
// period on the shaft, -3 dB near twice its natural frequency: above that the bit barely answers the shaft torque and
// the inversion would only amplify noise).
#include <string>
#include <vector>

#include "drillwave/estimation/estimate.hpp"

namespace drillwave::estimation {

// Whether the drive law makes the top speed a torque meter: a speed drive without integral action, or a torque drive.
bool HasInvertibleDrive(const LumpedModel& model);

struct TopSpeedCleaning {
  std::vector<double> speed, acceleration;  // low-passed; NaN at the edges the filter does not reach
  int glitches_masked = 0, burst_samples_kept = 0;
};

// The top speed as the observer reads it (sampled at dt; window lengths from the model's bit period).
TopSpeedCleaning CleanTopSpeed(const std::vector<double>& raw, double dt, const LumpedModel& model, bool despike);

// How far ahead of time t the cleaning reads (Hampel window, burst rule, low-pass): the observer's latency.
double HybridLatency(const LumpedModel& model, double dt);

struct HybridObserverOptions {
  double model_time_offset_s = 0;  // recording time of the model's time 0
  // Initial state (left at -1e300: the first inverted speed, the twist the first shaft torque gives); tests start it
  // wrong.
  double initial_bit_speed_rad_s = -1e300;
  double initial_twist_rad = -1e300;
  bool despike = true;

  // The offset and initial state finite (core/validity.hpp).
  bool IsValid(std::string* error) const;
};

// Throws ParameterError("from", ...) if the top speed is missing, ParameterError for options that are not valid,
// std::invalid_argument for a drive without HasInvertibleDrive.
BitEstimate EstimateHybrid(const LumpedModel& model, const SurfaceSignals& signals, double stuck_threshold_rad_s,
                           const HybridObserverOptions& options);

}  // namespace drillwave::estimation
