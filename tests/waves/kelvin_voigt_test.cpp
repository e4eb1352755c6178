// Kelvin-Voigt damping in the wave network: a dashpot eta Z / tau across each of m equal parts of a uniform string
// (eta G J / part length). Checked against closed forms of the discretization and of the continuum, and against the
// energy the dashpots take out.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "drillwave/cases/friction_json.hpp"
#include "drillwave/bitrock/friction.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/model/schedule.hpp"
#include "drillwave/waves/network_simulation.hpp"
#include "modal_decay.hpp"

namespace drillwave::waves {
namespace {

constexpr double kLength = 1000, kG = 79.3e9, kRho = 8000, kPolar = 1.19e-5;

// A uniform string cut into m parts with a Kelvin-Voigt dashpot across each; the nodes between them massless.
Network Chain(int m, double eta, Node top, Node bit) {
  const Section whole = Section::Torsional(kLength, kG, kRho, kPolar);
  Network net;
  net.nodes.push_back(top);
  for (int k = 0; k < m; ++k) {
    const double tau = whole.travel_time_s / m;
    net.sections.push_back({kLength / m, tau, whole.impedance, eta * whole.impedance / tau});
    Node node;
    node.name = "part";
    if (k + 1 < m) net.nodes.push_back(node);
  }
  net.nodes.push_back(bit);
  return net;
}

// Fixed-free chain of m lossless parts (travel time tau) with dashpots r Z across each: the speeds of the massless
// nodes are v_j = sin(q j) with q = (n - 1/2) pi / m (the top held, the free bit's mirror condition), and node j's
// balance, with the part's admittance Z (v_b csch theta - v_a coth theta) + r Z (v_b - v_a), theta = s tau, gives
//   cos q (1 + r sinh theta) = cosh theta + r sinh theta.
// Newton from the continuum root s^2 + eta w^2 s + w^2 = 0, w = q / tau (which it tends to as m grows).
std::complex<double> DiscreteRoot(int m, int mode, double eta, double travel_time) {
  const double tau = travel_time / m, r = eta / tau, q = (mode - 0.5) * kPi / m, w = q / tau;
  std::complex<double> theta =
      tau * std::complex<double>(-0.5 * eta * w * w, w * std::sqrt(1 - 0.25 * eta * eta * w * w));
  for (int it = 0; it < 50; ++it) {
    const auto f = std::cos(q) * (1.0 + r * std::sinh(theta)) - std::cosh(theta) - r * std::sinh(theta);
    const auto df = std::cos(q) * r * std::cosh(theta) - std::sinh(theta) - r * std::cosh(theta);
    theta -= f / df;
  }
  return theta / tau;
}

struct Decay {
  double simulated, discrete, continuum;
};

// A top whose speed is imposed, ramped from rest to `speed` over `ramp` seconds.
Node RampedTop(double speed, double ramp) {
  Node top;
  top.name = "top";
  top.drive = Drive::kPrescribedSpeed;
  top.setpoint = model::Schedule({{0.0, 0.0}, {ramp, speed}});
  return top;
}

// The first mode's decay after the held top is ramped to 1 rad/s: the bit's speed about 1 rad/s, demodulated.
Decay FirstModeDecay(int m, double eta) {
  Node bit;
  bit.name = "bit";
  const Network net = Chain(m, eta, RampedTop(1.0, 0.02), bit);
  NetworkRunOptions options;
  options.t_end_s = 12;
  options.output_interval_s = 1e-3;
  options.integrator.abs_tol = options.integrator.rel_tol = 1e-9;
  const NetworkRun run = SimulateNetwork(net, options);
  std::vector<double> y = run.trajectory.bit_speed_rad_s;
  for (double& v : y) v -= 1;
  const double travel = net.sections.size() * net.sections.front().travel_time_s;
  const std::complex<double> s = DiscreteRoot(m, 1, eta, travel);
  const double w1 = kPi / (2 * travel);
  const double decay =
      testing::ModalDecay(run.trajectory.time_s, y, s.imag(), 2 * kPi / s.imag(), 2, 11);
  std::printf("[ measured ] m = %d: first mode %.5f rad/s, decay %.6f 1/s; discrete closed form %.6f (%+.3f %%), "
              "continuum eta w1^2 / 2 = %.6f (%+.3f %%); %ld steps, %ld breakpoints\n",
              m, s.imag(), decay, -s.real(), 100 * (decay / -s.real() - 1), 0.5 * eta * w1 * w1,
              100 * (decay / (0.5 * eta * w1 * w1) - 1), run.stats.steps, run.stats.breakpoints);
  return {decay, -s.real(), 0.5 * eta * w1 * w1};
}

// The lumped-dashpot string's first mode decays at the rate of its own closed form, and that rate converges to the
// continuum's eta w1^2 / 2 (fixed-free: w1 = pi c / 2 L) as the parts get shorter.
TEST(KelvinVoigt, FirstModeDecayMatchesTheDiscreteClosedFormAndConvergesToTheContinuum) {
  const double eta = 0.02;
  std::vector<Decay> decays;
  for (int m : {5, 10, 20, 40}) decays.push_back(FirstModeDecay(m, eta));
  for (const Decay& d : decays) EXPECT_NEAR(d.simulated, d.discrete, 2e-3 * d.discrete);
  for (std::size_t k = 1; k < decays.size(); ++k)
    EXPECT_LT(std::abs(decays[k].discrete - decays[k].continuum), std::abs(decays[k - 1].discrete - decays[k - 1].continuum));
  EXPECT_NEAR(decays.back().simulated, decays.back().continuum, 5e-3 * decays.back().continuum);
}

// Without damping the same chain is the lossless string: its discrete closed form gives w1 = pi c / 2 L exactly.
TEST(KelvinVoigt, DiscreteClosedFormWithoutDashpotsIsTheLosslessString) {
  const double travel = kLength / std::sqrt(kG / kRho);
  const std::complex<double> s = DiscreteRoot(7, 1, 0.0, travel);
  EXPECT_NEAR(s.real(), 0.0, 1e-12);
  EXPECT_NEAR(s.imag(), kPi / (2 * travel), 1e-9);
}

// Energy balance: after a torque pulse on the free string between two inertias, the stored energy (end inertias and
// waves in flight) falls by exactly what the dashpots dissipate, sum kv (v_{k+1} - v_k)^2 integrated.
TEST(KelvinVoigt, StoredPlusDissipatedEnergyStaysConstant) {
  Node top;
  top.name = "top";
  top.inertia = 500;
  top.drive = Drive::kTorque;
  top.setpoint = model::Schedule({{0.0, 0.0}, {0.0, 2000.0}, {0.2, 2000.0}, {0.2, 0.0}});
  Node bit;
  bit.name = "bit";
  bit.inertia = 89;
  const Network net = Chain(10, 0.05, top, bit);
  NetworkRunOptions options;
  options.t_end_s = 30;
  options.output_interval_s = 0.01;
  options.record_energy = true;
  options.integrator.abs_tol = options.integrator.rel_tol = 1e-10;
  const NetworkRun run = SimulateNetwork(net, options);
  const auto& tr = run.trajectory;
  ASSERT_EQ(tr.dissipated_j.size(), tr.time_s.size());
  double reference = -1, drift = 0, dissipated = 0;
  for (std::size_t i = 0; i < tr.time_s.size(); ++i) {
    if (tr.time_s[i] < 0.25) continue;
    const double total = tr.energy_j[i] + tr.dissipated_j[i];
    if (reference < 0) reference = total;
    drift = std::max(drift, std::abs(total - reference) / reference);
    dissipated = tr.dissipated_j[i];
  }
  // The rigid rotation keeps the pulse's momentum: (P^2 / 2 J_total), P = 400 N·m·s; the vibration is what goes.
  const double rigid = 0.5 * 400.0 * 400.0 / (500 + 89 + kRho * kPolar * kLength);
  std::printf("[ measured ] stored + dissipated %.6f J, largest relative drift %.3g; dissipated %.4f J, stored at the "
              "end %.6f J against the rigid rotation's %.6f J (%ld steps)\n",
              reference, drift, dissipated, tr.energy_j.back(), rigid, run.stats.steps);
  EXPECT_LT(drift, 1e-6);
  EXPECT_GT(dissipated, 0.1 * reference);
  EXPECT_NEAR(tr.energy_j.back(), rigid, 1e-4 * rigid);
}

// A step of an imposed top speed is a jump that the dashpots spread over the run of massless nodes at once: the
// breakpoint machinery follows it (the run steps onto the echoes), so that few steps are redone for the waves'
// history, as on the string without dashpots, where every echo is a plain d'Alembert reflection or transmission.
integration::IntegrationStats StepResponseStats(double eta) {
  Node top;
  top.name = "top";
  top.drive = Drive::kPrescribedSpeed;
  top.setpoint = model::Schedule({{0.0, 0.0}, {0.1, 0.0}, {0.1, 1.0}});
  Node bit;
  bit.name = "bit";
  bit.inertia = 50;
  const Network net = Chain(8, eta, top, bit);
  NetworkRunOptions options;
  options.t_end_s = 3;
  options.output_interval_s = 1e-3;
  options.integrator.abs_tol = options.integrator.rel_tol = 1e-8;
  const NetworkRun run = SimulateNetwork(net, options);
  std::printf("[ measured ] top speed step, 8 parts, eta = %g s: %ld steps, %ld breakpoints, %ld history rejections, "
              "%ld derivative evaluations\n", eta, run.stats.steps, run.stats.breakpoints, run.stats.history_rejections,
              run.stats.derivative_evaluations);
  return run.stats;
}

TEST(KelvinVoigt, JumpsSpreadOverTheDashpotsAreFollowed) {
  const integration::IntegrationStats lossless = StepResponseStats(0.0), damped = StepResponseStats(0.01);
  EXPECT_GT(damped.breakpoints, 8);
  // Measured: 37 of 654 steps redone, against 10 of 491 without dashpots (the kinks of order 2 and more that the
  // dashpots pass on are left to the step-size control).
  EXPECT_LT(damped.history_rejections, damped.steps / 10);
  EXPECT_LT(lossless.history_rejections, lossless.steps / 10);
}

// A massless bit with smooth friction closes the node system's sweep with its own scalar balance a - b v - T(v). A
// viscous law c w there is the same string as a massless bit with a damper c, whose balance is linear: the runs agree
// to rounding. A velocity-weakening law (rational, chapter eqs. 2.12-2.13) with dashpots tends to the run without them
// as eta -> 0, first order in eta.
// top: the ramped imposed speed, or (dissipative) a massless top driven through a dashpot beta to that ramp, so that
// both ends are massless: without dashpots each balances the wave arriving at it, with them they are one system
// with the string between (the top's linear balance folded into the bit's).
std::vector<double> MasslessFrictionBitSpeed(double eta, const nlohmann::json& friction, double damper,
                                             bool dissipative_top = false) {
  Node bit;
  bit.name = "bit";
  bit.ground_damping = damper;
  if (!friction.is_null()) bit.friction = cases::ReadFrictionLaw(friction, "/bit/friction");
  Node top = RampedTop(10.0, 2.0);
  if (dissipative_top) top.drive = Drive::kSpeedDashpot, top.drive_damping = 400;
  const Network net = Chain(10, eta, top, bit);
  NetworkRunOptions options;
  options.t_end_s = 8;
  options.output_interval_s = 1e-3;
  options.integrator.abs_tol = options.integrator.rel_tol = 1e-10;
  return SimulateNetwork(net, options).trajectory.bit_speed_rad_s;
}

double LargestDifference(const std::vector<double>& a, const std::vector<double>& b) {
  EXPECT_EQ(a.size(), b.size());
  double largest = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) largest = std::max(largest, std::abs(a[i] - b[i]));
  return largest;
}

TEST(KelvinVoigt, MasslessBitWithViscousFrictionIsTheBitWithADamper) {
  const double c = 150;
  const auto friction = MasslessFrictionBitSpeed(0.02, {{"law", "viscous"}, {"c_Nms_per_rad", c}}, 0);
  const auto damper = MasslessFrictionBitSpeed(0.02, nullptr, c);
  const double difference = LargestDifference(friction, damper);
  std::printf("[ measured ] massless bit, eta 0.02 s: viscous friction against a damper of the same c, largest bit "
              "speed difference %.3g rad/s over 8 s (bit at %.4f rad/s)\n", difference, damper.back());
  EXPECT_LT(difference, 1e-9);
  EXPECT_GT(damper.back(), 1);
}

TEST(KelvinVoigt, MasslessBitWithVelocityWeakeningFrictionTendsToTheRunWithoutDashpots) {
  // Its steepest fall, about -p k / 8 zeta = -125 N m s, stays above -Z (300): the massless bit keeps one speed.
  const nlohmann::json rational = {{"law", "rational"}, {"p_Nm", 1000}, {"k", 0.5}, {"zeta", 0.5}};
  const auto plain = MasslessFrictionBitSpeed(0, rational, 0);
  std::vector<double> difference;
  for (double eta : {1e-4, 1e-5, 1e-6}) {
    difference.push_back(LargestDifference(MasslessFrictionBitSpeed(eta, rational, 0), plain));
    std::printf("[ measured ] massless bit with rational friction, eta %.0e s: largest bit speed difference to the run "
                "without dashpots %.3g rad/s over 8 s (bit at %.4f rad/s)\n", eta, difference.back(), plain.back());
  }
  EXPECT_GT(difference[0], 1e-6);  // the dashpots do act
  EXPECT_NEAR(difference[1] / difference[0], 0.1, 0.03);
  EXPECT_NEAR(difference[2] / difference[1], 0.1, 0.03);
}

// Both ends massless and tied by the dashpot of a single part, the whole string: a dissipative top (beta to a set
// point that steps to 10 rad/s at t = 0, the string at rest before) and a bit with a damper c. Every wave is constant
// between multiples of the travel time tau, and each level solves the two ends' balances together:
//   (Z + beta + kv) v_t - kv v_b = 2 Z U_in + beta 10,   -kv v_t + (Z + c + kv) v_b = 2 Z D_in,
// U_in and D_in the waves the other end sent one level before. The run against that lattice, inside the levels.
TEST(KelvinVoigt, TwoMasslessEndsTiedByOneDashpotFollowTheExactLattice) {
  const double beta = 400, c = 150, eta = 0.02;
  Node top = RampedTop(10.0, 0.0);
  top.drive = Drive::kSpeedDashpot, top.drive_damping = beta;
  top.setpoint = model::Schedule(10.0);
  Node bit;
  bit.name = "bit";
  bit.ground_damping = c;
  const Network net = Chain(1, eta, top, bit);
  NetworkRunOptions options;
  options.t_end_s = 40 * net.sections[0].travel_time_s;
  options.output_interval_s = net.sections[0].travel_time_s / 7;
  options.integrator.abs_tol = options.integrator.rel_tol = 1e-10;
  const NetworkTrajectory tr = SimulateNetwork(net, options).trajectory;

  const double z = net.sections[0].impedance, tau = net.sections[0].travel_time_s, kv = net.sections[0].dashpot;
  std::vector<double> bit_speed, down{0.0}, up{0.0};  // by level; level 0 before the start
  for (int k = 1; k <= 41; ++k) {
    const double a11 = z + beta + kv, a22 = z + c + kv, r1 = 2 * z * up[k - 1] + beta * 10, r2 = 2 * z * down[k - 1];
    const double det = a11 * a22 - kv * kv, vt = (r1 * a22 + kv * r2) / det, vb = (a11 * r2 + kv * r1) / det;
    down.push_back(vt - up[k - 1]), up.push_back(vb - down[k - 1]), bit_speed.push_back(vb);
  }
  double worst = 0, largest = 0;
  int compared = 0;
  for (std::size_t i = 0; i < tr.time_s.size(); ++i) {
    const double level = tr.time_s[i] / tau, inside = level - std::floor(level);
    if (inside < 1e-6 || inside > 1 - 1e-6) continue;  // on a level's boundary: either side
    const double exact = bit_speed[static_cast<std::size_t>(level)];
    worst = std::max(worst, std::abs(tr.bit_speed_rad_s[i] - exact)), largest = std::max(largest, std::abs(exact));
    ++compared;
  }
  std::printf("[ measured ] two massless ends tied by one dashpot (kv / Z = %.3f): bit speed within %.2e of the "
              "lattice at %d samples over 40 travel times (largest %.3f rad/s)\n", kv / z, worst, compared, largest);
  EXPECT_GT(compared, 40);
  EXPECT_GT(largest, 1.0);
  EXPECT_LT(worst, 1e-10 * largest);
}

// The same with a massless dissipative top as well: the two massless ends solved together through the dashpots'
// constant end slopes tend, first order in eta, to the ends closed one by one from their arriving waves.
TEST(KelvinVoigt, TwoMasslessEndsTendToTheRunWithoutDashpots) {
  const nlohmann::json rational = {{"law", "rational"}, {"p_Nm", 1000}, {"k", 0.5}, {"zeta", 0.5}};
  const auto plain = MasslessFrictionBitSpeed(0, rational, 0, true);
  std::vector<double> difference;
  for (double eta : {1e-4, 1e-5, 1e-6}) {
    difference.push_back(LargestDifference(MasslessFrictionBitSpeed(eta, rational, 0, true), plain));
    std::printf("[ measured ] massless dissipative top and massless bit, eta %.0e s: largest bit speed difference to "
                "the run without dashpots %.3g rad/s over 8 s (bit at %.4f rad/s)\n", eta, difference.back(),
                plain.back());
  }
  EXPECT_GT(difference[0], 1e-6);
  EXPECT_NEAR(difference[1] / difference[0], 0.1, 0.03);
  EXPECT_NEAR(difference[2] / difference[1], 0.1, 0.03);
}

}  // namespace
}  // namespace drillwave::waves
