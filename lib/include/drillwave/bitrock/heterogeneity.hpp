#pragma once
// The rock's strength varying with drilled depth. BASELINE.md's independent simulator multiplies the intrinsic
// specific energy eps and the contact strength sigma l by 1 + g(z), g a small random heterogeneity of the drilled depth
// z (std 0.5-1.5 %, correlation length 2 mm). Here z is the bit's axial position U (0 at t = 0, down positive): the
// blades cut the rock at the bottom of the hole, where the bit stands.
#include <cstdint>
#include <vector>

namespace drillwave::bitrock {

// g(z) = sum_{k=1..K} c cos(kappa_k z + phi_k), c = std sqrt(2 / K): a random-phase sum of K cosines whose
// wavenumbers kappa_k are drawn from the Gaussian spectrum N(0, 1 / correlation^2) and phases phi_k uniformly from
// [0, 2 pi), by a 64-bit Mersenne Twister seeded with `seed` and this file's own uniform and Box-Muller mappings
// (portable: the same field on every platform with the same libm). Over seeds g is stationary with mean 0, variance
// std^2 and correlation E[g(z) g(z + dz)] / std^2 = exp(-(dz / correlation)^2 / 2) (0.61 at one correlation length);
// smooth (every derivative continuous), so the integrator meets no jumps. Default (or std 0): homogeneous rock,
// Multiplier exactly 1.
// Deviation evaluates g through its quintic Hermite interpolant on cells of width 0.5 / max |kappa_k| (g, g' and g''
// exact at the cells' ends): within std sqrt(2 K) 0.5^6 / 46080 of the sum (4e-6 std for K = 64, a strength off by
// 4e-8), at the cost of a polynomial where the bit stays in a cell (the sum of cosines was a third of a diagnosis's
// time). A pure function of the field and z: the same value whatever was asked before.
class StrengthHeterogeneity {
 public:
  StrengthHeterogeneity() = default;
  // std >= 0 (relative), correlation > 0 [m], modes >= 1; throws std::invalid_argument otherwise.
  StrengthHeterogeneity(double std, double correlation, std::uint64_t seed, int modes);

  bool on() const { return amplitude_ > 0; }
  double std() const { return std_; }  // the relative standard deviation asked for
  double Deviation(double z) const;    // g(z), relative, through the interpolant
  double ExactDeviation(double z) const;  // the sum of cosines itself
  // 1 + g(z), exactly 1 when off.
  double Multiplier(double z) const { return on() ? 1.0 + Deviation(z) : 1.0; }

 private:
  std::uint64_t id_ = 0;  // this field's own number (its copies share it): the key of Deviation's last answer
  double std_ = 0;
  double amplitude_ = 0;                    // c
  double cell_ = 1;                         // the interpolant's cell width [m]
  std::vector<double> wavenumbers_, phases_;  // kappa_k [1/m], phi_k
  void Jet(double z, double out[3]) const;    // g, g', g'' at z, exactly
};

}  // namespace drillwave::bitrock
