// The two-disc set-up (kind two_disc, setup seed eqs. 1-7): the event-based stick-slip against a smoothed-friction
// reference (sign w -> tanh(w / eps)) whose smoothing is refined, two independent stick states, the Hopf point
// where the equilibrium loses stability against the seed's Routh-Hurwitz condition (eq. 12), and the coexistence of
// stick-slip and steady rotation above the Hopf point D.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/bitrock/friction.hpp"
#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "two_disc_reference.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

using testing::LoadCase;

RunResult RunDoc(const nlohmann::json& doc) { return RunCase(ParseCase(doc)).result; }

// Crossings of the lower disc's speed through a threshold, from the sampled trajectory: stick onsets (falling below
// it) and slip onsets (rising above it), linearly interpolated between samples. With threshold 0 (the event-based
// model, whose speed is exactly 0 while stuck) a stick onset is extrapolated from the two samples before it.
struct Crossings {
  std::vector<double> stick, slip;
};
Crossings FindCrossings(const std::vector<double>& t, const std::vector<double>& w, double threshold) {
  Crossings c;
  for (std::size_t i = 2; i < t.size(); ++i) {
    const double a = std::abs(w[i - 1]), b = std::abs(w[i]);
    if (threshold == 0) {
      if (a > 0 && b == 0) {
        const double slope = (std::abs(w[i - 2]) - a) / (t[i - 1] - t[i - 2]);
        c.stick.push_back(slope > 0 ? std::min(t[i], t[i - 1] + a / slope) : t[i]);
      } else if (a == 0 && b > 0 && i + 1 < t.size()) {
        // Leaving rest with zero acceleration the speed grows like (t - t_b)^2: sqrt(w) is linear in t.
        const double r0 = std::sqrt(b), r1 = std::sqrt(std::abs(w[i + 1]));
        c.slip.push_back(r1 > r0 ? std::max(t[i - 1], t[i] - r0 * (t[i + 1] - t[i]) / (r1 - r0)) : t[i - 1]);
      }
    } else if (a >= threshold && b < threshold) {
      c.stick.push_back(t[i - 1] + (a - threshold) / (a - b) * (t[i] - t[i - 1]));
    } else if (a < threshold && b >= threshold) {
      c.slip.push_back(t[i - 1] + (threshold - a) / (b - a) * (t[i] - t[i - 1]));
    }
  }
  return c;
}

// Mean distance from each reference time in [t0, t1] to the nearest time of the other list.
double MeanDistance(const std::vector<double>& reference, const std::vector<double>& other, double t0, double t1) {
  double sum = 0;
  int n = 0;
  for (double r : reference) {
    if (r < t0 || r > t1) continue;
    double best = 1e300;
    for (double o : other) best = std::min(best, std::abs(o - r));
    sum += best;
    ++n;
  }
  return n > 0 ? sum / n : 1e300;
}

double StuckFraction(const std::vector<double>& t, const std::vector<double>& w, double threshold, double t0,
                     double t1) {
  double stuck = 0;
  for (std::size_t i = 1; i < t.size(); ++i)
    if (t[i - 1] >= t0 && t[i] <= t1 && std::abs(w[i - 1]) <= threshold && std::abs(w[i]) <= threshold)
      stuck += t[i] - t[i - 1];
  return stuck / (t1 - t0);
}

double MaxIn(const std::vector<double>& t, const std::vector<double>& w, double t0, double t1) {
  double m = -1e300;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= t0 && t[i] <= t1) m = std::max(m, w[i]);
  return m;
}

