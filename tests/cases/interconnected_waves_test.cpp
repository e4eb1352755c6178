// The chapter's interconnected axial and torsional waves (kind interconnected_waves, eqs. 2.12-2.13): steady drilling
// against the closed form alpha1 v = alpha2 H - F(v), beta1 omega = beta2 Omega - F~(v); the bit's two speeds against
// an independent method-of-lines discretization of the two wave equations (lumped masses and springs, RK4), converging
// at second order; and bad input refused with its JSON path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/stability.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "refused_path.hpp"

namespace drillwave::cases {
namespace {

using nlohmann::json;
using Complex = std::complex<double>;

// The pipe of the chapter case (5-inch drill pipe, steel), 1000 m.
constexpr double kLength = 1000, kOuter = 0.127, kInner = 0.1086, kYoung = 200e9, kShear = 79.3e9, kDensity = 8000;
const double kArea = kPi / 4 * (kOuter * kOuter - kInner * kInner);
const double kPolar = kPi / 32 * (std::pow(kOuter, 4) - std::pow(kInner, 4));

// The chapter's law p k z / (k^2 z^2 + zeta), written out here independently of the library's.
struct Rational {
  double p, k, zeta;
  double operator()(double z) const { return p * k * z / (k * k * z * z + zeta); }
  json Json() const { return {{"law", "rational"}, {"p_Nm", p}, {"k", k}, {"zeta", zeta}}; }
};

struct Parameters {
  double alpha1, alpha2, beta1, beta2, mass, inertia;
  Rational weight, torque;
  json hook_force, top_speed;  // schedules
};

json Case(const Parameters& p, double duration, double tolerance) {
  return {{"name", "interconnected"},
          {"model",
           {{"kind", "interconnected_waves"},
            {"string",
             {{"length_m", kLength},
              {"outer_diameter_m", kOuter},
              {"inner_diameter_m", kInner},
              {"youngs_modulus_Pa", kYoung},
              {"shear_modulus_Pa", kShear},
              {"density_kg_m3", kDensity}}},
            {"hoist", {{"alpha1_Ns_per_m", p.alpha1}, {"alpha2", p.alpha2}, {"hook_force_N", p.hook_force}}},
            {"top",
             {{"beta1_Nms_per_rad", p.beta1}, {"beta2_Nms_per_rad", p.beta2}, {"speed_rad_s", p.top_speed}}},
            {"bit",
             {{"mass_kg", p.mass},
              {"inertia_kgm2", p.inertia},
              {"weight_law", p.weight.Json()},
              {"torque_law", p.torque.Json()}}}}},
          {"simulation",
           {{"duration_s", duration}, {"output_interval_s", 0.01}, {"abs_tol", tolerance}, {"rel_tol", tolerance}}}};
}

// The root of f, increasing on [lo, hi] with a sign change, by bisection.
double Bisect(const std::function<double(double)>& f, double lo, double hi) {
  for (int i = 0; i < 200; ++i) (f(0.5 * (lo + hi)) < 0 ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

TEST(InterconnectedWaves, SteadyStateIsTheClosedForm) {
  // Tops that reflect 0.3 of each wave (alpha1 = 0.7 / 1.3 Z_a, beta1 = 1.3 / 0.7 Z_t), constant inputs: the
  // transients die within the run; on the rising branch of the weight law (peak at sqrt(zeta) / k = 0.063 m/s).
  const double za = kArea * std::sqrt(kYoung * kDensity), zt = kPolar * std::sqrt(kShear * kDensity);
  Parameters p{0.7 / 1.3 * za, 0.8, 1.3 / 0.7 * zt, 500, 2e4, 70, {4000, 0.5, 1e-3}, {200, 0.5, 1e-3}, 30e3, 8.0};
  const CaseRun run = RunCase(ParseCase(Case(p, 60, 1e-10)));
  const double v = Bisect([&](double z) { return p.alpha1 * z + p.weight(z) - p.alpha2 * 30e3; }, 0, 0.063);
  const double omega = (p.beta2 * 8.0 - p.torque(v)) / p.beta1;
  const double rpm = 30 / kPi;
  const struct {
    const char* channel;
    double expected;
  } checks[] = {{"bit_axial_speed_m_s", v},        {"top_axial_speed_m_s", v},
                {"bit_rpm", omega * rpm},          {"top_rpm", omega * rpm},
                {"wob_N", p.weight(v)},            {"top_force_N", p.weight(v)},
                {"bit_torque_Nm", p.torque(v)},    {"top_torque_Nm", p.torque(v)}};
  std::printf("[ measured ] steady v = %.10g m/s, omega = %.10g rad/s (closed form)\n", v, omega);
  for (const auto& c : checks) {
    const double got = run.result.channel(c.channel).values.back();
    std::printf("[ measured ] %-20s %.12g, closed form %.12g, relative error %.2g\n", c.channel, got, c.expected,
                std::abs(got - c.expected) / std::abs(c.expected));
    EXPECT_NEAR(got, c.expected, 1e-8 * std::abs(c.expected)) << c.channel;
  }
  EXPECT_GT(v, 0.01);  // a real operating point, not the string at rest
  EXPECT_GT(p.torque(v), 0.1 * p.beta2 * 8.0);
}

// --- Method-of-lines reference --------------------------------------------------------------------------------------
// One channel as n + 1 lumped masses joined by n springs K / ds: half a segment's mass at each end, the bit's inertia
// added to the last node, the top's dashpot and input on the first (E Gamma U_s(0) = d U_t(0) - g I(t)):
//   m/2 q0'' = K (q1 - q0)/ds - d q0' + g I(t),   m qj'' = K (q_{j+1} - 2 qj + q_{j-1}) / ds,
//   (I_bit + m/2) qn'' = -K (qn - q_{n-1}) / ds - load(v_axial_bit).
struct LumpedChannel {
  double stiffness, mass_per_m, top_damping, top_gain, bit_inertia;
  std::function<double(double)> input;
  std::function<double(double)> load;  // of the bit's axial speed
};

class MethodOfLines {
 public:
  MethodOfLines(std::vector<LumpedChannel> channels, int n) : ch_(std::move(channels)), n_(n), ds_(kLength / n) {
    x_.assign(ch_.size() * 2 * (n_ + 1), 0.0);
  }
  // Bit speed of channel c (its last node's velocity).
  double BitSpeed(const std::vector<double>& x, std::size_t c) const { return x[Offset(c) + 2 * n_ + 1]; }
  double BitSpeed(std::size_t c) const { return BitSpeed(x_, c); }
  // One classical Runge-Kutta step.
  void Step(double t, double dt) {
    const std::size_t m = x_.size();
    std::vector<double> k1(m), k2(m), k3(m), k4(m), y(m);
    Rates(t, x_, k1);
    for (std::size_t i = 0; i < m; ++i) y[i] = x_[i] + 0.5 * dt * k1[i];
    Rates(t + 0.5 * dt, y, k2);
    for (std::size_t i = 0; i < m; ++i) y[i] = x_[i] + 0.5 * dt * k2[i];
    Rates(t + 0.5 * dt, y, k3);
    for (std::size_t i = 0; i < m; ++i) y[i] = x_[i] + dt * k3[i];
    Rates(t + dt, y, k4);
    for (std::size_t i = 0; i < m; ++i) x_[i] += dt / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  }

 private:
  // Layout per channel: positions q0..qn, then velocities.
  std::size_t Offset(std::size_t c) const { return c * 2 * (n_ + 1); }
  void Rates(double t, const std::vector<double>& x, std::vector<double>& dx) const {
    const double v_axial = BitSpeed(x, 0);
    for (std::size_t c = 0; c < ch_.size(); ++c) {
      const LumpedChannel& l = ch_[c];
      const double* q = &x[Offset(c)];
      const double* v = q + n_ + 1;
      double* dq = &dx[Offset(c)];
      double* dv = dq + n_ + 1;
      const double k = l.stiffness / ds_, m = l.mass_per_m * ds_;
      for (int j = 0; j <= n_; ++j) dq[j] = v[j];
      dv[0] = (k * (q[1] - q[0]) - l.top_damping * v[0] + l.top_gain * l.input(t)) / (0.5 * m);
      for (int j = 1; j < n_; ++j) dv[j] = k * (q[j + 1] - 2 * q[j] + q[j - 1]) / m;
      dv[n_] = (-k * (q[n_] - q[n_ - 1]) - l.load(v_axial)) / (l.bit_inertia + 0.5 * m);
    }
  }

  std::vector<LumpedChannel> ch_;
  int n_;
  double ds_;
  std::vector<double> x_;
};

// A C2 ramp from 0 to `level` over [0, rise] (smootherstep), and as knots every `knot` seconds for the kind.
double Ramp(double t, double level, double rise) {
  const double s = std::clamp(t / rise, 0.0, 1.0);
  return level * s * s * s * (10 - 15 * s + 6 * s * s);
}
json RampKnots(double level, double rise, double knot) {
  json knots = json::array();
  const int n = static_cast<int>(std::lround(rise / knot));
  for (int i = 0; i <= n; ++i) knots.push_back({i * knot, Ramp(i * knot, level, rise)});
  return {{"knots", knots}};
}

TEST(InterconnectedWaves, BitSpeedsConvergeToTheMethodOfLinesAtSecondOrder) {
  // A weight law about as stiff as the axial string (F'(0) = 1e5 N s/m against Z_a = 1.4e5), so that the axial waves
  // reach the bit and reflect; tops that reflect part of each wave. Inputs ramp smoothly in 0.2 s.
  constexpr double kRise = 0.2, kHook = 2000, kOmega = 5, kEnd = 2;
  const Parameters p{5e4, 1.0, 2000, 2000, 2000, 20, {100, 1, 1e-3}, {30, 1, 1e-3},
                     RampKnots(kHook, kRise, 2.5e-4), RampKnots(kOmega, kRise, 2.5e-4)};
  const CaseRun run = RunCase(ParseCase(Case(p, kEnd, 1e-11)));
  const std::vector<double>& time = run.result.time_s;
  const std::vector<double>& v_kind = run.result.channel("bit_axial_speed_m_s").values;
  const std::vector<double>& rpm_kind = run.result.channel("bit_rpm").values;

  const std::vector<LumpedChannel> channels = {
      {kYoung * kArea, kDensity * kArea, p.alpha1, p.alpha2, p.mass, [&](double t) { return Ramp(t, kHook, kRise); },
       p.weight},
      {kShear * kPolar, kDensity * kPolar, p.beta1, p.beta2, p.inertia,
       [&](double t) { return Ramp(t, kOmega, kRise); }, p.torque}};
  double v_scale = 0, w_scale = 0;
  for (std::size_t i = 0; i < time.size(); ++i)
    v_scale = std::max(v_scale, std::abs(v_kind[i])), w_scale = std::max(w_scale, std::abs(rpm_kind[i]));
  std::vector<double> errors;
  for (int n : {100, 200, 400}) {
    MethodOfLines mol(channels, n);
    const int per_sample = static_cast<int>(std::ceil(0.01 / (0.2 * kLength / n / std::sqrt(kYoung / kDensity))));
    const double dt = 0.01 / per_sample;
    double worst_v = 0, worst_w = 0, t = 0;
    for (std::size_t i = 1; i < time.size(); ++i) {
      for (int k = 0; k < per_sample; ++k, t += dt) mol.Step(t, dt);
      t = time[i];
      worst_v = std::max(worst_v, std::abs(mol.BitSpeed(0) - v_kind[i]) / v_scale);
      worst_w = std::max(worst_w, std::abs(mol.BitSpeed(1) * 30 / kPi - rpm_kind[i]) / w_scale);
    }
    std::printf("[ measured ] N = %d: largest bit-speed difference over 0-%g s, axial %.3g, torsional %.3g (of the "
                "largest speed)\n", n, kEnd, worst_v, worst_w);
    errors.push_back(std::max(worst_v, worst_w));
  }
  const double order1 = std::log2(errors[0] / errors[1]), order2 = std::log2(errors[1] / errors[2]);
  std::printf("[ measured ] observed order 100->200: %.3f, 200->400: %.3f\n", order1, order2);
  EXPECT_GT(order1, 1.8);
  EXPECT_LT(order1, 2.2);
  EXPECT_GT(order2, 1.8);
  EXPECT_LT(order2, 2.2);
  EXPECT_LT(errors[2], 1e-2);
}

// --- Linearization ----------------------------------------------------------------------------------------------------
// The chapter's law's slope, written out: F'(z) = p k (zeta - k^2 z^2) / (k^2 z^2 + zeta)^2.
double Slope(const Rational& f, double z) {
  const double q = f.k * f.k * z * z + f.zeta;
  return f.p * f.k * (f.zeta - f.k * f.k * z * z) / (q * q);
}

// One channel's characteristic function about steady drilling, from the round trip w(t) = r (v(t - 2 tau) - w(t -
// 2 tau)) and the bit's law I v' = Z (2 w - v) - load (load slope c):
//   f(s) = (I s + Z + c)(1 + r e^{-2 s tau}) - 2 Z r e^{-2 s tau}.
struct ClosedForm {
  double inertia, impedance, slope, reflection, travel_time;

  Complex Value(Complex s) const {
    const Complex e = std::exp(-2.0 * s * travel_time);
    return (inertia * s + impedance + slope) * (1.0 + reflection * e) - 2 * impedance * reflection * e;
  }
  Complex Derivative(Complex s) const {
    const Complex e = std::exp(-2.0 * s * travel_time);
    return inertia * (1.0 + reflection * e) - 2 * travel_time * reflection * e * (inertia * s + impedance + slope) +
           4 * travel_time * impedance * reflection * e;
  }
  // |f(s)| over the size of its terms: ~ rounding at a root.
  double RelativeResidual(Complex s) const {
    const Complex e = std::exp(-2.0 * s * travel_time);
    const double terms = (std::abs(inertia * s) + std::abs(impedance + slope)) * (1 + std::abs(reflection * e)) +
                         2 * impedance * std::abs(reflection * e);
    return std::abs(Value(s)) / terms;
  }
  // Newton from every start of a grid over Re s in [-12, 4], Im s in [0, 80], and along the real axis up to 400;
  // distinct roots with Im s >= 0 (the rest are conjugates) in re >= re_min, im <= im_max.
  std::vector<Complex> Roots(double re_min, double im_max) const {
    std::vector<Complex> starts;
    for (double re = -12; re <= 4; re += 2)
      for (double im = 0; im <= 80; im += 0.5) starts.emplace_back(re, im);
    for (double re = 8; re <= 400; re *= 1.5) starts.emplace_back(re, 0);
    std::vector<Complex> roots;
    for (Complex s : starts) {
      bool converged = false;
      for (int i = 0; i < 100 && !converged; ++i) {
        const Complex step = Value(s) / Derivative(s);
        s -= step;
        converged = std::abs(step) < 1e-14 * (1 + std::abs(s));
      }
      if (!converged || s.real() < re_min || std::abs(s.imag()) > im_max) continue;
      s = {s.real(), std::abs(s.imag())};
      if (std::abs(s.imag()) < 1e-9 * (1 + std::abs(s))) s = s.real();
      if (std::none_of(roots.begin(), roots.end(), [&](Complex r) { return std::abs(r - s) < 1e-8 * (1 + std::abs(s)); }))
        roots.push_back(s);
    }
    return roots;
  }
};

const double kAxialImpedance = kArea * std::sqrt(kYoung * kDensity);
const double kTorsionalImpedance = kPolar * std::sqrt(kShear * kDensity);
const double kAxialTravel = kLength / std::sqrt(kYoung / kDensity);
const double kTorsionalTravel = kLength / std::sqrt(kShear / kDensity);

ClosedForm AxialClosedForm(const Parameters& p, double v) {
  return {p.mass, kAxialImpedance, Slope(p.weight, v), (kAxialImpedance - p.alpha1) / (kAxialImpedance + p.alpha1),
          kAxialTravel};
}
ClosedForm TorsionalClosedForm(const Parameters& p) {
  return {p.inertia, kTorsionalImpedance, 0, (kTorsionalImpedance - p.beta1) / (kTorsionalImpedance + p.beta1),
          kTorsionalTravel};
}

TEST(InterconnectedWaves, CharacteristicRootsAreThoseOfTheClosedForm) {
  // The chapter case's tops, bit and laws on the 1000 m pipe: three steady states at H = 100 kN (the weight law's hump
  // makes alpha1 v + F(v) rise, fall and rise), the middle one on the falling side with alpha1 + F' < 0.
  const Parameters p = {1e5, 1, 2000, 2000, 25600, 89, {700, 0.5, 1e-5}, {28, 0.5, 1e-5}, 1e5, 10.0};
  const std::vector<OperatingPointStability> points = AnalyzeStability(ParseCase(Case(p, 1, 1e-8)));
  ASSERT_EQ(points.size(), 3u);
  const std::function<double(double)> excess = [&](double z) { return p.alpha1 * z + p.weight(z) - p.alpha2 * 1e5; };
  const double peak = std::sqrt(p.weight.zeta) / p.weight.k, trough = std::sqrt(p.weight.p / (p.weight.k * p.alpha1));
  const double speeds[] = {Bisect(excess, 0, peak), Bisect([&](double z) { return -excess(z); }, peak, trough),
                           Bisect(excess, trough, 10)};
  const ClosedForm torsional = TorsionalClosedForm(p);
  for (int k = 0; k < 3; ++k) {
    const analysis::Spectrum& sp = points[k].spectrum;
    const ClosedForm axial = AxialClosedForm(p, speeds[k]);
    EXPECT_NEAR(points[k].point.steady_state["bit_axial_speed_m_s"].get<double>(), speeds[k], 1e-12 * speeds[k]);
    // Every root found solves one of the two factors.
    double worst_residual = 0;
    for (const analysis::CharacteristicRoot& r : sp.roots)
      worst_residual = std::max(worst_residual, std::min(axial.RelativeResidual(r.s), torsional.RelativeResidual(r.s)));
    // The closed form's own roots (Re s >= -12, Im s <= 60) are found, and every root found there is one of them.
    std::vector<Complex> closed = axial.Roots(-12, 60), torsion = torsional.Roots(-12, 60);
    closed.insert(closed.end(), torsion.begin(), torsion.end());
    double worst_distance = 0;
    int compared = 0;
    for (const Complex c : closed) {
      if (c.imag() > 50) continue;
      double nearest = INFINITY;
      for (const analysis::CharacteristicRoot& r : sp.roots) nearest = std::min(nearest, std::abs(r.s - c));
      worst_distance = std::max(worst_distance, nearest / (1 + std::abs(c)));
      ++compared;
    }
    int unexplained = 0;
    for (const analysis::CharacteristicRoot& r : sp.roots)
      if (r.s.real() >= -12 && r.s.imag() <= 50)
        unexplained += std::none_of(closed.begin(), closed.end(),
                                    [&](Complex c) { return std::abs(r.s - c) < 1e-8 * (1 + std::abs(c)); });
    const double essential = std::max(std::log(std::abs(axial.reflection)) / (2 * kAxialTravel),
                                      std::log(std::abs(torsional.reflection)) / (2 * kTorsionalTravel));
    std::printf("[ measured ] steady state %d: v = %.9g m/s, F' = %.6g N s/m, %s, rightmost root %.9g%+.9gi; largest "
                "relative residual of the closed form at the %zu roots found %.2e; %d closed-form roots (Im s <= 50) "
                "matched to %.2e (relative), %d roots found that it lacks; essential abscissa %.12g (closed form "
                "%.12g)\n", k, speeds[k], axial.slope, analysis::VerdictName(sp.verdict), sp.roots[0].s.real(),
                sp.roots[0].s.imag(), sp.roots.size(), worst_residual, compared, worst_distance, unexplained,
                sp.essential_abscissa, essential);
    EXPECT_LT(worst_residual, 1e-10);
    EXPECT_GE(compared, 8);
    EXPECT_LT(worst_distance, 1e-8);
    EXPECT_EQ(unexplained, 0);
    EXPECT_NEAR(sp.essential_abscissa, essential, 1e-9 * std::abs(essential));
    EXPECT_EQ(sp.stable, k != 1);
  }
  EXPECT_LT(p.alpha1 + Slope(p.weight, speeds[1]), 0);  // the falling side: a real root s > 0
  EXPECT_GT(points[1].spectrum.roots[0].s.real(), 0);
  EXPECT_EQ(points[1].spectrum.roots[0].s.imag(), 0);
}

// Least-squares slope of log|y - reference| against t over the samples `use` picks.
double LogSlope(const std::vector<double>& t, const std::vector<double>& y, double reference,
                const std::function<bool(std::size_t)>& use) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!use(i)) continue;
    const double l = std::log(std::abs(y[i] - reference));
    sx += t[i], sy += l, sxx += t[i] * t[i], sxy += t[i] * l, ++n;
  }
  EXPECT_GE(n, 100);
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

TEST(InterconnectedWaves, StepResponseDecaysAtTheDominantRoot) {
  // A heavy bit (80 t) on a top that reflects 0.3 of the axial waves: the bit and string move nearly as one body
  // against the top's dashpot, a real root at -0.62 1/s; the next roots lie beyond -2.7 1/s (the axial chain at
  // ln 0.3 / (2 tau) = -3.0). The torsional top is matched (beta1 = 300 ~ Z_t): its roots lie far left. H steps by
  // 0.1 % at 15 s; the bit speed's distance from its new steady state, 4 to 16 s after the step, when the faster
  // modes have died (e^{-2.1 * 4}), decays at the rightmost root.
  const double za = kAxialImpedance;
  const json hook = {{"knots", {{0, 0}, {1, 30e3}, {15, 30e3}, {15, 30.03e3}}}};
  const Parameters p{0.7 / 1.3 * za, 1, 300, 300, 8e4, 80, {2000, 0.5, 1e-2}, {30, 0.5, 1e-2}, hook, 10.0};
  const auto c = ParseCase(Case(p, 31, 1e-11));
  const std::vector<OperatingPointStability> points = AnalyzeStability(c);
  ASSERT_EQ(points.size(), 1u);
  const analysis::CharacteristicRoot& dominant = points[0].spectrum.roots[0];
  ASSERT_EQ(dominant.s.imag(), 0);
  EXPECT_LT(points[0].spectrum.roots[1].s.real(), dominant.s.real() - 2);
  const double v = Bisect([&](double z) { return p.alpha1 * z + p.weight(z) - 30.03e3; }, 0, 1);
  const CaseRun run = RunCase(c);
  const std::vector<double>& t = run.result.time_s;
  const double measured = LogSlope(t, run.result.channel("bit_axial_speed_m_s").values, v,
                                   [&](std::size_t i) { return t[i] >= 19 && t[i] <= 31; });
  const double error = std::abs(measured / dominant.s.real() - 1);
  std::printf("[ measured ] step in H: rightmost root %.9g (next %.6g%+.6gi, essential %.6g); decay rate of the "
              "simulated bit speed's distance to v* = %.9g m/s over 19-31 s %.9g 1/s, relative error %.2e\n",
              dominant.s.real(), points[0].spectrum.roots[1].s.real(), points[0].spectrum.roots[1].s.imag(),
              points[0].spectrum.essential_abscissa, v, measured, error);
  EXPECT_LT(error, 1e-3);

  // The rotation follows the axial mode through F~'(v): in it W = a y with, from the torsional row at s = lambda,
  // a = -F~' (1 + r_t e) / (J lambda (1 + r_t e) + Z_t (1 - r_t e)), e = e^{-2 lambda tau_t}; against the simulation's
  // ratio of the two speeds' distances from steady drilling at 25 s, and against the linear system's null vector.
  const double lambda = dominant.s.real(), rt = TorsionalClosedForm(p).reflection;
  const double e = std::exp(-2 * lambda * kTorsionalTravel);
  const double ratio = -Slope(p.torque, v) * (1 + rt * e) /
                       (p.inertia * lambda * (1 + rt * e) + kTorsionalImpedance * (1 - rt * e));
  const Eigen::MatrixXcd delta = points[0].point.system.Characteristic(lambda);
  const double null_vector = -(delta(1, 0) / delta(1, 1)).real();
  const double omega = (p.beta2 * 10.0 - p.torque(v)) / p.beta1;
  const auto at = static_cast<std::size_t>(std::lround(25 / 0.01));
  const double simulated = (run.result.channel("bit_rpm").values[at] * kPi / 30 - omega) /
                           (run.result.channel("bit_axial_speed_m_s").values[at] - v);
  std::printf("[ measured ] rotation in the axial mode: d omega / d v = %.9g rad/m (closed form), %.9g (linear "
              "system), %.9g (simulation at 25 s), relative error %.2e\n", ratio, null_vector, simulated,
              std::abs(simulated / ratio - 1));
  EXPECT_NEAR(null_vector, ratio, 1e-10 * std::abs(ratio));
  EXPECT_NEAR(simulated, ratio, 1e-3 * std::abs(ratio));
}

TEST(InterconnectedWaves, SteadyStateOnTheFallingSideIsUnstableAndTheSimulationLeavesIt) {
  // The chapter's law with its steepest fall (F' = -p k / (8 zeta) = -2.5e5 N s/m at v_m = sqrt(3 zeta) / k) steeper
  // than the top's dashpot (alpha1 = 1.23e5, reflection 0.05): at H = alpha1 v_m + F(v_m) the steady state v_m lies
  // between two stable ones and has a real root s > 0. A triangular pulse of H at 5-6 s pushes the bit over it or not;
  // bisecting the pulse's height leaves the bit on v_m's stable manifold, close to it, until the root's growth
  // carries it away. Its distance from v_m, from 1e-6 to 1e-3 of v_m, grows at the root. (The closest approach, about
  // 1e-8 of v_m, is where the stable modes' decay (-6.6 1/s) meets the growth of what the bisection leaves, ~1e-12.)
  const Rational weight{2000, 0.5, 5e-4};
  const double alpha1 = 0.95 / 1.05 * kAxialImpedance, v_m = std::sqrt(3 * weight.zeta) / weight.k;
  const double h = alpha1 * v_m + weight(v_m);
  const auto pulsed = [&](double height) {
    const Parameters p{alpha1, 1, 300, 300, 4e4, 80, weight, {30, 0.5, 5e-4},
                       {{"knots", {{0, 0}, {1, h}, {5, h}, {5.5, h + height}, {6, h}}}}, 10.0};
    return ParseCase(Case(p, 25, 1e-12));
  };
  const std::vector<OperatingPointStability> points = AnalyzeStability(pulsed(0));
  ASSERT_EQ(points.size(), 3u);
  const analysis::Spectrum& middle = points[1].spectrum;
  EXPECT_NEAR(points[1].point.steady_state["bit_axial_speed_m_s"].get<double>(), v_m, 1e-12 * v_m);
  EXPECT_EQ(analysis::VerdictName(middle.verdict), std::string("unstable"));
  EXPECT_TRUE(points[0].spectrum.stable);
  EXPECT_TRUE(points[2].spectrum.stable);
  const double growth = middle.roots[0].s.real();
  ASSERT_GT(growth, 0);
  ASSERT_EQ(middle.roots[0].s.imag(), 0);

  const auto final_speed = [&](double height) {
    return RunCase(pulsed(height)).result.channel("bit_axial_speed_m_s").values.back();
  };
  double below = 0, above = 2e4;  // pulse heights that leave the bit on the lower and the upper state
  ASSERT_LT(final_speed(below), v_m);
  ASSERT_GT(final_speed(above), v_m);
  for (int i = 0; i < 60 && above - below > 1e-15 * above; ++i) {
    const double mid = 0.5 * (below + above);
    (final_speed(mid) < v_m ? below : above) = mid;
  }
  const CaseRun run = RunCase(pulsed(below));
  const std::vector<double>& t = run.result.time_s;
  const std::vector<double>& v = run.result.channel("bit_axial_speed_m_s").values;
  std::size_t closest = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] > 6 && std::abs(v[i] - v_m) < std::abs(v[closest] - v_m)) closest = i;
  const double measured = LogSlope(t, v, v_m, [&](std::size_t i) {
    const double d = std::abs(v[i] - v_m) / v_m;
    return i > closest && d > 1e-6 && d < 1e-3;
  });
  const double error = std::abs(measured / growth - 1);
  std::printf("[ measured ] falling side: v_m = %.9g m/s, F' = %.6g N s/m, rightmost root %.9g (%s), pulse %.12g N; "
              "closest approach %.2e of v_m at %.2f s, the final speed %.6g m/s; growth of the distance from v_m "
              "(1e-6 to 1e-3 of it) %.9g 1/s, relative error %.2e\n", v_m, Slope(weight, v_m), growth,
              analysis::VerdictName(middle.verdict), below, std::abs(v[closest] - v_m) / v_m, t[closest], v.back(),
              measured, error);
  EXPECT_LT(std::abs(v[closest] - v_m), 1e-7 * v_m);
  EXPECT_LT(error, 1e-3);
}

