// The start's bottom-hole roughness (bitrock::BottomRoughness): its statistics are what its parameters say, over a
// revolution and over seeds, a seed reproduces it, and the cut profile's prehistory carries it into the depth of cut.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>

#include <gtest/gtest.h>

#include "drillwave/bitrock/rgd.hpp"
#include "drillwave/bitrock/roughness.hpp"
#include "drillwave/core/constants.hpp"

namespace {

using drillwave::kPi;
using drillwave::bitrock::BottomRoughness;
using drillwave::bitrock::CutProfile;
using drillwave::integration::Side;

constexpr double kRms = 1e-5;  // m
constexpr int kModes = 20;

// Mean and mean square over a revolution by the rectangle rule on N points, exact for a trigonometric polynomial of
// degree below N / 2.
struct RevolutionMoments {
  double mean = 0, mean_square = 0;
};
RevolutionMoments OverARevolution(const BottomRoughness& h, int points = 256) {
  RevolutionMoments m;
  for (int i = 0; i < points; ++i) {
    const double v = h.Depth(2 * kPi * i / points);
    m.mean += v / points, m.mean_square += v * v / points;
  }
  return m;
}

TEST(BottomRoughness, HasMeanZeroAndTheGivenRmsOverEveryRevolution) {
  for (std::uint64_t seed : {0u, 1u, 7u, 123456u}) {
    for (int modes : {1, 3, kModes, 100}) {
      const BottomRoughness h(kRms, seed, modes);
      const RevolutionMoments m = OverARevolution(h, 1024);
      EXPECT_NEAR(m.mean, 0.0, 1e-13 * kRms) << "seed " << seed << ", " << modes << " modes";
      EXPECT_NEAR(std::sqrt(m.mean_square), kRms, 1e-12 * kRms) << "seed " << seed << ", " << modes << " modes";
      EXPECT_NEAR(h.Depth(0.3), h.Depth(0.3 + 2 * kPi), 1e-12 * kRms);  // periodic around the hole
    }
  }
}

// Over seeds, the depth at one angle is a random variable of mean 0 and variance rms^2 (2000 draws: the sample
// variance's standard error is about sqrt(2 / 2000) = 3 % of rms^2 for a nearly Gaussian sum of 20 cosines).
TEST(BottomRoughness, OverSeedsTheDepthAtAnAngleHasMeanZeroAndVarianceRmsSquared) {
  constexpr int kDraws = 2000;
  double sum = 0, sum_squares = 0;
  for (int seed = 0; seed < kDraws; ++seed) {
    const double v = BottomRoughness(kRms, seed, kModes).Depth(1.0);
    sum += v, sum_squares += v * v;
  }
  const double mean = sum / kDraws, variance = sum_squares / kDraws - mean * mean;
  std::printf("[ measured ] over %d seeds at 1 rad: mean %.3g rms, variance %.4f rms^2\n", kDraws, mean / kRms,
              variance / (kRms * kRms));
  EXPECT_LT(std::abs(mean), 4 * kRms / std::sqrt(kDraws));
  EXPECT_NEAR(variance, kRms * kRms, 0.12 * kRms * kRms);
}

TEST(BottomRoughness, TheSlopeIsTheDerivativeOfTheDepth) {
  const BottomRoughness h(kRms, 42, kModes);
  for (double theta : {-3.0, -0.5, 0.0, 1.25, 4.0}) {
    const double step = 1e-5;
    const double difference = (h.Depth(theta + step) - h.Depth(theta - step)) / (2 * step);
    EXPECT_NEAR(h.Slope(theta), difference, 1e-8 * kRms * kModes) << theta;  // |h'| reaches about rms K
  }
}

TEST(BottomRoughness, ASeedReproducesTheSurfaceAndAnotherDoesNot) {
  const BottomRoughness a(kRms, 5, kModes), b(kRms, 5, kModes), c(kRms, 6, kModes);
  double largest_difference = 0;
  for (int i = 0; i < 64; ++i) {
    const double theta = 2 * kPi * i / 64;
    EXPECT_EQ(a.Depth(theta), b.Depth(theta));
    largest_difference = std::max(largest_difference, std::abs(a.Depth(theta) - c.Depth(theta)));
  }
  EXPECT_GT(largest_difference, 0.1 * kRms);
}

TEST(BottomRoughness, ZeroRmsIsASmoothBottomAndBadParametersAreRefused) {
  const BottomRoughness flat(0.0, 3, kModes);
  EXPECT_FALSE(flat.on());
  EXPECT_EQ(flat.Depth(1.0), 0.0);
  EXPECT_FALSE(BottomRoughness().on());
  EXPECT_THROW(BottomRoughness(-1e-6, 1, kModes), std::invalid_argument);
  EXPECT_THROW(BottomRoughness(std::nan(""), 1, kModes), std::invalid_argument);
  EXPECT_THROW(BottomRoughness(kRms, 1, 0), std::invalid_argument);
}

// Before any step is stored the depth of cut reads the prehistory: steady drilling over the rough bottom,
// d = n (V0 t_n + h(Omega0 t) - h(Omega0 (t - t_n))) with the bit at U = V0 t + h(Omega0 t), t_n = 2 pi / (n Omega0).
TEST(BottomRoughness, TheCutProfilesPrehistoryIsSteadyDrillingOverTheRoughBottom) {
  constexpr int kBlades = 5;
  constexpr double kOmega = 2 * kPi, kRop = 0.01;
  const BottomRoughness h(kRms, 11, kModes);
  const double tn = 2 * kPi / (kBlades * kOmega);
  for (int passes : {1, 4}) {
    const CutProfile profile(kBlades, kOmega, kRop, passes, h);
    for (double t : {-0.05, -0.5, -1.3}) {
      const double u = kRop * t + h.Depth(kOmega * t);
      const double expected = kBlades * (kRop * tn + h.Depth(kOmega * t) - h.Depth(kOmega * (t - tn)));
      EXPECT_NEAR(profile.DepthOfCut(kOmega * t, u, t, Side::kLeft, true, -10.0), expected, 1e-12)
          << passes << " passes at t = " << t;
    }
  }
}

}  // namespace