TEST(TwoDisc, SmoothedFrictionConvergesToTheEventBasedStickSlip) {
  constexpr double kT0 = 30, kT1 = 60;
  nlohmann::json doc = LoadCase("two-disc-setup");
  doc["simulation"]["duration_s"] = kT1;
  doc["simulation"]["output_interval_s"] = 1e-3;
  doc["statistics"]["window_s"] = {kT0, kT1};

  const RunResult events = RunDoc(doc);
  const auto& t = events.time_s;
  const auto& w = events.channel("lower_rad_s").values;
  const Crossings exact = FindCrossings(t, w, 0.0);
  const double fraction = events.summary.at("stick_fraction").get<double>();
  const double period = events.summary.at("stick_slip_period_s").get<double>();
  const double w_max = events.summary.at("bit_speed_max_rad_s").get<double>();
  ASSERT_GE(events.summary.at("stick_onsets").get<int>(), 6);

  std::printf("[ measured ] two-disc set-up at 2 V, event-based: stick fraction %.5f, period %.5f s, max %.6f rad/s\n",
              fraction, period, w_max);
  std::printf("[ measured ]     eps [rad/s] | stick onsets |dt| | slip onsets |dt| | stick fraction err | period err "
              "| max speed err | steps\n");
  struct Row {
    double eps, stick, slip, fraction, period, w_max;
  };
  std::vector<Row> rows;
  for (double eps : {3e-2, 1e-2, 3e-3, 1e-3}) {
    nlohmann::json smooth = doc;
    smooth["model"]["friction_smoothing_rad_s"] = eps;
    const RunResult r = RunDoc(smooth);
    ASSERT_EQ(r.summary.at("events").get<int>(), 0) << "a smoothed law has no stick events";
    const auto& ts = r.time_s;
    const auto& ws = r.channel("lower_rad_s").values;
    // Stuck while |w| < 10 eps: the creep speed eps atanh(T / T_s) stays below that until T is within 4e-9 of T_s.
    const double threshold = 10 * eps;
    const Crossings c = FindCrossings(ts, ws, threshold);
    std::vector<double> onsets;
    for (double s : c.stick)
      if (s >= kT0 && s < kT1) onsets.push_back(s);
    const double smooth_period =
        onsets.size() >= 2 ? (onsets.back() - onsets.front()) / (onsets.size() - 1) : 1e300;
    Row row{eps,
            MeanDistance(exact.stick, c.stick, kT0, kT1),
            MeanDistance(exact.slip, c.slip, kT0, kT1),
            std::abs(StuckFraction(ts, ws, threshold, kT0, kT1) - fraction),
            std::abs(smooth_period - period),
            std::abs(MaxIn(ts, ws, kT0, kT1) - w_max)};
    rows.push_back(row);
    std::printf("[ measured ]     %10.0e | %16.3e | %15.3e | %18.3e | %10.3e | %13.3e | %ld\n", eps, row.stick, row.slip,
                row.fraction, row.period, row.w_max, r.summary.at("steps").get<long>());
  }
  // Every statistic gets closer as the smoothing is refined ...
  for (std::size_t k = 1; k < rows.size(); ++k) {
    EXPECT_LT(rows[k].stick, rows[k - 1].stick) << "eps " << rows[k].eps;
    EXPECT_LT(rows[k].slip, rows[k - 1].slip) << "eps " << rows[k].eps;
    EXPECT_LT(rows[k].fraction, rows[k - 1].fraction) << "eps " << rows[k].eps;
    EXPECT_LT(rows[k].w_max, rows[k - 1].w_max) << "eps " << rows[k].eps;
  }
  // ... and at eps = 1e-3 rad/s it is close to the event-based answer. The slip onsets converge like sqrt(eps): the
  // disc leaves rest with zero acceleration (the slip torque at 0+ equals the static level), so it needs a time
  // ~ sqrt(eps) to reach the threshold.
  const Row &coarsest = rows.front(), &finest = rows.back();
  EXPECT_LT(finest.stick, 1e-3);
  EXPECT_LT(finest.slip, 6e-2);
  EXPECT_LT(finest.fraction, 1.5e-2);
  EXPECT_LT(finest.period, 5e-4);
  EXPECT_LT(finest.w_max / w_max, 2e-4);
  // Observed orders over the factor 30 in eps: about 1 for the stick onsets, period and peak speed, about 0.6 for
  // the slip onsets and the stick fraction.
  EXPECT_GT(coarsest.stick / finest.stick, 8);
  EXPECT_GT(coarsest.w_max / finest.w_max, 15);
  EXPECT_GT(coarsest.slip / finest.slip, 4);
  EXPECT_GT(coarsest.fraction / finest.fraction, 4);
}

TEST(TwoDisc, EachDiscSticksOnItsOwn) {
  // Stick-slip at 2 V, motor off at 30 s: the upper disc sticks while the lower disc still turns; the lower disc
  // swings back and creeps towards rest with the string torque approaching its static level -T_sl from the slip
  // side. Near rest it is an overdamped oscillator (d_l(0)^2 = 0.0227 > 4 k J_l = 0.0095), so its speed decays
  // without reaching zero: no stick event, correctly.
  const RunResult r = RunDoc(LoadCase("two-disc-stop"));
  const auto& t = r.time_s;
  const auto& top_stuck = r.channel("top_stuck").values;
  const auto& bit_stuck = r.channel("bit_stuck").values;
  const auto& lower = r.channel("lower_rad_s").values;
  std::size_t upper_sticks = 0;
  while (upper_sticks < t.size() && !(t[upper_sticks] > 30.0 && top_stuck[upper_sticks] > 0.5)) ++upper_sticks;
  ASSERT_LT(upper_sticks, t.size()) << "the upper disc must stick after the motor is switched off";
  std::printf("[ measured ] motor off at 30 s: upper disc sticks at %.2f s, lower disc speed there %.3f rad/s\n",
              t[upper_sticks], lower[upper_sticks]);
  EXPECT_EQ(bit_stuck[upper_sticks], 0.0);
  EXPECT_GT(lower[upper_sticks], 0.1);
  // From then on the upper disc stays stuck and holds the string: its friction balances the string torque inside
  // its static range [-(T_su - dT_su), T_su + dT_su].
  for (std::size_t i = upper_sticks; i < t.size(); ++i) ASSERT_EQ(top_stuck[i], 1.0) << "t = " << t[i];
  const double string_torque = r.channel("top_torque_Nm").values.back();
  EXPECT_NEAR(r.channel("upper_friction_Nm").values.back(), -string_torque, 1e-12);
  EXPECT_LT(std::abs(string_torque), 0.3212 - 0.0095);
  // The lower disc ends creeping backwards ever slower, its friction at the static level -T_sl.
  EXPECT_LT(lower.back(), 0.0);
  EXPECT_GT(lower.back(), -1e-6);
  EXPECT_NEAR(r.channel("bit_torque_Nm").values.back(), -0.1642, 1e-6);
  EXPECT_NEAR(string_torque, -0.1642, 1e-6);
  EXPECT_LT(r.summary.at("energy_balance_residual_max_J").get<double>(), 1e-8);
}

