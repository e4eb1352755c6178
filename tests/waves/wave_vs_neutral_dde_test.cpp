// The wave network and the neutral DDE of DESIGN.md §1 describe the same string: dissipative top, bit inertia I_B,
// linear bit law T = c v. The bit speed y solves
//   y'(t) - U y'(t-2tau) = -Psi y(t) - U Psi y(t-2tau) + Pi Omega(t-tau) - c [y(t) - U y(t-2tau)] / I_B,
// U = (beta-Z)/(beta+Z), Psi = Z/I_B, Pi = 2 Z beta/(I_B (beta+Z)). The two are integrated by different code
// (wave buffers vs. the generic neutral solver's state history) and must agree to solver tolerance.
#include <algorithm>
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "drillwave/integration/delay_solver.hpp"
#include "drillwave/waves/network_simulation.hpp"

namespace drillwave::waves {
namespace {

constexpr double kBeta = 2000, kInertia = 89, kViscous = 500, kEnd = 30;

model::Schedule Ramp() { return model::Schedule({{0.0, 0.0}, {2.0, 10.0}}); }

Network SaldivarString() {
  Network net;
  net.sections.push_back(Section::Torsional(1172, 79.3e9, 8000, 1.19e-5));
  Node top;
  top.name = "top";
  top.drive = Drive::kSpeedDashpot;
  top.drive_damping = kBeta;
  top.setpoint = Ramp();
  Node bit;
  bit.name = "bit";
  bit.inertia = kInertia;
  bit.friction = bitrock::FrictionLaw(bitrock::Viscous{kViscous});
  net.nodes = {top, bit};
  return net;
}

// Largest difference of the bit speed between the two forms, both at tolerance tol.
double Disagreement(double tol) {
  const Network net = SaldivarString();
  const double z = net.sections[0].impedance, tau = net.sections[0].travel_time_s;
  const double ups = (kBeta - z) / (kBeta + z), psi = z / kInertia, pi = 2 * z * kBeta / (kInertia * (kBeta + z));
  const model::Schedule omega = Ramp();

  NetworkRunOptions options;
  options.t_end_s = kEnd;
  options.output_interval_s = 0.01;
  options.integrator.abs_tol = options.integrator.rel_tol = tol;
  const NetworkRun run = SimulateNetwork(net, options);

  integration::DelayProblem p;
  p.dimension = 1;
  p.neutral = true;
  p.constant_delays = {2 * tau};
  p.history = [](double, double* x, double* d) { x[0] = 0, d[0] = 0; };
  p.rhs = [&](double t, const std::vector<double>& y, const integration::PastView& past,
              const integration::DelayProblem::Mode&, std::vector<double>& dy) {
    const double y_old = past.Value(t - 2 * tau, 0, t), dy_old = past.Derivative(t - 2 * tau, 0, t);
    dy[0] = ups * dy_old - psi * y[0] - ups * psi * y_old + pi * omega.Value(t - tau) -
            kViscous * (y[0] - ups * y_old) / kInertia;
  };
  integration::IntegratorOptions o;
  o.abs_tol = o.rel_tol = tol;
  o.max_step = tau;  // Omega(t - tau) has kinks at tau and 2 + tau: keep steps short enough to see them
  const integration::DelaySolution dde = SolveDelayProblem(p, kEnd, o);

  double worst = 0;
  for (std::size_t i = 0; i < run.trajectory.time_s.size(); ++i)
    worst = std::max(worst, std::abs(run.trajectory.bit_speed_rad_s[i] - dde.Value(run.trajectory.time_s[i], 0)));
  std::cout << "[ measured ] tol " << tol << ": max |v_wave - y_dde| = " << worst << " rad/s (wave " << run.stats.steps
            << " steps, DDE " << dde.stats.steps << " steps)\n";
  return worst;
}

TEST(WaveVsNeutralDde, LinearBitLawAgreesToSolverTolerance) {
  const double loose = Disagreement(1e-6), tight = Disagreement(1e-10);
  EXPECT_LT(tight, 1e-7);         // bit speeds of ~10 rad/s; measured 1.3e-8
  EXPECT_LT(tight, 0.01 * loose);  // and the agreement follows the tolerance
}

}  // namespace
}  // namespace drillwave::waves
