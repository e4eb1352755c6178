// The string components of the axial_torsional kind against closed forms: a BHA section (impedance and travel-time
// step above the lumped bit) and Kelvin-Voigt damping (a dashpot across every sub-section).
#include <cmath>
#include <complex>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/io/json_reader.hpp"
#include "modal_decay.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

// BASELINE.md's string (the baseline-60rpm case) and steel.
constexpr double kG = 80769000000.0, kRho = 7850, kRhoMud = 1200, kGravity = 9.81;
constexpr double kPipeOd = 0.127, kPipeId = 0.1086104;
constexpr double kCollarOd = 0.17145, kCollarId = 0.0714375;  // 6.75 in x 2.8125 in

double Polar(double od, double id) { return kPi / 32 * (std::pow(od, 4) - std::pow(id, 4)); }
double Area(double od, double id) { return kPi / 4 * (od * od - id * id); }
double TorsionalImpedance(double od, double id) { return Polar(od, id) * std::sqrt(kG * kRho); }
double TorsionalTravelTime(double length) { return length / std::sqrt(kG / kRho); }

nlohmann::json Baseline() {
  return testing::LoadCase("baseline-60rpm");
}
// The baseline-bha string: 2600 m to the bit, the lowest 189.4 m collars, bit 3 kg m^2 and 800 kg.
nlohmann::json WithBha(double rpm) {
  nlohmann::json doc = Baseline();
  doc["model"]["string"]["length_m"] = 2600;
  doc["model"]["string"]["bha"] = {{"length_m", 189.4}, {"outer_diameter_m", kCollarOd}, {"inner_diameter_m", kCollarId}};
  doc["model"]["bit"]["inertia_kgm2"] = 3;
  doc["model"]["bit"]["mass_kg"] = 800;
  doc["model"]["top"]["speed_rad_s"] = rpm * kPi / 30;
  return doc;
}
void Bump(nlohmann::json& doc, double w, double t0, double factor) {  // set-point w, factor x w over [t0, t0 + 1] s
  doc["model"]["top"]["speed_rad_s"] = {{"knots", {{0, w}, {t0, w}, {t0 + 0.5, factor * w}, {t0 + 1, w}}}};
}
const std::vector<double>& Values(const CaseRun& run, const std::string& name) { return run.result.channel(name).values; }

// Lowest positive root of f above lo (scan, then bisection).
double LowestRoot(const std::function<double(double)>& f, double lo, double step) {
  double a = lo, fa = f(a);
  for (double b = lo + step;; a = b, b += step) {
    const double fb = f(b);
    if ((fa < 0) != (fb < 0)) {
      for (int i = 0; i < 100; ++i) {
        const double c = 0.5 * (a + b), fc = f(c);
        if ((fa < 0) != (fc < 0)) b = c;
        else a = c, fa = fc;
      }
      return 0.5 * (a + b);
    }
    fa = fb;
  }
}

// Where the spectrum of y on [from, to] (Hann window) peaks between lo and hi [rad/s], on a grid of step.
double SpectralPeak(const std::vector<double>& t, const std::vector<double>& y, double from, double to, double lo,
                    double hi, double step) {
  double best = lo, best_power = -1;
  for (double w = lo; w <= hi; w += step) {
    std::complex<double> sum = 0;
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t[i] >= from && t[i] <= to)
        sum += y[i] * (0.5 - 0.5 * std::cos(2 * kPi * (t[i] - from) / (to - from))) * std::polar(1.0, -w * t[i]);
    if (std::norm(sum) > best_power) best_power = std::norm(sum), best = w;
  }
  return best;
}

using testing::ModalDecay;
std::vector<double> BitSpeedChange(const CaseRun& run, double rpm) {  // [rad/s]
  std::vector<double> y = run.result.channel("bit_rpm").values;
  for (double& v : y) v = (v - rpm) * kPi / 30;
  return y;
}