// The equilibrium w of k_m u = T_u(w) + T_l(w) loses stability where the lower friction's slope d_l crosses the
// Routh-Hurwitz bound of the seed's eq. 12, for the linearization J_u J_l l^3 + (J_u d_l + J_l d_u) l^2 +
// (k (J_u + J_l) + d_u d_l) l + k (d_u + d_l) (DESIGN.md §4). Computed here from the case file's parameters and its
// friction laws; the simulation must rotate steadily just below that voltage and oscillate just above it.
TEST(TwoDisc, OscillationStartsWhereRouthHurwitzFails) {
  nlohmann::json doc = LoadCase("two-disc-steady");
  const testing::TwoDiscRouthHurwitz rh(doc["model"]);
  // First loss of stability along the branch, by bisection on w.
  ASSERT_TRUE(rh.Stable(0.01));
  ASSERT_FALSE(rh.Stable(2.0));
  const double lo = rh.Boundary(0.01, 2.0);
  const double u_hopf = rh.Voltage(lo);
  const double d_hopf = rh.lower().SlipTorqueDerivative(lo);
  std::printf("[ measured ] Routh-Hurwitz: equilibrium unstable from w = %.5f rad/s, u_c = %.5f V (d_l = %.6f; the "
              "seed's eq. 12 bound, with its own lower-disc values: -0.00114)\n", lo, u_hopf, d_hopf);
  EXPECT_NEAR(d_hopf, -0.00114, 1.5e-4);  // published values of a later identification: close, not equal

  doc["simulation"]["duration_s"] = 400;
  doc["statistics"]["window_s"] = {300, 400};
  auto range_at = [&](double u) {
    doc["model"]["upper_disc"]["input_voltage_V"] = u;
    return RunDoc(doc).summary.at("bit_speed_range_rad_s").get<double>();
  };
  const double below = range_at(0.95 * u_hopf), above = range_at(1.05 * u_hopf);
  std::printf("[ measured ] lower-disc speed range: %.3e rad/s at 0.95 u_A, %.3e rad/s at 1.05 u_A\n", below, above);
  EXPECT_LT(below, 1e-6);
  EXPECT_GT(above, 0.05);
}

// Between the subcritical Hopf point D (where e3 becomes e4) and the end of the periodic branch, stable rotation and
// the stick-slip cycle coexist (the seed's Fig. 4): the same voltage gives stick-slip from rest and steady rotation
// when it is approached from above (two-disc-hysteresis.json).
TEST(TwoDisc, StickSlipAndSteadyRotationCoexistAboveTheHopfPointD) {
  nlohmann::json from_above = LoadCase("two-disc-hysteresis");
  nlohmann::json from_rest = from_above;
  from_rest["model"]["upper_disc"]["input_voltage_V"] = 4.6;
  const RunResult down = RunDoc(from_above), up = RunDoc(from_rest);
  std::printf("[ measured ] u_c = 4.6 V: from rest %d stick onsets in [300, 400] s (lower disc %.3f to %.3f rad/s); "
              "from 8 V %d stick onsets, speed %.6f to %.6f rad/s\n", up.summary.at("stick_onsets").get<int>(),
              up.summary.at("bit_speed_min_rad_s").get<double>(), up.summary.at("bit_speed_max_rad_s").get<double>(),
              down.summary.at("stick_onsets").get<int>(), down.summary.at("bit_speed_min_rad_s").get<double>(),
              down.summary.at("bit_speed_max_rad_s").get<double>());
  EXPECT_GE(up.summary.at("stick_onsets").get<int>(), 10);
  EXPECT_EQ(up.summary.at("bit_speed_min_rad_s").get<double>(), 0.0);
  EXPECT_EQ(down.summary.at("stick_onsets").get<int>(), 0);
  EXPECT_LT(down.summary.at("bit_speed_range_rad_s").get<double>(), 0.02);
}

TEST(TwoDisc, BadInputNamesTheJsonPath) {
  nlohmann::json doc = LoadCase("two-disc-setup");
  doc["model"]["lower_disc"]["inertia_kgm2"] = -1;
  try {
    ParseCase(doc);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/model/lower_disc/inertia_kgm2") << e.what();
  }
  doc = LoadCase("two-disc-setup");
  doc["model"]["upper_disc"]["voltage"] = 1;
  EXPECT_THROW(ParseCase(doc), InputError);
}

}  // namespace
}  // namespace drillwave::cases
