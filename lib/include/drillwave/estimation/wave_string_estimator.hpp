#pragma once
// The bit of a wave string seen from the top: downward continuation of the measured top speed and torque through the
// string's sections (torsion) and of the hook load (axial), then the bit's own inertia for the torque and weight on
// bit. Exact for lossless uniform sections up to the sensors' noise; the estimate for time t is ready one travel time
// (plus the smoothing's half window) later.
#include "drillwave/estimation/estimate.hpp"
#include "drillwave/estimation/wave_continuation.hpp"

namespace drillwave::estimation {

// The pieces of the string's torsional (axial) channel, each section cut into its sub-sections.
std::vector<WavePiece> TorsionalPieces(const WaveStringModel& model);
std::vector<WavePiece> AxialPieces(const WaveStringModel& model);

// Needs top speed and top torque (InputError naming "top torque" otherwise); the hook load is optional (without it
// the weight on bit is the case's steady W0 with no band, and a note says so).
BitEstimate EstimateWaveString(const WaveStringModel& model, const SurfaceSignals& signals, double stuck_threshold_rad_s);

}  // namespace drillwave::estimation