// H = buoyant weight of pipe, collars and bit - W0 - c_a L V0 (V0 = d0 Omega / 2 pi, d0 = (W0 - a sigma l) /
// (a zeta eps)); the top drive holds T0 + c_t L Omega (bit torque T0 = a^2 eps d0 / 2 + a gamma mu a sigma l / 2).
// Held exactly without a disturbance, also with Kelvin-Voigt damping in both channels (no strain rate, no force).
TEST(AxialTorsionalString, BhaSteadyDrillingAndHookForceAreTheClosedForm) {
  const double w = 80 * kPi / 30, w0 = 90000, a = 0.10795, sigma_l = 450000, eps = 5e7, zeta = 0.6, mu = 0.6;
  const double d0 = (w0 - a * sigma_l) / (a * zeta * eps), v0 = d0 * w / (2 * kPi);
  const double buoyant = (kRho - kRhoMud) * kGravity * (Area(kPipeOd, kPipeId) * (2600 - 189.4) +
                                                       Area(kCollarOd, kCollarId) * 189.4) + 800 * kGravity * (1 - kRhoMud / kRho);
  const double hook = buoyant - w0 - 50 * 2600 * v0;
  const double top_torque = 0.5 * a * a * eps * d0 + 0.5 * a * mu * a * sigma_l + 0.06 * 2600 * w;
  for (double eta : {0.0, 0.02}) {
    nlohmann::json doc = WithBha(80);
    doc["model"]["string"]["kelvin_voigt_s"] = doc["model"]["string"]["axial_kelvin_voigt_s"] = eta;
    doc["simulation"]["duration_s"] = 2;
    doc["simulation"]["abs_tol"] = doc["simulation"]["rel_tol"] = 1e-9;
    doc["statistics"]["window_s"] = {0, 2};
    const auto run = RunCase(ParseCase(doc));
    const auto& s = run.summary;
    std::printf("[ measured ] eta %g s: hook force %.4f N (closed form %.4f), top torque %.6f N m (closed form %.6f), "
                "bit speed %.12f..%.12f rad/s\n", eta, s["hook_force_N"].get<double>(), hook,
                Values(run, "top_torque_Nm").back(), top_torque, s["bit_speed_min_rad_s"].get<double>(),
                s["bit_speed_max_rad_s"].get<double>());
    EXPECT_NEAR(s["hook_force_N"].get<double>(), hook, 1e-9 * hook);
    EXPECT_NEAR(Values(run, "hookload_N").back(), hook, 1e-6 * hook);
    EXPECT_NEAR(Values(run, "top_torque_Nm").back(), top_torque, 1e-6 * top_torque);
    EXPECT_NEAR(s["bit_speed_min_rad_s"].get<double>(), w, 1e-7);
    EXPECT_NEAR(s["bit_speed_max_rad_s"].get<double>(), w, 1e-7);
    EXPECT_NEAR(s["wob_mean_N"].get<double>(), w0, 1e-3);
    EXPECT_EQ(s["events"].get<int>(), 0);
  }
}

