// The published stability maps of the coupled model (and of its torsional loop alone), reproduced by the
// axial_torsional kind's linearization.
//
// Aarsnes & van de Wouw (2019), "Axial and torsional self-excited vibrations of a distributed drill-string", J. Sound
// Vib. 444, map the stability of the distributed string with the Richard-Germay-Detournay cut delay in the plane of
// two non-dimensional groups, V0 and Omega0, by the Nyquist criterion on the loop gain of their public code
// (github.com/ulfjakob/AxialTorsionalDrillString, "Coupled - nondim/axStabMapForComp.m"):
//   1 + G(s) = 0,  G(s) = (1 - e^{-s t_N}) / s (K_a g(s / c) - (V0 / Omega0) g(s)),  t_N = 1 / Omega0,
//   g(x) = (1 + Z_L tanh x) / (Z_L + tanh x),  Z_L = (1 + eta) / (1 - eta),
// with time in torsional travel times L / c_t, c = c_a / c_t = 1.6, the top's reflection eta = 0.7 in both channels
// and K_a = 20 (their parameters.m). The bit is massless and the string lossless; g is the string's admittance seen
// from the bit, normalized by the pipe's impedance.
//
// drillwave's kind is the same physics with inertias: derived in the same way, its determinant is this G with the
// string's admittance g / Z replaced by 1 / (Z / g + m s) at the bit and the tops' impedance by m_top s + Z Z_L. With
// every mass m = mu Z tau (mu -> 0), the top drive's gains kp = Z_L Z_t and a vanishing ki (the set-point start needs
// one), the hoist's dashpot c_h = Z_L Z_a, no wear flat (sigma l = 0), eps for K_a = n tau a zeta eps / Z_a,
// Omega0 = n tau omega / 2 pi and V0 = Omega0 n tau (a^2 eps / 2) (d0 / 2 pi) / Z_t (d0 the depth of cut per turn),
// the kind's roots in the published band must tend to the published zeros, first order in mu. Only the band: the
// published scan stops at |Im s| = 20 pi, and a mass's end reflects totally far above 1 / (mu tau), which the
// massless model does not.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/analysis/spectrum.hpp"
#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/io/json_reader.hpp"
#include "complex_newton.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

using Complex = std::complex<double>;

constexpr double kKa = 20, kEta = 0.7, kWaveSpeedRatio = 1.6;
constexpr double kBand = 20 * kPi;  // the published scan: |Im s| up to 10 * 2 pi
constexpr double kRigidMode = 0.05;  // |s| below it: the vanishing ki's slow mode, absent from the published model

