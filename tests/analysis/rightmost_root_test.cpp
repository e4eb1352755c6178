// The fast path of stability maps against the dense characteristic matrix and the full spectrum: the banded
// determinant equals the dense LU's, the argument principle counts the roots ComputeSpectrum finds in a box (and a
// delay-free system's eigenvalues), and roots continued from nearby seeds are certified only when nothing lies right
// of them.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/analysis/axial_torsional_linearization.hpp"
#include "drillwave/analysis/rightmost_root.hpp"
#include "drillwave/core/constants.hpp"

namespace drillwave::analysis {
namespace {

using Complex = std::complex<double>;

// The coupled string of the baseline (2000 m of 5" pipe) in four pieces per channel, built by hand: ground damping
// lumped at the nodes (half a piece's at the ends), the RGD bit-rock law's cutting gains, steady drilling at 60 rpm
// and 90 kN on the bit.
LinearDelaySystem CoupledString(double speed_rad_s, double weight_on_bit_N) {
  const int pieces = 4;
  const double piece = 2000.0 / pieces;
  auto channel = [&](double impedance, double wave_speed, double damping_per_m, double top, double bit) {
    WaveChannel ch{std::vector<double>(pieces, impedance), std::vector<double>(pieces, piece / wave_speed),
                   std::vector<double>(pieces + 1, damping_per_m * piece), top, bit, {}};
    ch.node_damping.front() *= 0.5, ch.node_damping.back() *= 0.5;
    return ch;
  };
  const double radius = 0.10795, energy = 5e7, zeta = 0.6, contact = radius * 4.5e5;
  AxialTorsionalString string{channel(300.0, 3207.0, 0.06, 2500, 90), channel(1.4e5, 5172.0, 50.0, 30000, 20000),
                              1e5,
                              2e5,
                              radius * zeta * energy,
                              0.5 * radius * radius * energy,
                              5,
                              true};
  const double depth_per_revolution = (weight_on_bit_N - contact) / string.cut_weight_per_depth;
  const double rop = depth_per_revolution * speed_rad_s / (2 * kPi);
  return LinearizeAxialTorsional(string, {speed_rad_s, rop, 0.0}).system;
}

int RootsRightOf(const Spectrum& sp, double re_left) {
  int count = 0;
  for (const CharacteristicRoot& r : sp.roots)
    if (r.s.real() > re_left) count += r.s.imag() == 0 ? 1 : 2;
  return count;
}

TEST(CharacteristicDeterminant, EqualsTheDenseLuOfTheCharacteristicMatrix) {
  const LinearDelaySystem sys = CoupledString(6.283, 90e3);
  const CharacteristicDeterminant det(sys);
  // The chain of waves, top drive to hoist through the bit, fits a narrow band.
  EXPECT_LE(det.lower_bandwidth() + det.upper_bandwidth(), sys.dimension() / 2);
  for (const Complex s : {Complex(0.3, 0.0), Complex(-0.7, 25.6), Complex(2.0, 150.0), Complex(-20.0, 3.0),
                          Complex(1e-5, 1e-4), Complex(400.0, 190.0)}) {
    const Complex dense = Eigen::PartialPivLU<Eigen::MatrixXcd>(sys.Characteristic(s)).determinant();
    const CharacteristicDeterminant::Value banded = det(s);
    EXPECT_NEAR(banded.log_modulus, std::log(std::abs(dense)), 1e-9 * (1 + std::abs(banded.log_modulus))) << s;
    EXPECT_NEAR(std::arg(banded.phase * std::conj(dense)), 0.0, 1e-9) << s;
  }
}

TEST(CountRootsInBox, CountsTheEigenvaluesOfADelayFreeSystem) {
  LinearDelaySystem sys;  // eigenvalues 0.5 +- 3i and -2
  sys.a0 = Eigen::MatrixXd::Zero(3, 3);
  sys.a0 << 0.5, -3, 0, 3, 0.5, 0, 0, 1, -2;
  const CharacteristicDeterminant det(sys);
  EXPECT_EQ(CountRootsInBox(det, 0.0, 10.0, 5.0), 2);
  EXPECT_EQ(CountRootsInBox(det, -3.0, 10.0, 5.0), 3);
  EXPECT_EQ(CountRootsInBox(det, -3.0, 10.0, 2.0), 1);  // the pair lies above the box
  EXPECT_EQ(CountRootsInBox(det, 1.0, 10.0, 5.0), 0);
  EXPECT_EQ(CountRootsInBox(det, 0.5, 10.0, 5.0), -1);  // the pair on the left edge
  EXPECT_GT(RootRealPartBound(sys), 0.5);
}

TEST(CountRootsInBox, CountsTheRootsTheFullSpectrumFindsInTheBox) {
  for (const auto& [speed, weight] : {std::pair{6.283, 90e3}, std::pair{12.0, 60e3}, std::pair{4.5, 150e3}}) {
    const LinearDelaySystem sys = CoupledString(speed, weight);
    const SpectrumOptions options;
    const Spectrum sp = ComputeSpectrum(sys, options);
    ASSERT_GE(sp.roots.size(), 8u);
    const double bound = RootRealPartBound(sys);
    EXPECT_GT(bound, sp.spectral_abscissa);
    const CharacteristicDeterminant det(sys);
    // Left edges midway between the real parts of consecutive roots (none on the edge).
    for (std::size_t k : {0u, 2u, 5u}) {
      const double re_left = 0.5 * (sp.roots[k].s.real() + sp.roots[k + 1].s.real());
      if (sp.roots[k].s.real() - sp.roots[k + 1].s.real() < 1e-6) continue;
      EXPECT_EQ(CountRootsInBox(det, re_left, bound, options.im_max), RootsRightOf(sp, re_left))
          << "speed " << speed << ", weight " << weight << ", left edge " << re_left;
    }
  }
}

// The count of roots right of the axis says "unstable" exactly where the full spectrum's verdict does: the coupled
// string's regenerative modes, and the scalar neutral x' - c x'(t - 1) = a x + b x(t - 1) on both sides of its
// boundary, with its essential spectrum left of the axis (c = 0.5) or on it (c = 1: marginal where no root is right).
TEST(UnstableByArgumentPrinciple, AgreesWithTheFullSpectrumsVerdict) {
  int unstable = 0, not_unstable = 0;
  auto check = [&](const LinearDelaySystem& sys, const std::string& what) {
    const Spectrum sp = ComputeSpectrum(sys);
    const std::optional<bool> counted = UnstableByArgumentPrinciple(sys, {});
    ASSERT_TRUE(counted.has_value()) << what;
    EXPECT_EQ(*counted, sp.verdict == Spectrum::Verdict::kUnstable)
        << what << ": verdict " << VerdictName(sp.verdict) << ", rightmost root " << sp.spectral_abscissa;
    (*counted ? unstable : not_unstable) += 1;
  };
  for (double speed : {4.5, 12.0}) check(CoupledString(speed, 90e3), "coupled string at " + std::to_string(speed));
  for (double c : {0.5, 1.0})
    for (double a : {-2.0, -0.7, 0.3})
      for (double b : {-0.5, 0.4, 1.5}) {
        LinearDelaySystem sys;
        sys.a0 = Eigen::MatrixXd::Constant(1, 1, a);
        sys.delays.push_back({1.0, Eigen::MatrixXd::Constant(1, 1, b), Eigen::MatrixXd::Constant(1, 1, c)});
        check(sys, "a " + std::to_string(a) + ", b " + std::to_string(b) + ", c " + std::to_string(c));
      }
  EXPECT_GT(unstable, 0);  // both verdicts occur
  EXPECT_GT(not_unstable, 0);
  LinearDelaySystem shifted;  // delay-free: eigenvalues a +- 3i and -2
  for (double a : {0.5, -0.5}) {
    shifted.a0 = Eigen::MatrixXd::Zero(3, 3);
    shifted.a0 << a, -3, 0, 3, a, 0, 0, 1, -2;
    EXPECT_EQ(UnstableByArgumentPrinciple(shifted, {}), std::optional<bool>(a > 0));
  }
}

// The abscissa bisected on the same count is the full spectrum's to within its precision, with the same verdict: the
// coupled string at two speeds, the scalar neutral equation on both sides of its boundary with its essential spectrum
// left of the axis or on it, and a delay-free system.
TEST(AbscissaByArgumentPrinciple, IsTheFullSpectrumsAbscissaAndVerdict) {
  constexpr double kPrecision = 1e-6;
  double worst = 0;
  auto check = [&](const LinearDelaySystem& sys, const std::string& what) {
    const Spectrum sp = ComputeSpectrum(sys);
    const std::optional<Spectrum> bisected = AbscissaByArgumentPrinciple(sys, {}, kPrecision);
    ASSERT_TRUE(bisected.has_value()) << what;
    EXPECT_EQ(bisected->verdict, sp.verdict) << what;
    EXPECT_NEAR(bisected->spectral_abscissa, sp.spectral_abscissa, kPrecision) << what;
    EXPECT_EQ(bisected->essential_abscissa, sp.essential_abscissa) << what;
    EXPECT_TRUE(bisected->roots.empty());
    worst = std::max(worst, std::abs(bisected->spectral_abscissa - sp.spectral_abscissa));
  };
  for (double speed : {4.5, 12.0}) check(CoupledString(speed, 90e3), "coupled string at " + std::to_string(speed));
  for (double c : {0.5, 1.0})
    for (double a : {-2.0, 0.3})
      for (double b : {-0.5, 1.5}) {
        LinearDelaySystem sys;
        sys.a0 = Eigen::MatrixXd::Constant(1, 1, a);
        sys.delays.push_back({1.0, Eigen::MatrixXd::Constant(1, 1, b), Eigen::MatrixXd::Constant(1, 1, c)});
        check(sys, "a " + std::to_string(a) + ", b " + std::to_string(b) + ", c " + std::to_string(c));
      }
  LinearDelaySystem shifted;  // delay-free: eigenvalues a +- 3i and -2
  for (double a : {0.5, -0.5}) {
    shifted.a0 = Eigen::MatrixXd::Zero(3, 3);
    shifted.a0 << a, -3, 0, 3, a, 0, 0, 1, -2;
    check(shifted, "delay-free, a " + std::to_string(a));
  }
  std::printf("[ measured ] bisected abscissa against the full spectrum's: largest difference %.1e\n", worst);
}

TEST(SpectrumFromSeeds, FindsTheFullSpectrumsRightmostRootFromNearbySeeds) {
  const LinearDelaySystem sys = CoupledString(6.283, 90e3);
  const Spectrum full = ComputeSpectrum(sys);
  std::vector<Complex> seeds;
  for (std::size_t k = 0; k < 6; ++k) seeds.push_back(full.roots[k].s * Complex(1.01, 0.005));
  const SeededSpectrum seeded = SpectrumFromSeeds(sys, seeds);
  ASSERT_TRUE(seeded.certified);
  EXPECT_EQ(seeded.spectrum.verdict, full.verdict);
  EXPECT_NEAR(seeded.spectrum.spectral_abscissa, full.spectral_abscissa, 1e-9 * std::abs(full.spectral_abscissa));
  EXPECT_NEAR(seeded.spectrum.roots.front().s.imag(), full.roots.front().s.imag(),
              1e-9 * std::abs(full.roots.front().s));
  EXPECT_EQ(seeded.spectrum.essential_abscissa, full.essential_abscissa);
}

TEST(SpectrumFromSeeds, IsNotCertifiedWhenARootRightOfTheSeedsIsMissed) {
  const LinearDelaySystem sys = CoupledString(6.283, 90e3);
  const Spectrum full = ComputeSpectrum(sys);
  // Seeds at the third root only: the two rightmost (or the rightmost pair) lie right of what Newton finds.
  std::size_t k = 1;
  while (k < full.roots.size() && full.roots[k].s.real() > full.roots[0].s.real() - 1e-6) ++k;
  ASSERT_LT(k, full.roots.size());
  const SeededSpectrum seeded = SpectrumFromSeeds(sys, {full.roots[k].s});
  EXPECT_FALSE(seeded.certified);
  EXPECT_FALSE(SpectrumFromSeeds(sys, {}).certified);
}

}  // namespace
}  // namespace drillwave::analysis
