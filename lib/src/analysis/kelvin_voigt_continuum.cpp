#include "drillwave/analysis/kelvin_voigt_continuum.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "drillwave/analysis/rightmost_root.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/validity.hpp"

namespace drillwave::analysis {
namespace {

using Complex = std::complex<double>;

// cosh(q) and sinh(q) / q for q^2 = x: even in q, so entire in x (series near 0, where sinh(q) / q is 0 / 0).
struct EvenHyperbolic {
  Complex cosh, sinhc;
};
EvenHyperbolic EvenHyperbolicOf(Complex x) {
  if (std::abs(x) < 1e-6) return {1.0 + x / 2.0 + x * x / 24.0, 1.0 + x / 6.0 + x * x / 120.0};
  const Complex q = std::sqrt(x);
  return {std::cosh(q), std::sinh(q) / q};
}

// The section's two-port from its lower end's (W, D) to its upper end's (header: k, Z by the lossless tau and Z0).
struct TwoPort {
  Complex cosh, sinh_over_z, z_sinh;
  void Apply(Complex& w, Complex& d) const {
    const Complex upper_w = cosh * w + sinh_over_z * d;
    d = z_sinh * w + cosh * d;
    w = upper_w;
  }
};
TwoPort SectionTwoPort(const ContinuumSection& section, double eta, double gamma, Complex s) {
  const double tau = section.travel_time_s, z0 = section.impedance;
  const double rho_j = z0 * tau / section.length_m;  // Z0 = rho J c, c = L / tau
  const double a = gamma / rho_j;
  const Complex stiffness = 1.0 + eta * s;  // the Kelvin-Voigt factor of G J
  const EvenHyperbolic h = EvenHyperbolicOf(s * (s + a) * tau * tau / stiffness);
  return {h.cosh, s * tau * h.sinhc / (z0 * stiffness), z0 * tau * (s + a) * h.sinhc};
}

void CheckString(const KelvinVoigtString& str) {
  auto bad = [](const std::string& what) { throw std::invalid_argument("continuum string: " + what); };
  if (str.sections.empty()) bad("no section");
  for (const ContinuumSection& s : str.sections)
    if (!(s.travel_time_s > 0 && s.impedance > 0 && s.length_m > 0) || !std::isfinite(s.travel_time_s) ||
        !std::isfinite(s.impedance) || !std::isfinite(s.length_m))
      bad("a section's travel time, impedance and length must be positive and finite");
  if (!(str.kelvin_voigt_s >= 0) || !std::isfinite(str.kelvin_voigt_s)) bad("eta must be >= 0 and finite");
  if (!(str.viscous_damping_Nms_per_rad_m >= 0) || !std::isfinite(str.viscous_damping_Nms_per_rad_m))
    bad("gamma must be >= 0 and finite");
  if (!(str.bit_inertia_kgm2 >= 0) || !std::isfinite(str.bit_torque_slope_Nms_per_rad))
    bad("the bit's inertia must be >= 0 and its torque slope finite");
}

double TotalTravelTime(const KelvinVoigtString& str) {
  double total = 0;
  for (const ContinuumSection& s : str.sections) total += s.travel_time_s;
  return total;
}

// Beyond it no root: the bit's I_B s + c meets the passive string's input impedance (Re Z_in >= 0 for Re s >= 0), so
// a root has I_B Re s <= -c. A massless velocity-weakening bit has no such bound: 1000 1/s is taken.
double RootRealPartBound(const KelvinVoigtString& str, double rightmost) {
  const double c = str.bit_torque_slope_Nms_per_rad, inertia = str.bit_inertia_kgm2;
  const double bound = c >= 0 ? 1.0 : inertia > 0 ? 1.0 - c / inertia : 1e3;
  return std::max(bound, rightmost + 1.0);
}

int ExpectedCount(const std::vector<Complex>& roots, double re_left) {
  int expected = 0;
  for (const Complex s : roots)
    if (s.real() > re_left) expected += s.imag() == 0 ? 1 : 2;
  return expected;
}

// Newton from every start of a grid over the box (rows pi / (4 T) / 2^round apart in Im s, 4 * 2^round columns in
// Re s), each run with the roots already in `found` divided out; new roots in the box are appended.
void SearchGrid(const CharacteristicFunction& f, const ContinuumSpectrum& box, double total_tau, int round,
                const SpectrumOptions& o, std::vector<Complex>& found) {
  const double row = kPi / (4 * total_tau) / (1 << round);
  const int columns = 4 << round;
  for (double im = 0.5 * row; im < box.im_max; im += row)
    for (int j = 0; j < columns; ++j) {
      Complex s(box.re_right + (box.re_left - box.re_right) * (j + 0.5) / columns, im);
      if (!NewtonOnFunction(f, s, o.newton_iterations, found)) continue;
      if (s.imag() < 0) s = std::conj(s);
      if (std::abs(s.imag()) < 1e-9 * (1.0 + std::abs(s))) s = {s.real(), 0.0};
      if (s.real() < box.re_left || s.imag() > box.im_max) continue;
      if (std::none_of(found.begin(), found.end(), [&](Complex r) { return std::abs(r - s) <= 1e-7 * (1 + std::abs(s)); }))
        found.push_back(s);
    }
}

// Newton's method on f itself (not on ln f) with a central difference, from a root found to about 1e-9: the fixed point
// f(s) = 0 does not depend on the difference's error, so a few steps settle the root to rounding. The polished root
// is kept unless it moved farther than the search's accuracy.
Complex PolishRoot(const KelvinVoigtString& str, Complex s) {
  Complex polished = s;
  for (int it = 0; it < 8; ++it) {
    const Complex h = 1e-6 * (1.0 + std::abs(polished));
    auto f = [&](Complex z) { return ContinuumCharacteristic(str, z).value(); };
    const Complex slope = (f(polished + h) - f(polished - h)) / (2.0 * h);
    if (slope == 0.0) break;
    const Complex step = f(polished) / slope;
    polished -= step;
    if (std::abs(step) <= 1e-15 * (1.0 + std::abs(polished))) break;
  }
  if (!(std::abs(polished - s) <= 1e-6 * (1.0 + std::abs(s)))) return s;
  return s.imag() == 0 ? Complex(polished.real(), 0.0) : polished;
}

}  // namespace

ContinuumValue ContinuumCharacteristic(const KelvinVoigtString& str, Complex s) {
  Complex w = 1.0, d = str.bit_inertia_kgm2 * s + str.bit_torque_slope_Nms_per_rad;
  for (auto it = str.sections.rbegin(); it != str.sections.rend(); ++it)
    SectionTwoPort(*it, str.kelvin_voigt_s, str.viscous_damping_Nms_per_rad_m, s).Apply(w, d);
  const ContinuumTop& top = str.top;
  switch (top.kind) {
    case ContinuumTop::Kind::kImposedSpeed: return {w, 0.0};
    case ContinuumTop::Kind::kDashpot: return {top.damping_Nms_per_rad * w, d};
    case ContinuumTop::Kind::kPiSpeed: {
      const Complex drive = top.inertia_kgm2 * s + top.damping_Nms_per_rad;
      // With an integral gain the PI's 1/s pole is multiplied out (its integral is a state of the system).
      if (top.ki_Nm_per_rad > 0) return {(drive * s + top.ki_Nm_per_rad) * w, s * d};
      return {drive * w, d};
    }
  }
  return {w, d};
}

ContinuumSpectrum ComputeContinuumSpectrum(const KelvinVoigtString& str, const SpectrumOptions& o) {
  CheckString(str);
  ThrowIfInvalid(o);
  const double eta = str.kelvin_voigt_s, total_tau = TotalTravelTime(str);
  const CharacteristicFunction f = [&str](Complex s) {
    const Complex v = ContinuumCharacteristic(str, s).value();
    const double size = std::abs(v);
    if (!(size > 0) || !std::isfinite(size)) return CharacteristicDeterminant::Value{-INFINITY, Complex(1.0)};
    return CharacteristicDeterminant::Value{std::log(size), v / size};
  };
  ContinuumSpectrum out;
  out.re_left = eta > 0 ? std::max(o.re_min, -0.9 / eta) : o.re_min;  // right of the roots' accumulation at -1/eta
  out.im_max = o.im_max;
  out.re_right = RootRealPartBound(str, out.re_left);
  std::vector<Complex> found;
  for (int round = 0; round < 4 && !out.certified; ++round) {
    SearchGrid(f, out, total_tau, round, o, found);
    SortRightmostFirst(found);
    out.re_right = RootRealPartBound(str, found.empty() ? out.re_left : found.front().real());
    const int count = CountRootsInBox(f, 0.25 / total_tau, out.re_left, out.re_right, out.im_max);
    out.certified = count == ExpectedCount(found, out.re_left);
  }
  for (Complex& s : found) s = PolishRoot(str, s);
  SortRightmostFirst(found);
  Spectrum& sp = out.spectrum;
  for (const Complex s : found) {
    const ContinuumValue v = ContinuumCharacteristic(str, s);
    sp.roots.push_back({s, std::abs(v.value()) / (std::abs(v.a) + std::abs(v.b))});
  }
  sp.candidates = sp.refined = static_cast<int>(found.size());
  sp.spectral_abscissa = found.empty() ? -std::numeric_limits<double>::infinity() : found.front().real();
  sp.essential_abscissa = eta > 0 ? -1 / eta : std::numeric_limits<double>::quiet_NaN();
  SetVerdict(sp);
  return out;
}

}  // namespace drillwave::analysis