// A collared string on a rough rock at a loose tolerance (train rec22's fitted BHA, run as a fit's screening might):
// its kinks reach the bit along paths through pipe and collar pieces whose sums of travel times differ by 2.4e-11 s,
// and a breakpoint at each of such a pair cost a step that short and the ramp back. The run spent 1e8 evaluations
// before t = 20 s (a pair every 5 us from t = 15 s; this test's budget ran out at t = 15.2 s); the pair is now one
// breakpoint, and the 20 s cost 72 thousand evaluations.
TEST(AxialTorsionalString, KinksArrivingTogetherAreOneBreakpoint) {
  nlohmann::json doc = WithBha(125);
  doc["model"]["string"]["bha"] = {{"length_m", 291.8008120561469}, {"outer_diameter_m", 0.1715}, {"inner_diameter_m", 0.0714}};
  doc["model"]["bit"]["inertia_kgm2"] = 4.5;
  doc["model"]["bit"]["mass_kg"] = 1000;
  doc["model"]["hoist"]["weight_on_bit_N"] = 85000;
  doc["model"]["rock"]["strength_heterogeneity"] = {{"std", 0.01}, {"correlation_m", 0.002}, {"seed", 1}};
  doc["model"]["rock"]["bottom_roughness"] = {{"rms_m", 1e-5}, {"seed", 1}};
  doc["simulation"]["duration_s"] = 20;
  doc["simulation"]["abs_tol"] = doc["simulation"]["rel_tol"] = 1e-3;
  doc["statistics"]["window_s"] = {0, 20};
  Case c = ParseCase(doc);
  c.settings.integrator.max_evaluations = 5000000;  // a twentieth of what the pairs had cost by t = 15 s
  const auto run = RunCase(c);
  std::printf("[ measured ] 20 s at tolerance 1e-3: %lld evaluations, %d steps\n",
              run.summary["derivative_evaluations"].get<long long>(), run.summary["steps"].get<int>());
  EXPECT_GT(run.summary["bit_speed_min_rad_s"].get<double>(), 0);  // it drills smoothly throughout
}

// string/bha as an array of sections (heavy-weight pipe, then collars): the steady state holds the three sections'
// buoyant weight in closed form, and collars given as two sections of one size are the one section they make up.
TEST(AxialTorsionalString, SeveralBhaSectionsHoldTheirWeightAndJoinSeamlessly) {
  constexpr double kHwOd = 0.127, kHwId = 0.0762;  // 5 in heavy-weight pipe, 3 in bore
  const double w = 80 * kPi / 30, w0 = 90000, a = 0.10795, sigma_l = 450000, eps = 5e7, zeta = 0.6;
  const double d0 = (w0 - a * sigma_l) / (a * zeta * eps), v0 = d0 * w / (2 * kPi);
  const double buoyant = (kRho - kRhoMud) * kGravity * (Area(kPipeOd, kPipeId) * (2600 - 280 - 189.4) +
                                                       Area(kHwOd, kHwId) * 280 + Area(kCollarOd, kCollarId) * 189.4) +
                         800 * kGravity * (1 - kRhoMud / kRho);
  const double hook = buoyant - w0 - 50 * 2600 * v0;
  nlohmann::json three = WithBha(80);
  three["model"]["string"]["bha"] = nlohmann::json::array(
      {{{"length_m", 280}, {"outer_diameter_m", kHwOd}, {"inner_diameter_m", kHwId}},
       {{"length_m", 189.4}, {"outer_diameter_m", kCollarOd}, {"inner_diameter_m", kCollarId}}});
  three["simulation"]["duration_s"] = 2;
  three["simulation"]["abs_tol"] = three["simulation"]["rel_tol"] = 1e-9;
  three["statistics"]["window_s"] = {0, 2};
  const auto steady = RunCase(ParseCase(three)).summary;
  std::printf("[ measured ] pipe + heavy-weight + collars: hook force %.4f N (closed form %.4f), bit speed "
              "%.12f..%.12f rad/s\n", steady["hook_force_N"].get<double>(), hook,
              steady["bit_speed_min_rad_s"].get<double>(), steady["bit_speed_max_rad_s"].get<double>());
  EXPECT_NEAR(steady["hook_force_N"].get<double>(), hook, 1e-9 * hook);
  EXPECT_NEAR(steady["bit_speed_min_rad_s"].get<double>(), w, 1e-7);
  EXPECT_NEAR(steady["bit_speed_max_rad_s"].get<double>(), w, 1e-7);
  EXPECT_EQ(steady["events"].get<int>(), 0);

  nlohmann::json one = WithBha(60);
  one["model"]["string"]["bha"]["subsections"] = 4;
  one["simulation"]["duration_s"] = 20;
  one["statistics"]["window_s"] = {5, 20};
  nlohmann::json two = one;
  two["model"]["string"]["bha"] = nlohmann::json::array(
      {{{"length_m", 94.7}, {"outer_diameter_m", kCollarOd}, {"inner_diameter_m", kCollarId}, {"subsections", 2}},
       {{"length_m", 94.7}, {"outer_diameter_m", kCollarOd}, {"inner_diameter_m", kCollarId}, {"subsections", 2}}});
  const auto a1 = RunCase(ParseCase(one)).summary, a2 = RunCase(ParseCase(two)).summary;
  std::printf("[ measured ] collars as one section: %d stick onsets, bit speed max %.9f; as two: %d, %.9f\n",
              a1["stick_onsets"].get<int>(), a1["bit_speed_max_rad_s"].get<double>(), a2["stick_onsets"].get<int>(),
              a2["bit_speed_max_rad_s"].get<double>());
  EXPECT_NEAR(a1["hook_force_N"].get<double>(), a2["hook_force_N"].get<double>(), 1e-6);
  EXPECT_EQ(a1["stick_onsets"].get<int>(), a2["stick_onsets"].get<int>());
  EXPECT_NEAR(a1["bit_speed_max_rad_s"].get<double>(), a2["bit_speed_max_rad_s"].get<double>(), 1e-6);
  EXPECT_NEAR(a1["stick_fraction"].get<double>(), a2["stick_fraction"].get<double>(), 1e-6);
}