// The published characteristic function, cleared of its poles: with g = A / B, A(x) = cosh x + Z_L sinh x and
// B(x) = Z_L cosh x + sinh x, s B(s / c) B(s) (1 + G(s)) = s B_a B_t + (1 - e^{-s t_N}) (K_a A_a B_t - (V0 / Omega0)
// A_t B_a) is entire, and has the zeros of 1 + G away from s = 0 (where 1 + G has a pole, B A != 0 stays). With
// ka = 0, their torsional map (MAIN_Torsional_FreqStabMap.m: the axial loop left out), B_a is no factor of it.
struct Published {
  double v0, omega0, ka = kKa;
  Complex operator()(Complex s) const {
    const double zl = (1 + kEta) / (1 - kEta);
    const Complex at = std::cosh(s) + zl * std::sinh(s), bt = zl * std::cosh(s) + std::sinh(s);
    const Complex delay = 1.0 - std::exp(-s / omega0);
    if (ka == 0) return s * bt - delay * v0 / omega0 * at;
    const Complex xa = s / kWaveSpeedRatio;
    const Complex aa = std::cosh(xa) + zl * std::sinh(xa), ba = zl * std::cosh(xa) + std::sinh(xa);
    return s * ba * bt + delay * (ka * aa * bt - v0 / omega0 * at * ba);
  }
  bool Refine(Complex& s) const {
    testing::NewtonZeroOptions o;
    o.difference_step = 1e-7;
    o.re_bound = 20, o.im_bound = 2 * kBand;  // cosh overflows far out; the band is all that is compared
    return testing::NewtonZero(*this, s, o);
  }
  // Its zeros with Im s in [0, band], Re s >= -3, |s| >= kRigidMode, by Newton from a grid of starts; by Re desc.
  std::vector<Complex> Zeros() const {
    std::vector<Complex> zeros;
    for (double re = -3; re <= 3; re += 0.25)
      for (double im = 0.1; im <= kBand; im += 0.25) {
        Complex s(re, im);
        if (!Refine(s)) continue;
        s = {s.real(), std::abs(s.imag())};
        if (s.imag() > kBand || s.real() < -3 || std::abs(s) < kRigidMode) continue;
        if (std::none_of(zeros.begin(), zeros.end(), [&](Complex z) { return std::abs(z - s) < 1e-8; }))
          zeros.push_back(s);
      }
    // Real zeros beyond that box: a large torsional gain V0 / Omega0 puts one near V0 / Omega0 - K_a. On the real
    // axis 1 + G is real and pole-free; bracket its sign changes and bisect.
    auto one_plus_g = [&](double x) {
      const double zl = (1 + kEta) / (1 - kEta);
      auto g = [&](double y) { return (1 + zl * std::tanh(y)) / (zl + std::tanh(y)); };
      return 1 + (1 - std::exp(-x / omega0)) / x * (ka * g(x / kWaveSpeedRatio) - v0 / omega0 * g(x));
    };
    const double reach = v0 / omega0 + ka + 10;
    for (double lo = 3, step = reach / 2000; lo < reach; lo += step) {
      double a = lo, b = lo + step;
      if ((one_plus_g(a) > 0) == (one_plus_g(b) > 0)) continue;
      for (int k = 0; k < 100 && b - a > 1e-13 * b; ++k) ((one_plus_g(0.5 * (a + b)) > 0) == (one_plus_g(a) > 0) ? a : b) = 0.5 * (a + b);
      zeros.emplace_back(0.5 * (a + b), 0.0);
    }
    std::sort(zeros.begin(), zeros.end(), [](Complex a, Complex b) { return a.real() > b.real(); });
    return zeros;
  }
};

