// The rock's strength heterogeneity (bitrock::StrengthHeterogeneity): over seeds its mean, standard deviation and
// correlation at one correlation length are what its parameters say, a seed reproduces it, std 0 is homogeneous rock
// to the byte, and the RGD law multiplies eps and sigma l by it at the bit's depth.
#include "drillwave/bitrock/heterogeneity.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>

#include "drillwave/bitrock/rgd.hpp"

namespace {

using drillwave::bitrock::Axial;
using drillwave::bitrock::RgdForces;
using drillwave::bitrock::RgdLaw;
using drillwave::bitrock::StrengthHeterogeneity;
using drillwave::bitrock::Turn;

constexpr double kStd = 0.01;
constexpr double kCorrelation = 2e-3;  // m, BASELINE.md's

// Over N seeds at two depths one correlation length apart: E[g] = 0, E[g^2] = std^2, E[g(z) g(z + L)] = std^2
// exp(-1/2). Tolerances: about four standard errors of N = 4000 draws (mean: 1 / sqrt(N) = 0.016 std; mean square:
// sqrt(2 / N) = 0.022 std^2; lagged product: sqrt((1 + rho^2) / N) = 0.019 std^2, for a Gaussian field).
TEST(StrengthHeterogeneity, OverSeedsHasMeanZeroTheGivenStdAndGaussianCorrelation) {
  constexpr int kSeeds = 4000;
  const double z = 0.3712;  // any depth: the field is stationary
  double mean = 0, mean_square = 0, lagged = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    const StrengthHeterogeneity g(kStd, kCorrelation, static_cast<std::uint64_t>(seed), 64);
    const double a = g.Deviation(z) / kStd, b = g.Deviation(z + kCorrelation) / kStd;
    mean += a / kSeeds, mean_square += a * a / kSeeds, lagged += a * b / kSeeds;
  }
  std::printf("[ measured ] over %d seeds: mean %.4f std, rms %.4f std, correlation at L %.4f (model %.4f)\n", kSeeds,
              mean, std::sqrt(mean_square), lagged, std::exp(-0.5));
  EXPECT_NEAR(mean, 0, 0.065);
  EXPECT_NEAR(mean_square, 1, 0.09);
  EXPECT_NEAR(lagged, std::exp(-0.5), 0.08);
}

// Along a long drilled depth of one seed with many modes: the same three numbers (each mode averages to its own share
// over many periods; the finite set of wavenumbers leaves a sampling error of about 1 / sqrt(modes)).
TEST(StrengthHeterogeneity, AlongALongDepthOfOneSeedHasTheSameStatistics) {
  const StrengthHeterogeneity g(kStd, kCorrelation, 11, 400);
  constexpr int kPoints = 40000;
  const double dz = kCorrelation / 5;
  double mean = 0, mean_square = 0, lagged = 0;
  for (int i = 0; i < kPoints; ++i) {
    const double a = g.Deviation(i * dz) / kStd, b = g.Deviation(i * dz + kCorrelation) / kStd;
    mean += a / kPoints, mean_square += a * a / kPoints, lagged += a * b / kPoints;
  }
  std::printf("[ measured ] along %.0f m of seed 11: mean %.4f std, rms %.4f std, correlation at L %.4f\n",
              kPoints * dz, mean, std::sqrt(mean_square), lagged);
  EXPECT_NEAR(mean, 0, 0.05);
  EXPECT_NEAR(mean_square, 1, 0.1);
  EXPECT_NEAR(lagged, std::exp(-0.5), 0.1);
}

// Deviation is the sum's quintic Hermite interpolant on cells where the fastest mode turns by half a radian: within
// std sqrt(2 K) 0.5^6 / 46080 (4e-6 std for K = 64) of the sum everywhere, above and below the start, and continuous
// across the cells' ends; asked in any order, it gives the same value (a pure function of z).
TEST(StrengthHeterogeneity, ItsInterpolantIsTheSumToFarBelowAnyTolerance) {
  const StrengthHeterogeneity g(kStd, kCorrelation, 5, 64);
  double worst = 0;
  for (int i = -20000; i <= 20000; ++i) {
    const double z = i * 1.37e-5 + 3e-7;
    worst = std::max(worst, std::abs(g.Deviation(z) - g.ExactDeviation(z)));
  }
  std::printf("[ measured ] interpolant against the sum over [-0.27, 0.27] m: %.3g std at most\n", worst / kStd);
  EXPECT_LT(worst, 4e-6 * kStd);
  EXPECT_GT(worst, 0);  // it is an interpolant, not the sum
  const double z = 0.0421, first = g.Deviation(z);
  for (double other : {-1.0, 5.0, z + 1e-4}) g.Deviation(other);
  EXPECT_EQ(g.Deviation(z), first);
}

TEST(StrengthHeterogeneity, ASeedReproducesTheFieldAndAnotherDoesNot) {
  const StrengthHeterogeneity a(kStd, kCorrelation, 3, 64), again(kStd, kCorrelation, 3, 64),
      other(kStd, kCorrelation, 4, 64);
  for (double z : {0.0, 1e-3, 0.05, 2.0}) {
    EXPECT_EQ(a.Deviation(z), again.Deviation(z));
    EXPECT_NE(a.Deviation(z), other.Deviation(z));
  }
}