// A BHA of the pipe's own diameters whose one piece is as long as the pipe's pieces is no junction at all: the run is
// the uniform string's (to the rounding of the hook force's drag sum).
TEST(AxialTorsionalString, BhaOfPipeSizeIsTheUniformString) {
  nlohmann::json uniform = Baseline();
  uniform["simulation"]["duration_s"] = 20;
  uniform["statistics"]["window_s"] = {5, 20};
  nlohmann::json split = uniform;
  split["model"]["string"]["subsections"] = 19;
  split["model"]["string"]["bha"] = {{"length_m", 100}, {"outer_diameter_m", kPipeOd}, {"inner_diameter_m", kPipeId},
                                     {"subsections", 1}};
  const auto a = RunCase(ParseCase(uniform)).summary, b = RunCase(ParseCase(split)).summary;
  std::printf("[ measured ] uniform: %d stick onsets, bit speed max %.9f; pipe + pipe-size BHA: %d, %.9f\n",
              a["stick_onsets"].get<int>(), a["bit_speed_max_rad_s"].get<double>(), b["stick_onsets"].get<int>(),
              b["bit_speed_max_rad_s"].get<double>());
  EXPECT_NEAR(a["hook_force_N"].get<double>(), b["hook_force_N"].get<double>(), 1e-9);
  EXPECT_EQ(a["stick_onsets"].get<int>(), b["stick_onsets"].get<int>());
  EXPECT_NEAR(a["bit_speed_max_rad_s"].get<double>(), b["bit_speed_max_rad_s"].get<double>(), 1e-6);
  EXPECT_NEAR(a["stick_fraction"].get<double>(), b["stick_fraction"].get<double>(), 1e-6);
}

