// The boundary-controlled bar of the chapter seed (eq. 2.9): q_tt = q_xx on [0, 1], q_x(0, t) = -u(t), free end at
// x = 1, on the wave network (c = Z = tau = 1; the force at x = 0 is a torque u(t) on a massless top node).
// d'Alembert: the down-going wave leaving x = 0 is D(t) = D(t-2) + u(t) = sum_k u(t - 2k), the free end reflects it
// unchanged, so v(1, t) = 2 D(t - 1) and v(0, t) = D(t) + D(t - 2). The momentum of the bar, the integral of
// v(x, t) over x, equals (phi(1, t+1) - phi(1, t-1)) / 2 and must equal the impulse of u (rigid-body drift).
#include <cmath>
#include <functional>
#include <iostream>

#include <gtest/gtest.h>

#include "drillwave/waves/network_simulation.hpp"

namespace drillwave::waves {
namespace {

struct BarRun {
  NetworkRun run;
  std::function<double(double)> down_wave;  // exact D(t)
};

BarRun RunBar(const model::Schedule& u, double t_end) {
  Network net;
  net.sections.push_back(Section::Torsional(1.0, 1.0, 1.0, 1.0));
  Node top;
  top.name = "x=0";
  top.drive = Drive::kTorque;
  top.setpoint = u;
  Node end;
  end.name = "x=1";
  net.nodes = {top, end};
  NetworkRunOptions options;
  options.t_end_s = t_end;
  options.output_interval_s = 1e-3;
  options.integrator.abs_tol = options.integrator.rel_tol = 1e-12;
  BarRun bar{SimulateNetwork(net, options), nullptr};
  bar.down_wave = [u](double t) {
    double d = 0;
    for (double s = t; s >= 0; s -= 2) d += u.Value(s);
    return d;
  };
  return bar;
}

// Largest deviation of both end speeds from the closed form, relative to scale; samples within 1e-6 of a jump of
// the input's echoes are skipped.
double EndSpeedError(const BarRun& bar, double scale, bool skip_jumps) {
  const auto& tr = bar.run.trajectory;
  double worst = 0;
  for (std::size_t i = 0; i < tr.time_s.size(); ++i) {
    const double t = tr.time_s[i];
    if (skip_jumps && std::abs(t - std::round(t)) < 1e-6) continue;
    const double v_end = t < 1 ? 0.0 : 2 * bar.down_wave(t - 1);
    const double v_top = bar.down_wave(t) + (t < 2 ? 0.0 : bar.down_wave(t - 2));
    worst = std::max({worst, std::abs(tr.bit_speed_rad_s[i] - v_end) / scale,
                      std::abs(tr.top_speed_rad_s[i] - v_top) / scale});
  }
  return worst;
}

TEST(ControlledBar, StepInputMatchesDalembert) {
  const BarRun bar = RunBar(model::Schedule({{0.0, 0.0}, {0.0, 1.5}}), 20);
  const double error = EndSpeedError(bar, 1.5, true);
  std::cout << "[ measured ] bar, step input: max relative error " << error << "\n";
  EXPECT_LT(error, 1e-8);
}

TEST(ControlledBar, SineInputMatchesDalembert) {
  // u = sin(3 t) sampled into a piecewise-linear schedule; the closed form uses that same schedule, so it is exact.
  std::vector<std::pair<double, double>> k;
  for (int i = 0; i <= 2000; ++i) k.emplace_back(i * 0.01, std::sin(3 * i * 0.01));
  const model::Schedule u(k);
  const BarRun bar = RunBar(u, 20);
  const double error = EndSpeedError(bar, 1.0, false);
  std::cout << "[ measured ] bar, sine input (2000 linear pieces): max relative error " << error << "\n";
  EXPECT_LT(error, 1e-8);
}

TEST(ControlledBar, MomentumEqualsTheImpulseOfTheControl) {
  std::vector<std::pair<double, double>> k;
  for (int i = 0; i <= 1000; ++i) k.emplace_back(i * 0.01, std::sin(3 * i * 0.01) + 0.2);
  const model::Schedule u(k);
  const BarRun bar = RunBar(u, 14);
  const auto& tr = bar.run.trajectory;
  auto angle_at = [&](double t) { return tr.bit_angle_rad[static_cast<std::size_t>(std::lround(t / 1e-3))]; };
  double worst = 0;
  for (double t = 1.5; t <= 12.5; t += 0.25) {
    double impulse = 0;  // exact integral of the piecewise-linear input
    for (std::size_t i = 1; i < k.size(); ++i) {
      const double a = k[i - 1].first, b = std::min(k[i].first, t);
      if (b > a) impulse += 0.5 * (b - a) * (u.Value(a) + u.Value(b));
    }
    if (t > k.back().first) impulse += (t - k.back().first) * k.back().second;
    const double momentum = 0.5 * (angle_at(t + 1) - angle_at(t - 1));
    worst = std::max(worst, std::abs(momentum - impulse) / std::max(1.0, std::abs(impulse)));
  }
  std::cout << "[ measured ] bar: momentum vs impulse of u, max relative difference " << worst << "\n";
  EXPECT_LT(worst, 1e-8);
}

}  // namespace
}  // namespace drillwave::waves
