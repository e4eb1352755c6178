// Strings of several sections: every junction splits each wave into a reflected and a transmitted part, so the
// echoes of one jump multiply; merged by arrival time they stay few (BreakpointQueue) and the solution stays exact.
#include <algorithm>
#include <cmath>
#include <string>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/io/json_reader.hpp"
#include "drillwave/waves/network_simulation.hpp"
#include "json_case.hpp"

namespace drillwave::waves {
namespace {

constexpr double kOmega0 = 10.0;
constexpr double kG = 79.3e9, kRho = 8000;

// Pipe of 900 m over collars of 300 m (travel times 3:1, an impedance step of 4.36), lossless, imposed top speed
// jumping from 0 to Omega0 at t = 0, free (massless, frictionless) bit: the solution is piecewise constant.
Network PipeOverCollars() {
  Network net;
  net.sections.push_back(Section::Torsional(900, kG, kRho, 1.19e-5));
  net.sections.push_back(Section::Torsional(300, kG, kRho, 5.19e-5));
  Node top;
  top.name = "top";
  top.drive = Drive::kPrescribedSpeed;
  top.setpoint = model::Schedule({{0.0, 0.0}, {0.0, kOmega0}});
  Node junction;
  junction.name = "junction";
  Node bit;
  bit.name = "bit";
  net.nodes = {top, junction, bit};
  return net;
}

// The same string as a lattice of delay cells one collar travel time long (the d'Alembert solution sampled exactly:
// between jumps the waves are constant). Returns the bit speed on each cell interval (k dt, (k + 1) dt).
std::vector<double> LatticeBitSpeed(const Network& net, int cells) {
  const double z1 = net.sections[0].impedance, z2 = net.sections[1].impedance;
  const int n1 = 3, n2 = 1;  // cells per section
  // Delay lines of the waves leaving each end: the value leaving at cell k arrives at the far end at cell k + n.
  std::vector<double> down1(cells + n1 + 1, 0.0), up1(cells + n1 + 1, 0.0), down2(cells + n2 + 1, 0.0),
      up2(cells + n2 + 1, 0.0);
  std::vector<double> bit(cells);
  for (int k = 0; k < cells; ++k) {
    const double d1_in = k >= n1 ? down1[k - n1] : 0.0;  // at the junction, from above
    const double u2_in = k >= n2 ? up2[k - n2] : 0.0;    // at the junction, from below
    const double u1_in = k >= n1 ? up1[k - n1] : 0.0;    // at the top
    const double d2_in = k >= n2 ? down2[k - n2] : 0.0;  // at the bit
    const double v_top = kOmega0, v_junction = (2 * z1 * d1_in + 2 * z2 * u2_in) / (z1 + z2), v_bit = 2 * d2_in;
    down1[k] = v_top - u1_in;
    up1[k] = v_junction - d1_in;
    down2[k] = v_junction - u2_in;
    up2[k] = v_bit - d2_in;
    bit[k] = v_bit;
  }
  return bit;
}

TEST(MultiSection, JunctionReflectsAndTransmitsAsTheExactStaircase) {
  const Network net = PipeOverCollars();
  const double dt = net.sections[1].travel_time_s;
  ASSERT_NEAR(net.sections[0].travel_time_s / dt, 3.0, 1e-12);
  const int cells = 600;  // 100 round trips of the whole string
  const std::vector<double> exact = LatticeBitSpeed(net, cells);
  NetworkRunOptions o;
  o.t_end_s = cells * dt;
  o.output_interval_s = dt / 7.0;
  o.integrator.abs_tol = o.integrator.rel_tol = 1e-12;
  const NetworkRun run = SimulateNetwork(net, o);
  const auto& tr = run.trajectory;
  double worst = 0;
  int checked = 0;
  for (std::size_t i = 0; i < tr.time_s.size(); ++i) {
    const double cell = tr.time_s[i] / dt, frac = cell - std::floor(cell);
    if (frac < 1e-6 || frac > 1 - 1e-6) continue;  // on a jump
    const int k = static_cast<int>(cell);
    if (k >= cells) continue;
    worst = std::max(worst, std::abs(tr.bit_speed_rad_s[i] - exact[k]) / kOmega0);
    ++checked;
  }
  std::cout << "[ measured ] pipe over collars: largest deviation from the lattice " << worst << " (relative to Omega0) over "
            << checked << " samples; " << run.stats.breakpoints << " breakpoints, " << run.stats.steps << " steps\n";
  EXPECT_GT(checked, 3000);
  EXPECT_LT(worst, 1e-12);
  // Without merging, every pass through the junction doubles the echoes (2^100 after 100 round trips); merged,
  // there are at most a few distinct arrival times per cell at each node.
  EXPECT_LT(run.stats.breakpoints, 10 * cells);
}

}  // namespace
}  // namespace drillwave::waves

namespace drillwave::cases {
namespace {

// Stick-slip statistics of strings with 2 and 5 sections converge as the tolerance is tightened: the echoes that are
// dropped or merged cost accuracy only at the level of the tolerance.
class SectionedStickSlip : public ::testing::TestWithParam<const char*> {};

TEST_P(SectionedStickSlip, StatisticsConvergeWithTheTolerance) {
  const nlohmann::json doc = testing::LoadCase(GetParam());
  struct Stats {
    double tol, period, fraction, mean;
  };
  std::vector<Stats> runs;
  for (double tol : {1e-4, 1e-6, 1e-8, 1e-10}) {
    nlohmann::json d = doc;
    d["simulation"]["abs_tol"] = d["simulation"]["rel_tol"] = tol;
    d["simulation"]["output_interval_s"] = 0.01;
    const CaseRun run = RunCase(ParseCase(d));
    runs.push_back({tol, run.summary["oscillation_period_s"].get<double>(), run.summary["stick_fraction"].get<double>(),
                    run.summary["bit_speed_mean_rad_s"].get<double>()});
    std::cout << "[ measured ] " << GetParam() << " tol " << tol << ": period " << runs.back().period
              << " s, stick fraction " << runs.back().fraction << ", mean speed " << runs.back().mean << " rad/s, "
              << run.summary["breakpoints"] << " breakpoints, " << run.summary["derivative_evaluations"]
              << " evaluations\n";
  }
  const Stats& ref = runs.back();
  auto error = [&](const Stats& s) {
    return std::max({std::abs(s.period - ref.period) / ref.period, std::abs(s.fraction - ref.fraction),
                     std::abs(s.mean - ref.mean) / ref.mean});
  };
  EXPECT_LT(error(runs[0]), 1e-4);
  EXPECT_LT(error(runs[1]), 1e-5);
  EXPECT_LT(error(runs[2]), 1e-7);
  EXPECT_LT(error(runs[2]), error(runs[0]));
}

INSTANTIATE_TEST_SUITE_P(TwoAndFiveSections, SectionedStickSlip, ::testing::Values("saldivar-collars", "saldivar-bha"),
                         [](const auto& info) { return std::string(info.index == 0 ? "Collars" : "Bha"); });

}  // namespace
}  // namespace drillwave::cases
