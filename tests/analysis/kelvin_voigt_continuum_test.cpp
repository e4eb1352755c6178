// The continuum Kelvin-Voigt string (analysis/kelvin_voigt_continuum.hpp) against the undamped string's exact roots,
// the modal closed form s^2 + eta w^2 s + w^2 = 0, and the discretized network the simulation integrates.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "complex_newton.hpp"
#include "drillwave/analysis/kelvin_voigt_continuum.hpp"
#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/stability.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/waves/network.hpp"
#include "json_case.hpp"

namespace drillwave::analysis {
namespace {

using Complex = std::complex<double>;

// The 1172 m pipe of the Saldivar cases.
const waves::Section kPipe = waves::Section::Torsional(1172, 79.3e9, 8000, 1.19e-5);

KelvinVoigtString PipeWithImposedTop(double eta, double bit_inertia) {
  KelvinVoigtString s;
  s.sections = {{kPipe.travel_time_s, kPipe.impedance, kPipe.length_m}};
  s.kelvin_voigt_s = eta;
  s.bit_inertia_kgm2 = bit_inertia;
  return s;
}

double RelativeDistance(const std::vector<CharacteristicRoot>& set, Complex s) {
  double d = INFINITY;
  for (const CharacteristicRoot& r : set) d = std::min(d, std::abs(r.s - s) / (1 + std::abs(s)));
  return d;
}

// The case's steady states with the continuum attached (string/kelvin_voigt_s > 0), eta and parts changed.
std::vector<cases::LinearizedOperatingPoint> CaseLinearization(const std::string& name, double eta, int parts) {
  nlohmann::json doc = testing::LoadCase(name);
  doc["model"]["string"]["kelvin_voigt_s"] = eta;
  doc["model"]["string"]["damping_subsections"] = parts;
  return cases::ParseCase(doc).model->Linearize();
}

// Imposed top, free bit of inertia I: W_top = cos x - (I x / (Z tau)) sin x at s = i x / tau, zero where
// x tan x = Z tau / I (one root in each (n pi, n pi + pi/2)).
std::vector<Complex> InertialBitClosedFormRoots(double bit_inertia, double im_max) {
  const double tau = kPipe.travel_time_s, mu = kPipe.impedance * tau / bit_inertia;
  std::vector<Complex> roots;
  for (int n = 0; n * kPi / tau < im_max; ++n) {
    double lo = n * kPi, hi = n * kPi + kPi / 2;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      (mid * std::tan(mid) < mu ? lo : hi) = mid;
    }
    if (0.5 * (lo + hi) / tau < im_max) roots.push_back({0.0, 0.5 * (lo + hi) / tau});
  }
  return roots;
}

// (a) eta -> 0: the lossless string's roots, in closed form and as the undamped network linearization finds them.
TEST(KelvinVoigtContinuum, UndampedLimitIsTheExactStringsRoots) {
  SpectrumOptions o;
  o.im_max = 60;
  const std::vector<Complex> closed = InertialBitClosedFormRoots(89, o.im_max);
  for (double eta : {0.0, 1e-15}) {
    const ContinuumSpectrum c = ComputeContinuumSpectrum(PipeWithImposedTop(eta, 89), o);
    double worst = 0;
    for (const Complex z : closed) worst = std::max(worst, RelativeDistance(c.spectrum.roots, z));
    std::printf("[ measured ] imposed top, 89 kg m^2 bit, eta %g s: %zu continuum roots, %zu closed-form (x tan x), "
                "largest distance %.2e, certified %d\n", eta, c.spectrum.roots.size(), closed.size(), worst, c.certified);
    EXPECT_EQ(c.spectrum.roots.size(), closed.size());
    EXPECT_LT(worst, 1e-10);
    EXPECT_TRUE(c.certified);
  }
  // Dissipative top, pipe + collars, Stribeck slope; PI top drive (rig-two-mass without its gear).
  for (const char* name : {"saldivar-collars", "rig-two-mass"}) {
    nlohmann::json doc = testing::LoadCase(name);
    doc["model"]["string"].erase("torsional_damping_Nms_per_rad_m");
    doc["model"]["top"].erase("gear");
    doc["model"]["top"].erase("motor_inertia_kgm2");
    const auto undamped = cases::AnalyzeStability(cases::ParseCase(doc), o);
    doc["model"]["string"]["kelvin_voigt_s"] = 1e-15;
    const auto points = cases::ParseCase(doc).model->Linearize();
    ASSERT_EQ(points.size(), undamped.size());
    ASSERT_TRUE(points[0].continuum) << name;
    const ContinuumSpectrum c = ComputeContinuumSpectrum(*points[0].continuum, o);
    double worst = 0;
    int compared = 0;
    for (const CharacteristicRoot& r : undamped[0].spectrum.roots)
      if (r.s.imag() < o.im_max - 1 && r.s.real() > o.re_min + 1)
        worst = std::max(worst, RelativeDistance(c.spectrum.roots, r.s)), ++compared;
    std::printf("[ measured ] %s undamped, eta 1e-15 s: %d roots of the network linearization, %zu continuum "
                "roots, largest distance %.2e, certified %d\n", name, compared, c.spectrum.roots.size(), worst,
                c.certified);
    EXPECT_GT(compared, 5);
    EXPECT_LT(worst, 1e-9) << name;
    EXPECT_TRUE(c.certified) << name;
  }
}

// (b) The discretized string's low modes tend to the continuum's as the parts shorten (second order: each mode's error
// falls fourfold per halving), while its near-undamped chain at pi / tau_piece has no continuum counterpart (eta =
// 0.05 s overdamps every mode above 2 / eta = 40 rad/s: the continuum's roots there are real, left of -18 1/s).
TEST(KelvinVoigtContinuum, DiscretizedRootsConvergeToTheContinuum) {
  const SpectrumOptions o;
  std::vector<Complex> low;  // the continuum's three lowest modes
  std::vector<double> previous_errors;
  for (int parts : {10, 20, 40}) {
    const auto points = CaseLinearization("saldivar-kelvin-voigt", 0.05, parts);
    ASSERT_EQ(points.size(), 1u);
    const ContinuumSpectrum c = ComputeContinuumSpectrum(*points[0].continuum, o);
    ASSERT_TRUE(c.certified);
    if (low.empty())
      for (const CharacteristicRoot& r : c.spectrum.roots)
        if (r.s.imag() > 0 && r.s.imag() < 16) low.push_back(r.s);
    ASSERT_EQ(low.size(), 3u);
    std::printf("[ measured ] saldivar-kelvin-voigt, %d parts:", parts);
    std::vector<double> errors;
    for (const Complex z : low) {
      Complex s = z;
      ASSERT_TRUE(RefineRoot(points[0].system, s, o)) << parts << " parts, from " << z;
      errors.push_back(std::abs(s - z));
      std::printf(" %.6f%+.4fi (error %.2e)", s.real(), s.imag(), errors.back());
    }
    // The chain near pi / tau_piece: the discretized model's is almost undamped; the continuum has no root there.
    const double chain = kPi * parts / kPipe.travel_time_s;
    Complex s(-0.1, chain);
    const bool found = RefineRoot(points[0].system, s, o);
    std::printf("; chain at pi/tau_piece %.1f rad/s: %.4f%+.3fi\n", chain, s.real(), s.imag());
    EXPECT_TRUE(found && s.real() > -0.2 && std::abs(s.imag() - chain) < 5) << parts << " parts";
    for (const CharacteristicRoot& r : c.spectrum.roots) EXPECT_LT(r.s.imag(), 40);
    for (std::size_t k = 0; k < previous_errors.size(); ++k)
      EXPECT_GT(previous_errors[k] / errors[k], 3.5) << parts << " parts, mode " << k;
    previous_errors = errors;
  }
  std::printf("[ measured ] continuum: %s, rightmost %.6f%+.6fi\n", "saldivar-kelvin-voigt", low.front().real(),
              low.front().imag());
}

// Imposed top and massless free bit: the continuum's modes w_k = (2k + 1) pi / (2 tau) each give
// s^2 + eta w_k^2 s + w_k^2 = 0 exactly (the Kelvin-Voigt term is proportional to the stiffness).
// With distributed viscous damping a = gamma / (rho J) as well: s^2 + (a + eta w^2) s + w^2 = 0.
std::vector<Complex> ModalRoots(double eta, const SpectrumOptions& o, double a = 0) {
  std::vector<Complex> roots;
  for (int k = 0;; ++k) {
    const double w = (2 * k + 1) * kPi / (2 * kPipe.travel_time_s), half = (a + eta * w * w) / 2;
    if (-half < o.re_min && half > w) break;  // overdamped and out of the box from here on
    const Complex root = std::sqrt(Complex(half * half - w * w));
    for (const Complex s : {-half + root, -half - root})
      if (s.real() >= o.re_min && s.imag() >= 0 && s.imag() <= o.im_max) roots.push_back(s);
  }
  return roots;
}

// (b, c) eta = 0.002 s: every continuum root is a modal root, up to pi / tau_piece of 20 parts (168.8 rad/s), where they
// decay at about eta w^2 / 2 = 28 1/s; the lowest decays at eta w0^2 / 2 = 0.017806 1/s.
TEST(KelvinVoigtContinuum, RootsAreTheModalClosedForm) {
  SpectrumOptions o;
  o.im_max = 180;
  const double eta = 0.002, w0 = kPi / (2 * kPipe.travel_time_s);
  const auto start = std::chrono::steady_clock::now();
  const ContinuumSpectrum c = ComputeContinuumSpectrum(PipeWithImposedTop(eta, 0), o);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::vector<Complex> modal = ModalRoots(eta, o);
  double worst = 0;
  for (const Complex z : modal) worst = std::max(worst, RelativeDistance(c.spectrum.roots, z));
  const CharacteristicRoot& near_chain = *std::min_element(
      c.spectrum.roots.begin(), c.spectrum.roots.end(), [&](const CharacteristicRoot& a, const CharacteristicRoot& b) {
        return std::abs(a.s.imag() - 20 * kPi / kPipe.travel_time_s) < std::abs(b.s.imag() - 20 * kPi / kPipe.travel_time_s);
      });
  const Complex lowest = c.spectrum.roots.front().s;
  std::printf("[ measured ] eta %g s: %zu continuum roots (%.3f s), %zu modal, largest distance %.2e; near pi/tau_piece"
              " (20 parts) %.4f%+.4fi (eta w^2 / 2 = %.4f); lowest %.9f%+.6fi against -eta w0^2 / 2 = %.9f\n", eta,
              c.spectrum.roots.size(), seconds, modal.size(), worst, near_chain.s.real(), near_chain.s.imag(),
              eta * near_chain.s.imag() * near_chain.s.imag() / 2, lowest.real(), lowest.imag(), -eta * w0 * w0 / 2);
  EXPECT_TRUE(c.certified);
  EXPECT_EQ(c.spectrum.roots.size(), modal.size());
  EXPECT_LT(worst, 1e-10);
  EXPECT_NEAR(near_chain.s.real(), -eta * near_chain.s.imag() * near_chain.s.imag() / 2,
              0.05 * eta * near_chain.s.imag() * near_chain.s.imag());
  EXPECT_NEAR(lowest.real(), -0.017806, 5e-7);
  EXPECT_NEAR(lowest.real(), -eta * w0 * w0 / 2, 1e-12);
}

// gamma > 0 (the distributed viscous damping of the string's equation) shifts every modal root by the same -a / 2 where
// eta alone would leave them: a = gamma / (rho J) = gamma L / (Z0 tau).
TEST(KelvinVoigtContinuum, ViscousDampingShiftsTheModalRoots) {
  SpectrumOptions o;
  o.im_max = 100;
  const double eta = 0.002, a = 0.8;
  KelvinVoigtString string = PipeWithImposedTop(eta, 0);
  string.viscous_damping_Nms_per_rad_m = a * kPipe.impedance * kPipe.travel_time_s / kPipe.length_m;
  const ContinuumSpectrum c = ComputeContinuumSpectrum(string, o);
  const std::vector<Complex> modal = ModalRoots(eta, o, a);
  double worst = 0;
  for (const Complex z : modal) worst = std::max(worst, RelativeDistance(c.spectrum.roots, z));
  std::printf("[ measured ] eta %g s, a %g 1/s: %zu continuum roots, %zu modal, largest distance %.2e; lowest "
              "%.9f%+.6fi\n", eta, a, c.spectrum.roots.size(), modal.size(), worst, c.spectrum.roots.front().s.real(),
              c.spectrum.roots.front().s.imag());
  EXPECT_TRUE(c.certified);
  EXPECT_EQ(c.spectrum.roots.size(), modal.size());
  EXPECT_LT(worst, 1e-10);
  const double w0 = kPi / (2 * kPipe.travel_time_s);
  EXPECT_NEAR(c.spectrum.roots.front().s.real(), -(a + eta * w0 * w0) / 2, 1e-10);
}

// The continuum costs the same whatever the parts: its function has one two-port per section.
// The continuum does not depend on how many parts the case names (its cost neither: printed, not asserted).
TEST(KelvinVoigtContinuum, IsTheSameWhateverThePartsAndCostsNoMore) {
  std::complex<double> first_rightmost;
  for (int parts : {20, 40, 80}) {
    const auto points = CaseLinearization("saldivar-kelvin-voigt", 0.05, parts);
    const auto start = std::chrono::steady_clock::now();
    const ContinuumSpectrum c = ComputeContinuumSpectrum(*points[0].continuum);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("[ measured ] saldivar-kelvin-voigt continuum at %d parts: %.4f s, %zu roots, rightmost %.6f%+.6fi, "
                "%s\n", parts, seconds, c.spectrum.roots.size(), c.spectrum.roots.front().s.real(),
                c.spectrum.roots.front().s.imag(), VerdictName(c.spectrum.verdict));
    EXPECT_TRUE(c.certified);
    if (parts == 20) first_rightmost = c.spectrum.roots.front().s;
    EXPECT_LT(std::abs(c.spectrum.roots.front().s - first_rightmost), 1e-10 * std::abs(first_rightmost)) << parts;
  }
}

}  // namespace
}  // namespace drillwave::analysis
