#pragma once
// Downward continuation of one wave channel (torsion or axial motion) of a drill string: from velocity and force
// measured at the top over a time span, the velocity and force at the bottom (DESIGN.md §1). A uniform piece of
// impedance Z and travel time tau carries v = D + U and F = Z (D - U) (torque carried downward; for the axial channel
// the compression, i.e. minus the tension): the down-going wave D reaches the lower end tau after it left the upper
// end, and the up-going wave U there is the one that reaches the upper end tau later. So the lower end at time t
// needs the upper end at t - tau and t + tau: the bottom's estimate for t is ready at t + tau (the latency).
// Distributed viscous damping is lumped as shunt dashpots at the pieces' middles, as the simulator lumps it.
#include <vector>

namespace drillwave::estimation {

struct WavePiece {
  double impedance = 0;      // Z = sqrt(K rho X) > 0: N m s/rad (torsion) or N s/m (axial)
  double travel_time_s = 0;  // tau = length / wave speed > 0
  double shunt_damping = 0;  // damping per metre times length, >= 0, lumped at the middle of the piece
};

struct WaveEnd {
  std::vector<double> velocity;  // NaN where the span of the top's signals does not reach (the first and last tau)
  std::vector<double> force;
};

// Velocity and force at the lower end of `pieces` (top to bottom) on the top's time grid. The grid must be uniform
// (spacing within 1e-6 relative); values between samples are interpolated by cubic Catmull-Rom splines. Throws
// std::invalid_argument for series of different lengths, fewer than 4 samples or a non-uniform grid.
WaveEnd ContinueDownward(const std::vector<double>& time_s, const std::vector<double>& top_velocity,
                         const std::vector<double>& top_force, const std::vector<WavePiece>& pieces);

// Total travel time of the pieces.
double TravelTime(const std::vector<WavePiece>& pieces);

// x(t + shift) on the uniform grid of x (spacing dt) by Catmull-Rom interpolation; NaN outside the span.
std::vector<double> Shifted(const std::vector<double>& x, double dt, double shift_s);

}  // namespace drillwave::estimation