// The transmitted wave at the pipe/collar junction (d'Alembert, DESIGN.md §1). Undamped string, a nearly free bit
// (0.3 kg m^2): after a top speed step, until the wave reflected at the top returns, the bit turns at
//   dw_bit(t) = 2 T sum_k R^k dw_top(t - tau_p - tau_c - 2 k tau_c),  T = 2 Z_p / (Z_p + Z_c), R = (Z_c - Z_p) / (Z_p + Z_c)
// (transmitted into the collars, doubled at the free end, reflected back down at the junction from below).
TEST(AxialTorsionalString, BhaJunctionTransmitsTheDalembertFraction) {
  const double w = 150 * kPi / 30, t0 = 0.5;
  nlohmann::json doc = WithBha(150);
  doc["model"]["string"]["torsional_damping_Nms_per_rad_m"] = 0;
  doc["model"]["bit"]["inertia_kgm2"] = 0.3;
  // Weight on bit just above a sigma l: a shallow cut, whose torque hardly answers the speed change (at 90 kN the
  // shorter cut delay of the faster bit thins the cut and adds 4 % to the step).
  doc["model"]["hoist"]["weight_on_bit_N"] = 50000;
  doc["model"]["top"]["speed_rad_s"] = {{"knots", {{0, w}, {t0, w}, {t0 + 0.01, 1.1 * w}}}};
  const double tau_p = TorsionalTravelTime(2600 - 189.4), tau_c = TorsionalTravelTime(189.4);
  doc["simulation"]["duration_s"] = t0 + tau_p + tau_c + 0.4;
  doc["simulation"]["output_interval_s"] = 0.0005;
  doc["simulation"]["abs_tol"] = doc["simulation"]["rel_tol"] = 1e-8;
  doc["statistics"]["window_s"] = {0, doc["simulation"]["duration_s"].get<double>()};
  const auto run = RunCase(ParseCase(doc));
  const auto& t = run.result.time_s;
  const auto& top = Values(run, "top_rpm");
  const auto& bit = Values(run, "bit_rpm");
  const double zp = TorsionalImpedance(kPipeOd, kPipeId), zc = TorsionalImpedance(kCollarOd, kCollarId);
  const double transmitted = 2 * zp / (zp + zc), reflected = (zc - zp) / (zp + zc), rpm0 = 150;
  auto top_step = [&](double s) {  // dw_top(s) [rpm], linear between samples
    if (s <= t.front()) return 0.0;
    const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>((s - t.front()) / (t[1] - t[0])), t.size() - 2);
    return top[i] + (top[i + 1] - top[i]) * (s - t[i]) / (t[i + 1] - t[i]) - rpm0;
  };
  double worst = 0, step = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < t0 + tau_p + tau_c - 0.02) continue;
    double predicted = 0, weight = 2 * transmitted;
    for (int k = 0; k < 40; ++k, weight *= reflected) predicted += weight * top_step(t[i] - tau_p - tau_c - 2 * k * tau_c);
    worst = std::max(worst, std::abs(bit[i] - rpm0 - predicted));
    step = std::max(step, std::abs(predicted));
  }
  // At the first plateau (the first junction echo not yet back at the bit): 2 T of the top's step one travel time ago.
  const double plateau_time = t0 + tau_p + tau_c + 1.8 * tau_c;
  const std::size_t at = static_cast<std::size_t>(std::lround(plateau_time / (t[1] - t[0])));
  const double plateau = (bit[at] - rpm0) / top_step(t[at] - tau_p - tau_c);
  std::printf("[ measured ] Z_p %.1f, Z_c %.1f N m s: bit speed step at the first plateau %.4f of the top's (2T = %.4f); "
              "largest deviation from the d'Alembert series %.4f rpm of a %.3f rpm response\n", zp, zc, plateau,
              2 * transmitted, worst, step);
  EXPECT_NEAR(plateau, 2 * transmitted, 0.01);
  EXPECT_LT(worst, 0.03 * step);
}

