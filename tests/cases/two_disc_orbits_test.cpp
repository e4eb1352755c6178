// Periodic orbits of the two-disc set-up (setup seed, Fig. 4): the stick-slip cycle by shooting with saltation
// matrices against the simulation and against finite differences of the event-resolved flow, and the bifurcation
// diagram by continuation: Hopf points against Routh-Hurwitz, the fold of the periodic branch against brute-force runs
// from rest, the stable branch's amplitude against a long run.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/analysis/periodic_orbits.hpp"
#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/orbits.hpp"
#include "drillwave/io/json_reader.hpp"
#include "two_disc_reference.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

using testing::LoadCase;

const char kVoltage[] = "/model/upper_disc/input_voltage_V";

// A long run at voltage u from rest: its summary and the state (twist, upper speed, lower speed) where the lower disc
// is fastest in the last statistics window.
struct Simulated {
  nlohmann::json summary;
  Eigen::VectorXd peak;
};
Simulated Simulate(nlohmann::json doc, double u, double duration) {
  io::SetByPointer(doc, kVoltage, u);
  doc["simulation"]["duration_s"] = duration;
  doc["statistics"]["window_s"] = {duration - 100, duration};
  const Case c = ParseCase(doc);
  const CaseRun run = RunCase(c);
  const double k = doc["model"]["string"]["stiffness_Nm_per_rad"];
  const auto& t = run.result.time_s;
  const auto &torque = run.result.channel("top_torque_Nm").values, &upper = run.result.channel("upper_rad_s").values,
             &lower = run.result.channel("lower_rad_s").values;
  std::size_t best = t.size() - 1;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= duration - 100 && lower[i] > lower[best]) best = i;
  Eigen::VectorXd x(3);
  x << torque[best] / k, upper[best], lower[best];
  return {run.summary, x};
}

TEST(TwoDiscOrbits, StickSlipCycleMatchesTheSimulationAndFiniteDifferences) {
  const nlohmann::json doc = LoadCase("two-disc-setup");  // u_c = 2 V: stick-slip (branch p1)
  const Simulated sim = Simulate(doc, 2.0, 200);
  const double period_sim = sim.summary.at("stick_slip_period_s");
  const auto field = ParseCase(doc).model->OrbitField();
  const analysis::PeriodicOrbit orbit = analysis::FindPeriodicOrbit(*field, sim.peak, period_sim);
  double top = 0;
  for (const auto& x : orbit.states) top = std::max(top, x[2]);
  std::printf("[ measured ] u_c = 2 V: period %.9f s (simulation %.9f), lower-disc peak %.9f rad/s (simulation %.9f), "
              "%d switches, multipliers |%.3e| |%.3e| |%.3e|\n", orbit.period, period_sim, top,
              sim.summary.at("bit_speed_max_rad_s").get<double>(), orbit.switches, std::abs(orbit.multipliers[0]),
              std::abs(orbit.multipliers[1]), std::abs(orbit.multipliers[2]));
  EXPECT_NEAR(orbit.period, period_sim, 1e-4 * period_sim);
  EXPECT_NEAR(top, sim.summary.at("bit_speed_max_rad_s").get<double>(), 1e-4);
  EXPECT_EQ(orbit.switches, 2);  // the lower disc sticks once and slips once per period
  EXPECT_TRUE(orbit.stable);
  EXPECT_NEAR(std::abs(orbit.multipliers[0]), 1.0, 1e-7);  // trivial
  EXPECT_LT(std::abs(orbit.multipliers[2]), 1e-9);         // sticking forgets the lower disc's speed
  const Eigen::MatrixXd fd = analysis::FiniteDifferenceMonodromy(*field, orbit.x0, orbit.period, 1e-6);
  const double error = (fd - orbit.monodromy).lpNorm<Eigen::Infinity>();
  std::printf("[ measured ] monodromy: saltation vs central differences, max difference %.3e (max entry %.3e)\n",
              error, orbit.monodromy.lpNorm<Eigen::Infinity>());
  EXPECT_LT(error, 1e-5 * orbit.monodromy.lpNorm<Eigen::Infinity>());
}

