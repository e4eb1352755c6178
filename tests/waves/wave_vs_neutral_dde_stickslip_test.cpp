// Stick–slip through both forms: the wave network (set-valued Stribeck bit with events) and the neutral DDE of
// DESIGN.md §1 solved by the generic solver. The DDE needs the past friction torque T(t - 2 tau), which while
// stuck is not a function of the speed; it carries q = integral of the actual friction torque as a second state,
// so T(t - 2 tau) = q'(t - 2 tau) is a neutral term read from the derivative history.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>

#include <gtest/gtest.h>

#include "drillwave/integration/delay_solver.hpp"
#include "drillwave/waves/network_simulation.hpp"

namespace drillwave::waves {
namespace {

constexpr double kBeta = 2000, kInertia = 89, kEnd = 80, kWindow = 40;

struct Statistics {
  double period, max_speed;
  int onsets;
};

Statistics FromOnsets(const std::vector<double>& onsets, double max_speed) {
  std::vector<double> in;
  for (double t : onsets)
    if (t >= kWindow) in.push_back(t);
  return {in.size() >= 2 ? (in.back() - in.front()) / (in.size() - 1) : NAN, max_speed, static_cast<int>(in.size())};
}

TEST(WaveVsNeutralDde, StribeckStickSlipStatisticsAgree) {
  const bitrock::FrictionLaw law(bitrock::Stribeck{97347, 0.155575, 0.5, 0.8, 0.9, 1.0, 0.03});
  const model::Schedule omega({{0.0, 0.0}, {2.0, 10.0}});
  const double tol = 1e-9;

  Network net;
  net.sections.push_back(Section::Torsional(1172, 79.3e9, 8000, 1.19e-5));
  Node top;
  top.drive = Drive::kSpeedDashpot;
  top.drive_damping = kBeta;
  top.setpoint = omega;
  Node bit;
  bit.inertia = kInertia;
  bit.friction = law;
  net.nodes = {top, bit};
  NetworkRunOptions options;
  options.t_end_s = kEnd;
  options.output_interval_s = 0.001;
  options.integrator.abs_tol = options.integrator.rel_tol = tol;
  const NetworkRun run = SimulateNetwork(net, options);
  std::vector<double> wave_onsets;
  for (const RegimeChange& c : run.regime_changes)
    if (c.to == bitrock::Turn::kStuck) wave_onsets.push_back(c.time_s);
  double wave_max = 0;
  for (std::size_t i = 0; i < run.trajectory.time_s.size(); ++i)
    if (run.trajectory.time_s[i] >= kWindow) wave_max = std::max(wave_max, run.trajectory.bit_speed_rad_s[i]);
  const Statistics wave = FromOnsets(wave_onsets, wave_max);

  const double z = net.sections[0].impedance, tau = net.sections[0].travel_time_s;
  const double ups = (kBeta - z) / (kBeta + z), psi = z / kInertia, pi = 2 * z * kBeta / (kInertia * (kBeta + z));
  const double t_static = law.StaticPositive();
  using Mode = integration::DelayProblem::Mode;
  using State = integration::DelayProblem::State;
  // Friction torque that keeps the bit at rest (y = y' = 0).
  auto holding_torque = [&](double t, const integration::PastView& past) {
    const double y_old = past.Value(t - 2 * tau, 0, t), dy_old = past.Derivative(t - 2 * tau, 0, t);
    const double torque_old = past.Derivative(t - 2 * tau, 1, t);
    return kInertia * (ups * dy_old - ups * psi * y_old + pi * omega.Value(t - tau)) + ups * torque_old;
  };
  integration::DelayProblem p;
  p.dimension = 2;
  p.neutral = true;
  p.constant_delays = {2 * tau};
  p.initial_mode = {0};  // at rest, stuck
  p.history = [](double, double* x, double* d) { x[0] = x[1] = d[0] = d[1] = 0; };
  p.rhs = [&](double t, const State& y, const integration::PastView& past, const Mode& mode, State& dy) {
    if (mode[0] == 0) {
      dy[0] = 0;
      dy[1] = holding_torque(t, past);
      return;
    }
    const double y_old = past.Value(t - 2 * tau, 0, t), dy_old = past.Derivative(t - 2 * tau, 0, t);
    const double torque_old = past.Derivative(t - 2 * tau, 1, t);
    const double torque = law.SlipTorque(mode[0] > 0 ? std::max(y[0], 1e-300) : std::min(y[0], -1e-300));
    dy[0] = ups * dy_old - psi * y[0] - ups * psi * y_old + pi * omega.Value(t - tau) -
            (torque - ups * torque_old) / kInertia;
    dy[1] = torque;
  };
  p.witnesses = {
      [&](double t, const State& y, const integration::PastView& past, const Mode& mode) {
        return mode[0] == 0 ? t_static - holding_torque(t, past) : mode[0] * y[0];
      },
      [&](double t, const State&, const integration::PastView& past, const Mode& mode) {
        return mode[0] == 0 ? holding_torque(t, past) + t_static : 1.0;
      }};
  std::vector<double> dde_onsets;
  p.on_event = [&](int witness, double t, State& y, Mode& mode) {
    if (mode[0] == 0) {
      mode[0] = witness == 0 ? 1 : -1;
      y[0] = 0;
      return;
    }
    // Came to rest: stick. If the holding torque already exceeds the static level, a stuck witness is negative at
    // the restart and the solver fires it at once (the bit reverses).
    mode[0] = 0;
    y[0] = 0;
    dde_onsets.push_back(t);
  };
  integration::IntegratorOptions o;
  o.abs_tol = o.rel_tol = tol;
  const integration::DelaySolution sol = SolveDelayProblem(p, kEnd, o);
  double dde_max = 0;
  for (double t = kWindow; t <= kEnd; t += 0.001) dde_max = std::max(dde_max, sol.Value(t, 0));
  const Statistics dde = FromOnsets(dde_onsets, dde_max);

  std::cout << std::setprecision(10) << "[ measured ] stick-slip period: wave " << wave.period << " s, DDE " << dde.period << " s; max bit speed: wave "
            << wave.max_speed << ", DDE " << dde.max_speed << " rad/s; onsets in window " << wave.onsets << " / "
            << dde.onsets << "\n";
  ASSERT_GE(wave.onsets, 2);
  EXPECT_EQ(wave.onsets, dde.onsets);
  EXPECT_NEAR(dde.period, wave.period, 1e-6 * wave.period);
  EXPECT_NEAR(dde.max_speed, wave.max_speed, 1e-5 * wave.max_speed);
}

}  // namespace
}  // namespace drillwave::waves