// The baseline case as the published model's physical twin at (V0, Omega0), masses mu Z tau. With axial_blocked the
// bit's mass is a million Z_a tau instead: the bit cannot move axially within the band, the axial loop drops out and
// what is left is the published torsional map's loop.
struct Twin {
  nlohmann::json doc;
  double tau = 0;  // torsional travel time [s], the published time unit
  Twin(double v0, double omega0, double mu, bool axial_blocked = false) {
    doc = testing::LoadCase("baseline-60rpm");
    doc.erase("expect");
    auto& m = doc["model"];
    auto& s = m["string"];
    const double g = s["shear_modulus_Pa"], rho = s["density_kg_m3"], length = s["length_m"];
    const double od = s["outer_diameter_m"], id = s["inner_diameter_m"];
    const double e = kWaveSpeedRatio * kWaveSpeedRatio * g;
    s["youngs_modulus_Pa"] = e;
    s["mud_density_kg_m3"] = 0;
    s["torsional_damping_Nms_per_rad_m"] = 0;
    s["axial_damping_Ns_per_m2"] = 0;
    s["subsections"] = 2;
    s.erase("side_friction");
    const double zt = kPi / 32 * (std::pow(od, 4) - std::pow(id, 4)) * std::sqrt(g * rho);
    const double za = kPi / 4 * (od * od - id * id) * std::sqrt(e * rho);
    tau = length / std::sqrt(g / rho);
    const double zl = (1 + kEta) / (1 - kEta);
    const int n = m["bit"]["blades"];
    const double a = m["bit"]["radius_m"], zeta = m["rock"]["zeta"];
    const double eps = kKa * za / (n * tau * a * zeta);
    m["rock"]["intrinsic_specific_energy_Pa"] = eps;
    m["rock"]["sigma_l_N_per_m"] = 0;
    const double omega = 2 * kPi * omega0 / (n * tau);
    const double depth = v0 * 2 * kPi * zt / (omega0 * n * tau * (a * a * eps / 2));
    const double kp = zl * zt;
    m["top"] = {{"inertia_kgm2", mu * zt * tau}, {"kp_Nms_per_rad", kp}, {"ki_Nm_per_rad", 1e-6 * kp / tau},
                {"speed_rad_s", omega}};
    m["hoist"] = {{"mass_kg", mu * za * tau}, {"damping_Ns_per_m", zl * za}, {"weight_on_bit_N", a * zeta * eps * depth}};
    m["bit"]["inertia_kgm2"] = mu * zt * tau;
    m["bit"]["mass_kg"] = (axial_blocked ? 1e6 : mu) * za * tau;
  }
  // The linearization's roots in the published band, in published units (s tau), by Re desc.
  std::vector<Complex> Roots() const {
    const auto points = ParseCase(doc).model->Linearize();
    if (points.size() != 1) return {};
    analysis::SpectrumOptions o;
    o.im_max = 1.2 * kBand / tau;
    o.re_min = -3 / tau;
    o.collocation_nodes = 96;
    std::vector<Complex> roots;
    for (const auto& r : analysis::ComputeSpectrum(points[0].system, o).roots) {
      const Complex s = r.s * tau;
      if (s.imag() <= kBand && std::abs(s) >= kRigidMode) roots.push_back(s);
    }
    return roots;
  }
};

double Rightmost(const std::vector<Complex>& roots) {
  return roots.empty() ? -std::numeric_limits<double>::infinity() : roots.front().real();
}

// At a few points of the published plane, in and out of the unstable region: every root of the kind with Re s > -1
// lies next to a published zero and vice versa, the distance falls about tenfold with mu, and at mu = 1e-6 it is
// below 2e-4 (published units).
TEST(PublishedStabilityMap, CoupledRootsTendToTheZerosOfAarsnesAndVanDeWouw) {
  for (const auto& [v0, omega0] : {std::pair{1.0, 2.6}, std::pair{10.0, 5.0}, std::pair{31.6, 19.0}}) {
    const Published published{v0, omega0};
    const std::vector<Complex> zeros = published.Zeros();
    ASSERT_FALSE(zeros.empty());
    double previous = 0;
    for (double mu : {1e-4, 1e-5, 1e-6}) {
      const std::vector<Complex> roots = Twin(v0, omega0, mu).Roots();
      double worst = 0;
      int matched = 0;
      auto nearest = [](Complex s, const std::vector<Complex>& set) {
        double d = std::numeric_limits<double>::infinity();
        for (Complex z : set) d = std::min(d, std::abs(z - s));
        return d;
      };
      for (Complex r : roots) {
        if (r.real() > -1) worst = std::max(worst, nearest(r, zeros)), ++matched;
      }
      for (Complex z : zeros) {
        if (z.real() > -1 && z.imag() < kBand - 1) worst = std::max(worst, nearest(z, roots));
      }
      std::printf("[ measured ] V0 %.1f, Omega0 %.1f, mu %.0e: %d roots with Re s > -1, farthest from a published "
                  "zero (or a zero from a root) %.2e; rightmost %.6f (published %.6f)\n",
                  v0, omega0, mu, matched, worst, Rightmost(roots), Rightmost(zeros));
      EXPECT_GE(matched, 5);
      if (previous > 0) {
        EXPECT_LT(worst, 0.2 * previous) << "V0 " << v0 << ", Omega0 " << omega0 << ", mu " << mu;
      }
      previous = worst;
    }
    EXPECT_LT(previous, 2e-4) << "V0 " << v0 << ", Omega0 " << omega0;
  }
}