TEST(TwoDiscOrbits, BifurcationDiagramOfTheSeedsFigure4) {
  const nlohmann::json doc = LoadCase("two-disc-setup");
  const OrbitsSpec spec = ParseContinueOption(std::string(kVoltage) + "=0.3:6:115", doc);
  const OrbitsResult result = ContinueOrbits(doc, spec, nullptr);

  // Hopf points against the seed's Routh-Hurwitz condition (eq. 12), bisected on the steady speed.
  const testing::TwoDiscRouthHurwitz rh(doc["model"]);
  const double u_a = rh.Voltage(rh.Boundary(0.01, 2.0)), u_d = rh.Voltage(rh.Boundary(2.0, 20.0));
  ASSERT_EQ(result.equilibria.hopf.size(), 2u);
  std::printf("[ measured ] Hopf points by continuation %.9f V and %.9f V; Routh-Hurwitz %.9f V and %.9f V\n",
              result.equilibria.hopf[0].p, result.equilibria.hopf[1].p, u_a, u_d);
  EXPECT_NEAR(result.equilibria.hopf[0].p, u_a, 1e-6);
  EXPECT_NEAR(result.equilibria.hopf[1].p, u_d, 1e-6);

  // One branch joins D and A: unstable from D up to the fold, then stable (sticking in between) down to A.
  ASSERT_EQ(result.branches.size(), 1u);
  const auto& branch = result.branches[0];
  std::printf("[ measured ] branch from %.6f V: %zu orbits, %s\n", result.starts[0].p, branch.points.size(),
              branch.end.c_str());
  ASSERT_EQ(branch.folds.size(), 1u);
  const double fold = branch.folds[0].p;
  std::printf("[ measured ] fold C at %.6f V (period %.4f s, critical multiplier %.6f)\n", fold,
              branch.folds[0].period, branch.folds[0].critical_multiplier);
  EXPECT_NEAR(branch.folds[0].critical_multiplier, 1.0, 1e-2);
  EXPECT_NE(branch.end.find("Hopf"), std::string::npos);
  EXPECT_NEAR(branch.points.back().p, u_d, 1e-3);  // started at A, ends at D
  bool sticks = false;
  for (const auto& pt : branch.points) sticks |= pt.orbit.switches > 0;
  EXPECT_TRUE(sticks);

  // Bistability: the steady state and the cycle coexist between D and C, on the grid's resolution (0.05 V).
  const auto coexist = CoexistenceRanges(result);
  ASSERT_EQ(coexist.size(), 1u);
  std::printf("[ measured ] coexistence on the grid: [%.4f, %.4f] V\n", coexist[0].first, coexist[0].second);
  EXPECT_GT(coexist[0].first, u_d);
  EXPECT_LT(coexist[0].first, u_d + 0.051);
  EXPECT_LT(coexist[0].second, fold);
  EXPECT_GT(coexist[0].second, fold - 0.051);

  // Brute force: from rest the set-up ends on the cycle just below the fold and at steady rotation just above it
  // (near the fold the transient creeps past the cycle's ghost: 2 mV above it, 800 s suffice).
  const Simulated below = Simulate(doc, fold - 0.002, 800), above = Simulate(doc, fold + 0.002, 800);
  std::printf("[ measured ] from rest: lower-disc speed range %.4f rad/s at fold - 2 mV, %.2e at fold + 2 mV\n",
              below.summary.at("bit_speed_range_rad_s").get<double>(),
              above.summary.at("bit_speed_range_rad_s").get<double>());
  EXPECT_GT(below.summary.at("bit_speed_range_rad_s").get<double>(), 1.0);
  EXPECT_LT(above.summary.at("bit_speed_range_rad_s").get<double>(), 0.02);

  // The stable branch's peak lower-disc speed at 2 V (linear between neighbours) against a long run.
  const Simulated at2 = Simulate(doc, 2.0, 300);
  double peak = std::nan("");
  for (std::size_t i = 1; i < branch.points.size(); ++i) {
    const auto &a = branch.points[i - 1], &b = branch.points[i];
    if (a.orbit.stable && b.orbit.stable && (a.p - 2.0) * (b.p - 2.0) <= 0)
      peak = a.amplitude_max + (b.amplitude_max - a.amplitude_max) * (2.0 - a.p) / (b.p - a.p);
  }
  std::printf("[ measured ] peak lower-disc speed at 2 V: branch %.5f rad/s, simulation %.5f rad/s\n", peak,
              at2.summary.at("bit_speed_max_rad_s").get<double>());
  EXPECT_NEAR(peak, at2.summary.at("bit_speed_max_rad_s").get<double>(), 0.02);
}

}  // namespace
}  // namespace drillwave::cases