// Deviation keeps each thread's last answer (a state asks for one depth several times): asked at one depth in turn,
// fields answer for themselves, a copy as its original, and a field built where a destroyed one stood (the same
// address, likely) with another seed does not answer with the old field's value.
TEST(StrengthHeterogeneity, ItsLastAnswerIsOnlyEverItsOwn) {
  const double z = 0.0123;
  const StrengthHeterogeneity a(kStd, kCorrelation, 3, 64), b(kStd, kCorrelation, 4, 64);
  const double a_z = a.Deviation(z), b_z = b.Deviation(z);
  EXPECT_NE(a_z, b_z);
  EXPECT_EQ(a.Deviation(z), a_z);
  EXPECT_EQ(b.Deviation(z), b_z);
  const StrengthHeterogeneity copy = a;
  EXPECT_EQ(copy.Deviation(z), a_z);
  double first = 0, second = 0;
  {
    const StrengthHeterogeneity gone(kStd, kCorrelation, 5, 64);
    first = gone.Deviation(z);
  }
  {
    const StrengthHeterogeneity next(kStd, kCorrelation, 6, 64);
    second = next.Deviation(z);
  }
  EXPECT_EQ(first, StrengthHeterogeneity(kStd, kCorrelation, 5, 64).Deviation(z));
  EXPECT_EQ(second, StrengthHeterogeneity(kStd, kCorrelation, 6, 64).Deviation(z));
  EXPECT_NE(first, second);
}

TEST(StrengthHeterogeneity, ZeroStdIsHomogeneousRockAndBadParametersAreRefused) {
  const StrengthHeterogeneity zero(0, kCorrelation, 5, 64);
  EXPECT_FALSE(zero.on());
  EXPECT_FALSE(StrengthHeterogeneity().on());
  for (double z : {0.0, 0.1, -0.2}) EXPECT_EQ(zero.Multiplier(z), 1.0);
  EXPECT_THROW(StrengthHeterogeneity(-0.01, kCorrelation, 1, 64), std::invalid_argument);
  EXPECT_THROW(StrengthHeterogeneity(kStd, 0, 1, 64), std::invalid_argument);
  EXPECT_THROW(StrengthHeterogeneity(kStd, kCorrelation, 1, 0), std::invalid_argument);
}

// BASELINE.md's nominal law.
RgdLaw Nominal() {
  RgdLaw law;
  law.a = 0.108, law.zeta = 0.6, law.eps = 60e6, law.sigma_l = 60e6 * 0.0012, law.mu = 0.6, law.gamma = 1;
  law.static_mu = law.mu;
  return law;
}

RgdForces OnBottom(const RgdLaw& law, Axial axial, double z) {
  RgdForces f;
  f.depth = 2.6e-3, f.drive_force = 90e3;
  law.OnBottom(Turn::kForward, axial, 6.0, true, z, f);
  return f;
}

TEST(StrengthHeterogeneity, ScalesTheCuttingAndContactForcesAtTheBitsDepthAndZeroStdGivesTheOldForces) {
  const RgdLaw homogeneous = Nominal();
  RgdLaw zero = Nominal(), rough = Nominal();
  zero.strength_heterogeneity = StrengthHeterogeneity(0, kCorrelation, 1, 64);
  rough.strength_heterogeneity = StrengthHeterogeneity(kStd, kCorrelation, 1, 64);
  for (Axial axial : {Axial::kAdvancing, Axial::kHeld, Axial::kLifting}) {
    for (double z : {0.0, 0.0013, 0.4}) {
      const RgdForces h = OnBottom(homogeneous, axial, z), o = OnBottom(zero, axial, z), r = OnBottom(rough, axial, z);
      // The old law, written out: the same to the bit.
      const double d = 2.6e-3, cut_weight = homogeneous.CutWeightPerDepth() * d;
      EXPECT_EQ(h.cut_weight, cut_weight);
      EXPECT_EQ(o.cut_weight, h.cut_weight);
      EXPECT_EQ(o.weight, h.weight);
      EXPECT_EQ(o.torque, h.torque);
      EXPECT_EQ(o.static_forward, h.static_forward);
      EXPECT_EQ(homogeneous.ContactForceAt(z), homogeneous.ContactForce());
      const double m = 1 + rough.strength_heterogeneity.Deviation(z);
      EXPECT_NE(m, 1.0);
      EXPECT_NEAR(r.cut_weight, m * h.cut_weight, 1e-9 * h.cut_weight);
      EXPECT_NEAR(rough.ContactForceAt(z), m * homogeneous.ContactForce(), 1e-9 * homogeneous.ContactForce());
      if (axial == Axial::kAdvancing) {
        EXPECT_NEAR(r.weight, m * h.weight, 1e-9 * h.weight);
        EXPECT_NEAR(r.torque, m * h.torque, 1e-9 * h.torque);
      }
    }
  }
}

}  // namespace
