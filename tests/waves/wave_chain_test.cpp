// waves::WaveChain on its own: the steady state it starts from balances its ends, and waves driven in at the top of
// an undamped chain of several pieces come back as the closed-form d'Alembert sum (each round trip reflected at a
// clamped bit and at the driven top), through the node histories, their split parts and the end forces.
#include "drillwave/waves/wave_chain.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace drillwave::waves {
namespace {

using integration::Side;

ChainSpec Uniform(int pieces, double z, double tau) {
  ChainSpec spec;
  spec.z.assign(pieces, z), spec.tau.assign(pieces, tau);
  spec.damping.assign(pieces + 1, 0.0), spec.load.assign(pieces + 1, 0.0), spec.coulomb.assign(pieces + 1, 0.0);
  return spec;
}

// Pipe and BHA pieces with damping, weight and side friction on the nodes: in steady motion the string carries the
// bit's force up, adding each node's damping and friction and taking off its weight.
TEST(WaveChain, SteadyMotionBalancesBothEnds) {
  ChainSpec spec = Uniform(6, 120.0, 0.02);
  spec.z[4] = spec.z[5] = 310.0, spec.tau[4] = spec.tau[5] = 0.013;
  double expected_top = 0;
  const double v = 6.0, bit_force = 5300.0;
  for (int j = 0; j <= 6; ++j) {
    spec.damping[j] = 1.5 + j, spec.load[j] = 40.0 * j;
    if (j > 0 && j < 6) spec.coulomb[j] = 25.0;
    expected_top += spec.damping[j] * v - spec.load[j] + spec.coulomb[j];
  }
  expected_top += bit_force;
  const WaveChain chain(spec, v, bit_force);
  EXPECT_NEAR(chain.steady_top_force(), expected_top, 1e-9 * expected_top);
  const ChainEnds f = chain.EndForces(-1.0, Side::kLeft, {v, v});
  EXPECT_NEAR(f.bit, bit_force, 1e-9 * bit_force);  // the string pushes the bit as the rock holds it
  EXPECT_NEAR(f.top, -expected_top, 1e-9 * expected_top);
}

// Undamped, uniform, at rest; the top driven at v(t) = 1 - cos(w t) from t = 0, the bit clamped. The wave sent down
// from the top is D(t) = sum_k v(t - 2kT) (each echo comes back from the clamped bit inverted and leaves the driven
// top inverted again), and the bit feels 2 Z D(t - T), T the travel time of the whole chain.
TEST(WaveChain, DrivenTopReachesAClampedBitAsTheDAlembertSum) {
  const int pieces = 5;
  const double z = 250.0, tau = 0.04, travel = pieces * tau, w = 9.0;
  WaveChain chain(Uniform(pieces, z, tau), 0.0, 0.0);
  auto v = [w](double t) { return t > 0 ? 1 - std::cos(w * t) : 0.0; };
  auto dv = [w](double t) { return t > 0 ? w * std::sin(w * t) : 0.0; };
  auto bit_force = [&](double t) {
    double down = 0;
    for (double sent = t - travel; sent > 0; sent -= 2 * travel) down += v(sent);
    return 2 * z * down;
  };
  const double h = tau / 8;  // every arrival on a step boundary
  std::vector<double> end_kinks;
  double worst = 0, largest = 0, worst_check = 0;
  for (int k = 0; k < 400; ++k) {  // 10 round trips
    const double t0 = k * h, t1 = t0 + h;
    const WaveChain::StepEnds step{t0, t1, {v(t0), 0}, {dv(t0), 0}, {v(t0 + 0.25 * h), 0}, {v(t0 + 0.5 * h), 0},
                                   {v(t1), 0}, {dv(t1), 0}};
    worst_check = std::max(worst_check, chain.Prepare(step, 1e-9, 1e-9));
    chain.Commit(t0, t1, 2 * tau, end_kinks);
    // Between step ends, as an integrator's stages ask (the bit's arrivals were sent a piece's travel time before).
    const double t = t1 + 0.3 * h;
    worst = std::max(worst, std::abs(chain.EndForces(t, Side::kLeft, {v(t), 0}).bit - bit_force(t)));
    largest = std::max(largest, std::abs(bit_force(t)));
  }
  std::printf("[ measured ] 10 round trips: bit force within %.2e of the d'Alembert sum (largest %.1f), worst quarter-"
              "point check %.2g\n", worst, largest, worst_check);
  EXPECT_GT(largest, 1000.0);
  EXPECT_LT(worst, 1e-7 * largest);
  EXPECT_LT(worst_check, 1.0);  // the stored quartics hold these smooth waves to the tolerance at h = tau / 8
}

}  // namespace
}  // namespace drillwave::waves