// Pipe + collars + bit: the frequency equation with the top held (stiff PI) and the bit inertia J_b free,
//   1 - (Z_c / Z_p) tan(w tau_p) tan(w tau_c) = J_b w (tan(w tau_p) / Z_p + tan(w tau_c) / Z_c),
// against the peaks of the bit speed's spectrum after a small set-point bump: undamped string (c_t = 0, so that the
// peaks are the natural frequencies) and a shallow cut (W0 just above a sigma l: the bit-rock law hardly adds
// stiffness or damping). Spectral resolution of the 60 s record: 2 pi / 60 = 0.10 rad/s; the peaks are located to
// better than that.
TEST(AxialTorsionalString, BhaFreeTorsionalResponseMatchesTheFrequencyEquation) {
  const double rpm = 150, w = rpm * kPi / 30;
  nlohmann::json doc = WithBha(rpm);
  doc["model"]["string"]["torsional_damping_Nms_per_rad_m"] = 0;
  doc["model"]["hoist"]["weight_on_bit_N"] = 50000;
  Bump(doc, w, 1, 1.01);
  doc["simulation"]["duration_s"] = 65;
  doc["simulation"]["abs_tol"] = doc["simulation"]["rel_tol"] = 1e-8;
  doc["statistics"]["window_s"] = {0, 65};
  const auto run = RunCase(ParseCase(doc));
  const auto& t = run.result.time_s;
  const std::vector<double> y = BitSpeedChange(run, rpm);
  const double zp = TorsionalImpedance(kPipeOd, kPipeId), zc = TorsionalImpedance(kCollarOd, kCollarId), jb = 3;
  const double tp = TorsionalTravelTime(2600 - 189.4), tc = TorsionalTravelTime(189.4);
  auto equation = [&](double s) {  // times cos(s tau_p) cos(s tau_c)
    const double cp = std::cos(s * tp), sp = std::sin(s * tp), cc = std::cos(s * tc), sc = std::sin(s * tc);
    return cp * cc - zc / zp * sp * sc - jb * s * (sp * cc / zp + cp * sc / zc);
  };
  const double first = LowestRoot(equation, 0.01, 0.01), second = LowestRoot(equation, first + 0.01, 0.01);
  // Without the collars (the pipe to the bit, J_b = 3): what a model without the BHA would predict.
  const double bare = LowestRoot([&](double s) { return std::cos(s * (tp + tc)) - jb * s * std::sin(s * (tp + tc)) / zp; },
                                 0.01, 0.01);
  // The strongest peak below 3 rad/s, and the strongest between 3 and 7 rad/s.
  const double peak1 = SpectralPeak(t, y, 5, 65, 0.5, 3, 1e-3), peak2 = SpectralPeak(t, y, 5, 65, 3, 7, 1e-3);
  std::printf("[ measured ] spectral peaks %.4f and %.4f rad/s; frequency equation %.4f and %.4f (%+.2f %%, %+.2f %%); "
              "the pipe alone to the bit would ring at %.4f rad/s\n", peak1, peak2, first, second,
              100 * (peak1 / first - 1), 100 * (peak2 / second - 1), bare);
  EXPECT_NEAR(peak1, first, 0.01 * first);
  EXPECT_NEAR(peak2, second, 0.01 * second);
}

