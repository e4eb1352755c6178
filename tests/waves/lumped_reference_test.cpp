// An independent reference (N lumped elements, no waves, no delays) converges to the wave engine's stick–slip
// statistics as N grows: the engine is the N -> infinity limit it approaches.
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "drillwave/waves/network_simulation.hpp"
#include "lumped_string.hpp"

namespace drillwave::waves {
namespace {

TEST(LumpedReference, ConvergesToTheWaveEngineAsElementsAreAdded) {
  const reference::LumpedStringParams params;
  Network net;
  net.sections.push_back(Section::Torsional(params.length_m, params.shear_modulus_pa, params.density_kg_m3,
                                            params.polar_moment_m4));
  Node top;
  top.drive = Drive::kSpeedDashpot;
  top.drive_damping = params.beta;
  top.setpoint = params.top_speed;
  Node bit;
  bit.inertia = params.bit_inertia;
  bit.friction = params.friction;
  net.nodes = {top, bit};
  NetworkRunOptions options;
  options.t_end_s = 80;
  options.output_interval_s = 0.01;
  options.integrator.abs_tol = options.integrator.rel_tol = 1e-10;
  const NetworkRun run = SimulateNetwork(net, options);
  std::vector<double> onsets;
  for (const RegimeChange& c : run.regime_changes)
    if (c.to == Regime::kStuck && c.time_s >= 40) onsets.push_back(c.time_s);
  ASSERT_GE(onsets.size(), 2u);
  const double period = (onsets.back() - onsets.front()) / (onsets.size() - 1);

  integration::IntegratorOptions o;
  o.abs_tol = o.rel_tol = 1e-8;
  double previous_error = INFINITY;
  std::cout << "[ table ] N  period_s  relative period error  derivative evaluations  wall_s\n";
  for (int n : {10, 20, 40, 80}) {
    const auto r = reference::SimulateLumpedString(params, n, 80, 40, o);
    const double error = std::abs(r.stick_slip_period_s - period) / period;
    std::cout << "[ table ] " << n << "  " << r.stick_slip_period_s << "  " << error << "  "
              << r.stats.derivative_evaluations << "  " << r.stats.wall_time_s << "\n";
    EXPECT_LT(error, previous_error) << "N = " << n;
    previous_error = error;
  }
  std::cout << "[ measured ] wave engine period " << period << " s\n";
  EXPECT_LT(previous_error, 2e-3);
}

}  // namespace
}  // namespace drillwave::waves