// --- Bad input --------------------------------------------------------------------------------------------------------
json ChapterCase() {
  const Parameters p{1e5, 1, 2000, 2000, 25600, 89, {700, 0.5, 1e-5}, {28, 0.5, 1e-5}, 1e5, 10.0};
  return Case(p, 1, 1e-8);
}

std::string RefusalMessage(const json& doc) {
  try {
    ParseCase(doc);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(InterconnectedWaves, BadInputIsRefusedWithItsJsonPath) {
  EXPECT_EQ(testing::RefusedPath(ChapterCase()), "");
  json doc = ChapterCase();
  doc["model"]["hoist"]["alpha1_Ns_per_m"] = -5.0;
  EXPECT_EQ(testing::RefusedPath(doc), "/model/hoist/alpha1_Ns_per_m");
  EXPECT_NE(RefusalMessage(doc).find("-5"), std::string::npos) << RefusalMessage(doc);  // the value found
  EXPECT_NE(RefusalMessage(doc).find("> 0"), std::string::npos) << RefusalMessage(doc);  // the range expected

  doc = ChapterCase();
  doc["model"]["string"].erase("youngs_modulus_Pa");
  EXPECT_EQ(testing::RefusedPath(doc), "/model/string/youngs_modulus_Pa");

  doc = ChapterCase();
  doc["model"]["string"]["inner_diameter_m"] = 0.2;
  EXPECT_EQ(testing::RefusedPath(doc), "/model/string/inner_diameter_m");

  doc = ChapterCase();
  doc["model"]["top"]["beta_2_Nms_per_rad"] = 1000.0;  // misspelt optional key: refused, not silently defaulted
  EXPECT_EQ(testing::RefusedPath(doc), "/model/top/beta_2_Nms_per_rad");
  EXPECT_NE(RefusalMessage(doc).find("unknown field"), std::string::npos) << RefusalMessage(doc);

  doc = ChapterCase();
  doc["model"]["top"]["speed_rad_s"] = {{"knots", {{0, 1}, {-1, 2}}}};  // knots going back in time
  EXPECT_EQ(testing::RefusedPath(doc).rfind("/model/top/speed_rad_s", 0), 0u) << testing::RefusedPath(doc);

  doc = ChapterCase();
  doc["model"]["bit"]["torque_law"] = {{"law", "coulomb"}, {"T_c_Nm", 100.0}};  // set-valued: no stuck regime here
  EXPECT_EQ(testing::RefusedPath(doc), "/model/bit/torque_law/law");

  doc = ChapterCase();
  doc["model"]["bit"]["weight_law"]["zeta"] = 0.0;
  EXPECT_EQ(testing::RefusedPath(doc), "/model/bit/weight_law/zeta");
}

}  // namespace
}  // namespace drillwave::cases
