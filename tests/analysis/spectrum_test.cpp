// Characteristic roots of linear delay systems against closed forms: the scalar retarded DDE (Lambert W), a
// neutral system whose characteristic function factorizes (an exact root chain), incommensurate neutral delays (the
// robust essential abscissa against its closed form and a fine phase grid), and the delay-free lumped limit
// of the two-disc set-up (DESIGN.md §4).
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>

#include <gtest/gtest.h>

#include "drillwave/analysis/spectrum.hpp"
#include "drillwave/core/constants.hpp"

namespace drillwave::analysis {
namespace {

using Complex = std::complex<double>;

Eigen::MatrixXd Scalar(double v) { return Eigen::MatrixXd::Constant(1, 1, v); }

// Branch k of the Lambert W function (w e^w = z) by Halley's iteration from the asymptotic expansion; written here
// independently of the library.
Complex LambertW(Complex z, int k) {
  const Complex two_pi_ik(0.0, 2 * kPi * k);
  Complex l1 = std::log(z) + two_pi_ik;
  Complex w = l1 - std::log(l1);
  if (k == 0 && std::abs(z) < 1) w = z;  // principal branch near 0
  for (int it = 0; it < 100; ++it) {
    const Complex e = std::exp(w), f = w * e - z;
    const Complex step = f / (e * (w + 1.0) - (w + 2.0) * f / (2.0 * w + 2.0));
    w -= step;
    if (std::abs(step) < 1e-15 * (1.0 + std::abs(w))) break;
  }
  return w;
}

// x' = a x + b x(t - tau): s = a + W_k(b tau e^{-a tau}) / tau for every branch k.
TEST(Spectrum, ScalarRetardedDdeMatchesLambertW) {
  const double a = -1.0, b = -2.0, tau = 1.0;
  LinearDelaySystem sys{Scalar(a), {{tau, Scalar(b), {}}}};
  SpectrumOptions o;
  o.re_min = -6;
  o.im_max = 60;
  const Spectrum sp = ComputeSpectrum(sys, o);
  ASSERT_GE(sp.roots.size(), 6u);
  double worst = 0;
  int matched = 0;
  for (int k = -12; k <= 12; ++k) {
    Complex s = a + LambertW(b * tau * std::exp(-a * tau), k) / tau;
    if (s.imag() < 0 || s.real() < o.re_min || s.imag() > o.im_max) continue;
    double best = 1e300;
    for (const auto& r : sp.roots) best = std::min(best, std::abs(r.s - s));
    worst = std::max(worst, best / (1 + std::abs(s)));
    ++matched;
  }
  std::printf("[ measured ] x' = -x - 2 x(t-1): %d Lambert-W roots in the region, worst relative distance %.2e; "
              "rightmost %.12f%+.12fi\n", matched, worst, sp.roots[0].s.real(), sp.roots[0].s.imag());
  EXPECT_GE(matched, 6);
  EXPECT_LT(worst, 1e-10);
  // Every root found is a Lambert-W root (nothing spurious): as many found as predicted.
  EXPECT_EQ(static_cast<int>(sp.roots.size()), matched);
  const Complex w0 = a + LambertW(b * tau * std::exp(-a * tau), 0) / tau;
  EXPECT_NEAR(sp.spectral_abscissa, w0.real(), 1e-10);
  EXPECT_TRUE(sp.stable);
  EXPECT_EQ(sp.essential_abscissa, -INFINITY);
}

// y' - U y'(t - tau) = -p y + p U y(t - tau): Delta(s) = (s + p)(1 - U e^{-s tau}), roots -p and the chain
// s = (ln U + 2 pi i k) / tau, exactly; the chain is the essential spectrum. U and 2 tau of the saldivar string.
TEST(Spectrum, NeutralChainOfAFactorizedSystemIsExact) {
  const double u = 0.7393, tau = 0.7445, p = 3.0;
  LinearDelaySystem sys{Scalar(-p), {{tau, Scalar(p * u), Scalar(u)}}};
  SpectrumOptions o;
  o.im_max = 100;
  const Spectrum sp = ComputeSpectrum(sys, o);
  const double chain = std::log(u) / tau;
  EXPECT_NEAR(sp.essential_abscissa, chain, 1e-12);
  int chain_roots = 0, lone = 0;
  for (const auto& r : sp.roots) {
    if (std::abs(r.s - Complex(-p, 0)) < 1e-9) {
      ++lone;
      continue;
    }
    EXPECT_NEAR(r.s.real(), chain, 1e-9) << r.s;
    const double k = r.s.imag() * tau / (2 * kPi);
    EXPECT_NEAR(k, std::round(k), 1e-9) << r.s;
    ++chain_roots;
  }
  const int expected = static_cast<int>(std::floor(o.im_max * tau / (2 * kPi))) + 1;  // k = 0 .. floor
  std::printf("[ measured ] neutral factorized: %d chain roots at Re = %.10f (exact %.10f), %d at -p; expected %d\n",
              chain_roots, sp.roots.empty() ? 0.0 : sp.roots[0].s.real(), chain, lone, expected);
  EXPECT_EQ(lone, 1);
  EXPECT_EQ(chain_roots, expected);
  EXPECT_TRUE(sp.stable);
  // The same with U > 1: the difference operator is unstable, so is the system, whatever the rightmost root says.
  LinearDelaySystem unstable{Scalar(-p), {{tau, Scalar(p * 1.2), Scalar(1.2)}}};
  const Spectrum su = ComputeSpectrum(unstable, o);
  EXPECT_NEAR(su.essential_abscissa, std::log(1.2) / tau, 1e-12);
  EXPECT_FALSE(su.stable);
}

// Incommensurate neutral delays (1 and sqrt 2): no companion matrix exists, and the essential abscissa is the robust
// one, the sigma where sup over the phase theta of rho(D_1 e^{-sigma} + D_2 e^{-sigma sqrt 2 + i theta}) falls to 1.
// For scalars the phases align at the supremum, so |d_1| e^{-sigma} + |d_2| e^{-sigma sqrt 2} = 1 exactly; for a
// non-normal pair of 2 x 2 matrices the reference is this test's own: bisection on sigma of a 20 000-point phase grid.
TEST(Spectrum, IncommensurateNeutralDelaysGiveTheRobustEssentialAbscissa) {
  const double tau_1 = 1.0, tau_2 = std::sqrt(2.0);
  auto bisect = [](auto above_one) {  // the sigma in [-10, 10] where above_one turns false
    double lo = -10, hi = 10;
    for (int it = 0; it < 60; ++it) (above_one(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
    return 0.5 * (lo + hi);
  };
  SpectrumOptions o;
  o.im_max = 30;
  for (const double d_2 : {0.3, 0.9}) {  // the difference operator stable, then unstable
    const double d_1 = -0.45;
    LinearDelaySystem sys{Scalar(-2), {{tau_1, Scalar(0.1), Scalar(d_1)}, {tau_2, Scalar(0.2), Scalar(d_2)}}};
    const double exact = bisect([&](double sigma) {
      return std::abs(d_1) * std::exp(-sigma * tau_1) + std::abs(d_2) * std::exp(-sigma * tau_2) >= 1;
    });
    const double found = ComputeSpectrum(sys, o).essential_abscissa;
    std::printf("[ measured ] scalar d = (%.2f, %.2f): essential abscissa %.10f, exact %.10f\n", d_1, d_2, found, exact);
    EXPECT_NEAR(found, exact, 1e-7 * (1 + std::abs(exact)));
  }
  Eigen::MatrixXd d1(2, 2), d2(2, 2);
  d1 << 0.3, 0.6, 0.0, -0.2;
  d2 << 0.1, 0.0, 0.5, 0.35;
  LinearDelaySystem sys{-Eigen::MatrixXd::Identity(2, 2), {{tau_1, 0.1 * d1, d1}, {tau_2, 0.1 * d2, d2}}};
  const double reference = bisect([&](double sigma) {
    double best = 0;
    for (int i = 0; i < 20000; ++i) {
      const Eigen::MatrixXcd m = std::exp(-sigma * tau_1) * d1.cast<Complex>() +
                                 std::polar(std::exp(-sigma * tau_2), 2 * kPi * i / 20000) * d2.cast<Complex>();
      best = std::max(best, m.eigenvalues().cwiseAbs().maxCoeff());
    }
    return best >= 1;
  });
  const double found = ComputeSpectrum(sys, o).essential_abscissa;
  std::printf("[ measured ] non-normal 2 x 2 pair: essential abscissa %.10f, 20 000-point reference %.10f\n", found,
              reference);
  EXPECT_NEAR(found, reference, 1e-6);
}

// The setup seed's lumped limit: x = (theta_u - theta_l, theta_u', theta_l'), characteristic polynomial
// J_u J_l l^3 + (J_u d_l + J_l d_u) l^2 + (k (J_u + J_l) + d_u d_l) l + k (d_u + d_l). The rightmost root crosses
// the imaginary axis where the Routh-Hurwitz condition a2 a1 = a3 a0 holds.
TEST(Spectrum, TwoDiscLumpedLimitCrossesWhereRouthHurwitzSays) {
  const double ju = 0.4765, jl = 0.0326, k = 0.0727, du = 2.0;
  auto system = [&](double dl) {
    Eigen::MatrixXd a(3, 3);
    a << 0, 1, -1, -k / ju, -du / ju, 0, k / jl, 0, -dl / jl;
    return LinearDelaySystem{a, {}};
  };
  // Routh-Hurwitz boundary by bisection on a2 a1 - a3 a0.
  auto hurwitz = [&](double dl) {
    const double a3 = ju * jl, a2 = ju * dl + jl * du, a1 = k * (ju + jl) + du * dl, a0 = k * (du + dl);
    return a2 * a1 - a3 * a0;
  };
  double lo = -0.01, hi = 0.0;
  for (int i = 0; i < 200; ++i) (hurwitz(0.5 * (lo + hi)) > 0 ? hi : lo) = 0.5 * (lo + hi);
  const double boundary = 0.5 * (lo + hi);
  const Spectrum above = ComputeSpectrum(system(boundary + 1e-5));
  const Spectrum below = ComputeSpectrum(system(boundary - 1e-5));
  const Spectrum on = ComputeSpectrum(system(boundary));
  std::printf("[ measured ] two-disc lumped limit: Routh-Hurwitz boundary d_l = %.8f; rightmost root there "
              "%.3e%+.6fi\n", boundary, on.roots[0].s.real(), on.roots[0].s.imag());
  EXPECT_TRUE(above.stable);
  EXPECT_FALSE(below.stable);
  EXPECT_NEAR(on.spectral_abscissa, 0.0, 1e-9);
  EXPECT_GT(on.roots[0].s.imag(), 0.1);  // a Hopf point: a complex pair crosses
  // At the crossing the frequency is sqrt(a1 / a3) (the Routh-Hurwitz quadratic factor).
  const double a3 = ju * jl, a1 = k * (ju + jl) + du * boundary;
  EXPECT_NEAR(on.roots[0].s.imag(), std::sqrt(a1 / a3), 1e-8);
}

TEST(Spectrum, RejectsMalformedSystems) {
  EXPECT_THROW(ComputeSpectrum(LinearDelaySystem{Eigen::MatrixXd(2, 3), {}}), std::invalid_argument);
  EXPECT_THROW(ComputeSpectrum(LinearDelaySystem{Scalar(1), {{0.0, Scalar(1), {}}}}), std::invalid_argument);
  EXPECT_THROW(ComputeSpectrum(LinearDelaySystem{Scalar(1), {{1.0, Eigen::MatrixXd::Zero(2, 2), {}}}}),
               std::invalid_argument);
  EXPECT_THROW(ComputeSpectrum(LinearDelaySystem{Scalar(NAN), {}}), std::invalid_argument);
}

}  // namespace
}  // namespace drillwave::analysis