// Kelvin-Voigt damping (chapter eq. 2.20) on a uniform string with the top held and a light bit: the damping is
// stiffness-proportional, sigma_n = eta w_n^2 / 2 on top of the viscous c_t / (2 rho J), with w_n the roots of
// tan(w tau) = Z / (J_b w). The first mode's decay by complex demodulation of the bit speed after a small bump; the
// Kelvin-Voigt part as the difference of the decay with and without eta, for 10, 20 and 40 sub-sections. The weight
// on bit is just above a sigma l: at 50 kN the regenerative cut (its delay t_n) already takes 0.04 1/s off the
// viscous decay and 12 % off the Kelvin-Voigt part, not additively.
TEST(AxialTorsionalString, KelvinVoigtDecayMatchesTheClosedFormAndConverges) {
  const double rpm = 150, w = rpm * kPi / 30, eta = 0.024, length = 1500, jb = 1;
  nlohmann::json doc = Baseline();
  doc["model"]["string"]["length_m"] = length;
  doc["model"]["bit"]["inertia_kgm2"] = jb;
  doc["model"]["hoist"]["weight_on_bit_N"] = 48700;
  Bump(doc, w, 1, 1.01);
  doc["simulation"]["duration_s"] = 16;
  doc["simulation"]["abs_tol"] = doc["simulation"]["rel_tol"] = 1e-9;
  doc["statistics"]["window_s"] = {0, 16};
  const double z = TorsionalImpedance(kPipeOd, kPipeId), tau = TorsionalTravelTime(length);
  const double w1 = LowestRoot([&](double s) { return z * std::cos(s * tau) - jb * s * std::sin(s * tau); }, 0.01, 0.01);
  const double viscous = 0.06 / (2 * kRho * Polar(kPipeOd, kPipeId)), kv = 0.5 * eta * w1 * w1;
  std::vector<double> errors;
  for (int m : {10, 20, 40}) {
    double sigma[2], cost[2];  // without, with eta
    for (int with : {0, 1}) {
      doc["model"]["string"]["subsections"] = m;
      doc["model"]["string"]["kelvin_voigt_s"] = with ? eta : 0.0;
      const auto run = RunCase(ParseCase(doc));
      sigma[with] = ModalDecay(run.result.time_s, BitSpeedChange(run, rpm), w1, 2 * kPi / w1, 3, 14);
      cost[with] = 1000 * run.summary["wall_time_s"].get<double>() / 16;
    }
    errors.push_back((sigma[1] - sigma[0]) / kv - 1);
    std::printf("[ measured ] m = %d, mode 1 (%.4f rad/s): decay %.5f 1/s without eta (viscous %.5f), %.5f with; "
                "Kelvin-Voigt part %.5f vs eta w1^2 / 2 = %.5f (%+.2f %%); %.1f ms per simulated second without eta, "
                "%.1f with\n", m, w1, sigma[0], viscous, sigma[1], sigma[1] - sigma[0], kv, 100 * errors.back(),
                cost[0], cost[1]);
    EXPECT_NEAR(sigma[0], viscous, 0.03 * viscous) << m;
  }
  EXPECT_LT(std::abs(errors[2]), 0.02);
  EXPECT_LE(std::abs(errors[2]), std::abs(errors[0]));
}

// Kelvin-Voigt damping with side friction: the internal nodes are tied by dashpots and held by friction (HeldNodes).
// Steady drilling holds exactly (no strain rate, every internal node sliding at the top's speed against its
// friction); and as eta goes to 0 the stick-slip run tends to the one with side friction alone, linearly in eta.
TEST(AxialTorsionalString, KelvinVoigtWithSideFrictionHoldsSteadyDrillingAndTendsToSideFrictionAlone) {
  nlohmann::json doc = Baseline();  // 2000 m in 20 pieces
  doc["model"]["string"]["side_friction"]["torque_per_m_Nm"] = 2;
  doc["model"]["string"]["kelvin_voigt_s"] = 0.02;
  doc["model"]["top"]["speed_rad_s"] = 2 * kPi;  // no disturbance (the point is unstable: 5 s before noise grows)
  doc["simulation"]["duration_s"] = 5;
  doc["statistics"]["window_s"] = {0, 5};
  const auto steady = RunCase(ParseCase(doc));
  // The internal nodes carry the friction of all but the two half pieces at the ends: L - L / 20.
  const double expected =
      steady.summary["steady_bit_torque_Nm"].get<double>() + 0.06 * 2000 * 2 * kPi + 2 * (2000 - 100);
  double drift = 0;
  for (double v : Values(steady, "top_torque_Nm")) drift = std::max(drift, std::abs(v - expected));
  EXPECT_LT(drift, 1e-8 * expected) << "top torque off T0 + c_t L Omega + side friction (L - L / 20) = " << expected;

  doc = Baseline();  // its 1-s bump of the set-point: stick-slip develops
  doc["model"]["string"]["side_friction"]["torque_per_m_Nm"] = 2;
  doc["simulation"]["duration_s"] = 14;
  doc["simulation"]["abs_tol"] = doc["simulation"]["rel_tol"] = 1e-8;
  doc["statistics"]["window_s"] = {0, 14};
  std::vector<std::vector<double>> bit;
  for (double eta : {0.0, 1e-7, 1e-6, 1e-5}) {
    doc["model"]["string"]["kelvin_voigt_s"] = eta;
    bit.push_back(Values(RunCase(ParseCase(doc)), "bit_rpm"));
  }
  double largest = 0;
  for (double v : bit[0]) largest = std::max(largest, std::abs(v));
  std::vector<double> difference;
  for (int k : {1, 2, 3}) {
    ASSERT_EQ(bit[k].size(), bit[0].size());
    double worst = 0;
    for (std::size_t i = 0; i < bit[0].size(); ++i) worst = std::max(worst, std::abs(bit[k][i] - bit[0][i]));
    difference.push_back(worst);
  }
  std::printf("[ measured ] steady drilling with eta 0.02 s and side friction: top torque within %.1e N m of the "
              "closed form %.2f; 14 s of stick-slip (bit up to %.1f rpm) against side friction alone: bit speed "
              "%.2e, %.2e, %.2e rpm off with eta 1e-7, 1e-6, 1e-5 s\n", drift, expected, largest, difference[0],
              difference[1], difference[2]);
  EXPECT_GT(largest, 100.0);  // it did slip
  EXPECT_LT(difference[0], 1e-3 * largest);
  EXPECT_LT(difference[0], 0.2 * difference[1]);  // first order in eta
  EXPECT_LT(difference[1], 0.2 * difference[2]);
}

