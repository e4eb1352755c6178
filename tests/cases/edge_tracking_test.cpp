// The unstable cycle that separates the Saldivar string's two attractors at top speeds above its Hopf point (the
// steady state is linearly stable there, yet the run from rest sticks and slips): found by edge tracking on the
// amplitude of a top-speed dip applied at the steady state. As the top speed comes down to the Hopf point the cycle
// must shrink and its period tend to 2 pi / omega of the critical root pair of the linearization.
#include "drillwave/cases/edge_tracking.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/stability.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

nlohmann::json Saldivar() {
  return testing::LoadCase("saldivar-stickslip");
}

// Brought to the steady state at top speed omega from a fast rigid rotation (20 rad/s, where it slides), then a
// half-second dip of the top speed to knot 4's value; the run tells by its last 30 s whether the bit still sticks.
nlohmann::json DipCase(double omega, double duration) {
  nlohmann::json doc = Saldivar();
  doc["model"]["top"]["speed_rad_s"] = {
      {"knots", {{0, 20}, {30, 20}, {60, omega}, {100, omega}, {100.5, omega - 2}, {101, omega}}}};
  doc["model"]["initial"] = {{"bit_speed_rad_s", 20}};
  doc["simulation"]["duration_s"] = duration;
  doc["statistics"]["window_s"] = {duration - 30, duration};
  return doc;
}

// The rightmost root pair at top speed omega (the critical pair near the Hopf point).
std::complex<double> RightmostRoot(double omega) {
  nlohmann::json doc = Saldivar();
  doc["model"]["top"]["speed_rad_s"] = omega;
  return AnalyzeStability(ParseCase(doc)).front().spectrum.roots.front().s;
}

TEST(EdgeTracking, SaldivarSaddleCycleShrinksToTheHopfPoint) {
  const double omega_hopf = 8.34409;
  const std::complex<double> critical = RightmostRoot(omega_hopf);
  const double period_hopf = 2 * kPi / std::abs(critical.imag());
  std::printf("[ measured ] critical root at %.5f rad/s: %.3e %+.6fi, 2 pi / omega = %.5f s\n", omega_hopf,
              critical.real(), critical.imag(), period_hopf);
  std::vector<double> amplitude, period;
  for (double omega : {10.0, 9.0, 8.6}) {
    EdgeSpec spec;
    spec.pointer = "/model/top/speed_rad_s/knots/4/1";
    spec.decays = omega - 1, spec.sticks = omega - 6;
    spec.tolerance = 1e-11;
    const EdgeResult edge = TrackEdge(DipCase(omega, 300), spec);
    const RunResult& run = edge.edge;
    std::vector<double> bit(run.channel("bit_rpm").values);
    for (double& v : bit) v *= kPi / 30;
    const ShadowedCycle cycle = FindShadowedCycle(run.time_s, bit, 101);
    std::printf("[ measured ] top %.2f rad/s: edge at knot %.12f (%d runs); saddle cycle period %.5f s, bit speed "
                "peak-to-peak %.5f rad/s (at t = %.1f s, change %.2e per cycle)\n", omega, edge.decays, edge.runs,
                cycle.period_s, cycle.amplitude, cycle.time_s, cycle.relative_change);
    ASSERT_TRUE(cycle.found);
    EXPECT_LT(cycle.relative_change, 0.05);
    amplitude.push_back(cycle.amplitude);
    period.push_back(cycle.period_s);
  }
  EXPECT_GT(amplitude[0], amplitude[1]);
  EXPECT_GT(amplitude[1], amplitude[2]);
  EXPECT_LT(std::abs(period[2] - period_hopf), std::abs(period[0] - period_hopf));
  EXPECT_NEAR(period[2], period_hopf, 0.03 * period_hopf);
  // Near a Hopf point the cycle's amplitude grows like sqrt(omega - omega_hopf).
  const double ratio = (amplitude[2] * amplitude[2] / (8.6 - omega_hopf)) /
                       (amplitude[1] * amplitude[1] / (9.0 - omega_hopf));
  std::printf("[ measured ] A^2 / (omega - omega_H): ratio 8.6 to 9 rad/s = %.4f\n", ratio);
  EXPECT_NEAR(ratio, 1.0, 0.15);
}

}  // namespace
}  // namespace drillwave::cases
