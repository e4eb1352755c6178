// The chapter's interconnected axial and torsional waves (kind interconnected_waves, eqs. 2.12-2.13): steady drilling
// against the closed form alpha1 v = alpha2 H - F(v), beta1 omega = beta2 Omega - F~(v); the bit's two speeds against
// an independent method-of-lines discretization of the two wave equations (lumped masses and springs, RK4), converging
// at second order; and bad input refused with its JSON path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "refused_path.hpp"

namespace drillwave::cases {
namespace {

using nlohmann::json;

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