TEST(AxialTorsionalString, BadBhaAndKelvinVoigtInputNameTheirPath) {
  auto error_of = [](const nlohmann::json& doc) {
    try {
      ParseCase(doc);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  nlohmann::json doc = WithBha(80);
  doc["model"]["string"]["bha"]["length_m"] = 2600;
  EXPECT_NE(error_of(doc).find("/model/string/bha/length_m"), std::string::npos) << error_of(doc);
  doc = WithBha(80);
  doc["model"]["string"]["bha"]["lenght_m"] = 1;
  EXPECT_NE(error_of(doc).find("/model/string/bha/lenght_m"), std::string::npos) << error_of(doc);
  doc = WithBha(80);  // several sections: too long together, a misspelt field, none
  doc["model"]["string"]["bha"] = nlohmann::json::array({{{"length_m", 2000}, {"outer_diameter_m", kCollarOd},
                                                          {"inner_diameter_m", kCollarId}},
                                                         {{"length_m", 700}, {"outer_diameter_m", kCollarOd},
                                                          {"inner_diameter_m", kCollarId}}});
  EXPECT_NE(error_of(doc).find("/model/string/bha: expected sections shorter together (2700 m)"), std::string::npos)
      << error_of(doc);
  doc["model"]["string"]["bha"][0]["length_m"] = 200;
  doc["model"]["string"]["bha"][1]["lenght_m"] = 1;
  EXPECT_NE(error_of(doc).find("/model/string/bha/1/lenght_m"), std::string::npos) << error_of(doc);
  doc["model"]["string"]["bha"] = nlohmann::json::array();
  EXPECT_NE(error_of(doc).find("/model/string/bha: expected at least one section"), std::string::npos)
      << error_of(doc);
  doc = WithBha(80);
  doc["model"]["string"]["kelvin_voigt_s"] = -0.1;
  EXPECT_NE(error_of(doc).find("/model/string/kelvin_voigt_s"), std::string::npos) << error_of(doc);
  doc["model"]["string"]["kelvin_voigt_s"] = 0.02;
  doc["model"]["string"]["side_friction"]["torque_per_m_Nm"] = 5;  // combined (HeldNodes)
  EXPECT_EQ(error_of(doc), "");
  doc = WithBha(80);  // retardation times beyond 10 s: the range is stated
  doc["model"]["string"]["axial_kelvin_voigt_s"] = 1e300;
  EXPECT_NE(error_of(doc).find("/model/string/axial_kelvin_voigt_s: expected a number in [0, 10]"), std::string::npos)
      << error_of(doc);
  doc["model"]["string"]["axial_kelvin_voigt_s"] = 10;
  EXPECT_EQ(error_of(doc), "");
}

}  // namespace
}  // namespace drillwave::cases