// The boundary of the published map at K_a = 20: along V0 = 1 and V0 = 10 the axial regenerative mode stabilizes as
// the rotation speeds up. The kind's boundary (mu = 1e-6), found by bisection on the rightmost root in the band,
// lies where the published one does.
TEST(PublishedStabilityMap, BoundaryInRotationSpeedIsThePublishedOne) {
  for (double v0 : {1.0, 10.0}) {
    auto bisect = [&](auto rightmost) {
      double lo = 5, hi = 25;  // unstable at 5, stable at 25 (both sides checked)
      EXPECT_GT(rightmost(lo), 0);
      EXPECT_LT(rightmost(hi), 0);
      for (int k = 0; k < 30 && hi - lo > 1e-6 * hi; ++k) {
        const double mid = 0.5 * (lo + hi);
        (rightmost(mid) > 0 ? lo : hi) = mid;
      }
      return 0.5 * (lo + hi);
    };
    const double published = bisect([&](double om) { return Rightmost(Published{v0, om}.Zeros()); });
    const double kind = bisect([&](double om) { return Rightmost(Twin(v0, om, 1e-6).Roots()); });
    std::printf("[ measured ] V0 %.0f: stable above Omega0 = %.6f (published characteristic function) and %.6f (the "
                "kind's linearization, mu 1e-6)\n", v0, published, kind);
    EXPECT_NEAR(kind, published, 1e-4 * published);
  }
}

// The published maps' grid (axStabMapForComp.m scans V0 in [0.1, 31.6] and Omega0 in [0.049, 51], log-spaced): on a
// 5 x 6 grid of it the kind (mu = 1e-6) gives every verdict of the published function, and its rightmost root in the
// band within 1e-3 (relative beyond |s| = 1: at small Omega0 and large V0 a real root near V0 / Omega0 - K_a). Both
// maps: the coupled one at K_a = 20, and the torsional one (their MAIN_Torsional_FreqStabMap.m) with the bit held
// axially by a large mass.
void ExpectThePublishedVerdictsOnTheGrid(bool torsional) {
  int unstable = 0, points = 0;
  double worst = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 6; ++j) {
      const double v0 = std::pow(10, -1 + 2.5 * i / 4), omega0 = std::pow(10, -1.31 + 3.02 * j / 5);
      const double published = Rightmost(Published{v0, omega0, torsional ? 0.0 : kKa}.Zeros());
      const double kind = Rightmost(Twin(v0, omega0, 1e-6, torsional).Roots());
      EXPECT_EQ(kind > 0, published > 0) << "V0 " << v0 << ", Omega0 " << omega0 << ": " << kind << " vs " << published;
      // The masses' error grows with |s| (mu s tau against the impedances): relative for the fast real roots.
      const double error = std::abs(kind - published) / std::max(1.0, std::abs(published));
      EXPECT_LT(error, 1e-3) << "V0 " << v0 << ", Omega0 " << omega0 << ": " << kind << " vs " << published;
      worst = std::max(worst, error);
      unstable += published > 0;
      ++points;
    }
  std::printf("[ measured ] %s map: %d grid points, %d unstable by the published function; the kind agrees on every "
              "verdict, rightmost roots within %.2e (relative beyond 1)\n", torsional ? "torsional" : "coupled", points,
              unstable, worst);
  EXPECT_GT(unstable, 0);
  EXPECT_LT(unstable, points);
}

TEST(PublishedStabilityMap, VerdictsOnThePublishedGridAreThePublishedOnes) { ExpectThePublishedVerdictsOnTheGrid(false); }

TEST(PublishedStabilityMap, TorsionalVerdictsOnThePublishedGridAreThePublishedOnes) {
  ExpectThePublishedVerdictsOnTheGrid(true);
}

}  // namespace
}  // namespace drillwave::cases
