// waves::WaveChain on its own: the steady state it starts from balances its ends, and waves driven in at the top of
// an undamped chain of several pieces come back as the closed-form d'Alembert sum (each round trip reflected at a
// clamped bit and at the driven top), through the node histories, their split parts and the end forces.
#include "drillwave/cases/friction_json.hpp"
#include "drillwave/waves/wave_chain.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "drillwave/bitrock/friction.hpp"
#include "drillwave/waves/network_simulation.hpp"

namespace drillwave::waves {
namespace {

using integration::Side;

ChainSpec Uniform(int pieces, double z, double tau) {
  ChainSpec spec;
  spec.z.assign(pieces, z), spec.tau.assign(pieces, tau);
  spec.damping.assign(pieces + 1, 0.0), spec.load.assign(pieces + 1, 0.0), spec.coulomb.assign(pieces + 1, 0.0);
  return spec;
}

// Pipe and BHA pieces with damping, weight and side friction on the nodes: in steady motion the string carries the
// bit's force up, adding each node's damping and friction and taking off its weight.
TEST(WaveChain, SteadyMotionBalancesBothEnds) {
  ChainSpec spec = Uniform(6, 120.0, 0.02);
  spec.z[4] = spec.z[5] = 310.0, spec.tau[4] = spec.tau[5] = 0.013;
  double expected_top = 0;
  const double v = 6.0, bit_force = 5300.0;
  for (int j = 0; j <= 6; ++j) {
    spec.damping[j] = 1.5 + j, spec.load[j] = 40.0 * j;
    if (j > 0 && j < 6) spec.coulomb[j] = 25.0;
    expected_top += spec.damping[j] * v - spec.load[j] + spec.coulomb[j];
  }
  expected_top += bit_force;
  const WaveChain chain(spec, v, bit_force);
  EXPECT_NEAR(chain.steady_top_force(), expected_top, 1e-9 * expected_top);
  const ChainEnds f = chain.EndForces(-1.0, Side::kLeft, {v, v});
  EXPECT_NEAR(f.bit, bit_force, 1e-9 * bit_force);  // the string pushes the bit as the rock holds it
  EXPECT_NEAR(f.top, -expected_top, 1e-9 * expected_top);
}

// Undamped, uniform, at rest; the top driven at v(t) = 1 - cos(w t) from t = 0, the bit clamped. The wave sent down
// from the top is D(t) = sum_k v(t - 2kT) (each echo comes back from the clamped bit inverted and leaves the driven
// top inverted again), and the bit feels 2 Z D(t - T), T the travel time of the whole chain.
TEST(WaveChain, DrivenTopReachesAClampedBitAsTheDAlembertSum) {
  const int pieces = 5;
  const double z = 250.0, tau = 0.04, travel = pieces * tau, w = 9.0;
  WaveChain chain(Uniform(pieces, z, tau), 0.0, 0.0);
  auto v = [w](double t) { return t > 0 ? 1 - std::cos(w * t) : 0.0; };
  auto dv = [w](double t) { return t > 0 ? w * std::sin(w * t) : 0.0; };
  auto bit_force = [&](double t) {
    double down = 0;
    for (double sent = t - travel; sent > 0; sent -= 2 * travel) down += v(sent);
    return 2 * z * down;
  };
  const double h = tau / 8;  // every arrival on a step boundary
  std::vector<double> end_kinks;
  double worst = 0, largest = 0, worst_check = 0;
  for (int k = 0; k < 400; ++k) {  // 10 round trips
    const double t0 = k * h, t1 = t0 + h;
    const WaveChain::StepEnds step{t0, t1, {v(t0), 0}, {dv(t0), 0}, {v(t0 + 0.25 * h), 0}, {v(t0 + 0.5 * h), 0},
                                   {v(t1), 0}, {dv(t1), 0}};
    worst_check = std::max(worst_check, chain.Prepare(step, 1e-9, 1e-9));
    chain.Commit(t0, t1, 2 * tau, end_kinks);
    // Between step ends, as an integrator's stages ask (the bit's arrivals were sent a piece's travel time before).
    const double t = t1 + 0.3 * h;
    worst = std::max(worst, std::abs(chain.EndForces(t, Side::kLeft, {v(t), 0}).bit - bit_force(t)));
    largest = std::max(largest, std::abs(bit_force(t)));
  }
  std::printf("[ measured ] 10 round trips: bit force within %.2e of the d'Alembert sum (largest %.1f), worst quarter-"
              "point check %.2g\n", worst, largest, worst_check);
  EXPECT_GT(largest, 1000.0);
  EXPECT_LT(worst, 1e-7 * largest);
  EXPECT_LT(worst_check, 1.0);  // the stored quartics hold these smooth waves to the tolerance at h = tau / 8
}

// A jump through junctions: three pieces of different impedances and incommensurate travel times, at rest, the top
// set turning at 1 rad/s at t = 0 (a jump on the node histories' first knot), the bit clamped. The exact solution is a
// staircase: at a junction a jump splits into a reflected and a transmitted one, at the ends it reflects. Reference:
// the d'Alembert recursion itself, w sent by a node at time T - n.tau from the waves it received (memoized on the
// counts n of each piece's travel time). WaveChain stores the jumps in node histories split at their arrivals and
// reports those that reach an end, where the steps stop: the end forces match the staircase to rounding.
class Staircase {
 public:
  Staircase(std::vector<double> z, std::vector<double> tau, double t) : z_(std::move(z)), tau_(std::move(tau)), t_(t) {}
  // The wave node j sends down (into piece j) or up (into piece j - 1) at time t - n.tau.
  double Sent(int j, bool down, std::array<int, 3> n) {
    const double t = t_ - n[0] * tau_[0] - n[1] * tau_[1] - n[2] * tau_[2];
    if (t < 0) return 0.0;  // at rest
    const auto key = std::make_tuple(j, down, n);
    if (auto it = memo_.find(key); it != memo_.end()) return it->second;
    const int m = static_cast<int>(z_.size());
    double from_above = 0, from_below = 0, v;
    if (j > 0) from_above = Sent(j - 1, true, Later(n, j - 1));
    if (j < m) from_below = Sent(j + 1, false, Later(n, j));
    if (j == 0) v = 1.0;
    else if (j == m) v = 0.0;
    else v = 2 * (z_[j - 1] * from_above + z_[j] * from_below) / (z_[j - 1] + z_[j]);
    return memo_[key] = v - (down ? from_below : from_above);
  }
  double TopForce() { return z_[0] * (2 * Sent(1, false, {1, 0, 0}) - 1.0); }
  double BitForce() { return z_.back() * 2 * Sent(2, true, {0, 0, 1}); }

 private:
  static std::array<int, 3> Later(std::array<int, 3> n, int piece) { return ++n[piece], n; }
  std::vector<double> z_, tau_;
  double t_;
  std::map<std::tuple<int, bool, std::array<int, 3>>, double> memo_;
};

TEST(WaveChain, AJumpThroughJunctionsIsTheExactStaircase) {
  ChainSpec spec = Uniform(3, 200.0, 0.0);
  spec.z = {200.0, 650.0, 310.0};
  spec.tau = {0.031, 0.0473, 0.0177};
  WaveChain chain(spec, 0.0, 0.0);
  const double h = 0.01, t_end = 1.0, tol = 1e-13;
  std::vector<double> end_kinks;
  double worst = 0, largest = 0;
  int steps = 0, samples = 0;
  for (double t0 = 0; t0 < t_end - 1e-12; ++steps) {
    double t1 = std::min(t_end, t0 + h);
    for (double kink : end_kinks)
      if (kink > t0 + 1e-12 && kink < t1) t1 = kink;
    chain.ForgetStart();  // the top's and the bit's waves at a jump's arrival: their right limits
    const ChainEnds turning{1.0, 0.0}, steady{0.0, 0.0};
    EXPECT_LT(chain.Prepare({t0, t1, turning, steady, turning, turning, turning, steady}, tol, tol), 1.0) << t0;
    chain.Commit(t0, t1, 0.1, end_kinks);
    end_kinks.erase(std::remove_if(end_kinks.begin(), end_kinks.end(), [&](double k) { return k <= t1 + 1e-12; }),
                    end_kinks.end());
    for (double s : {0.3, 0.7}) {  // inside every third step taken, where a later step's stage would ask
      if (steps % 3) break;
      const double t = t0 + s * (t1 - t0);
      Staircase exact(spec.z, spec.tau, t);
      const ChainEnds f = chain.EndForces(t, Side::kLeft, turning);
      worst = std::max({worst, std::abs(f.top - exact.TopForce()), std::abs(f.bit - exact.BitForce())});
      largest = std::max({largest, std::abs(f.top), std::abs(f.bit)});
      ++samples;
    }
    t0 = t1;
  }
  std::printf("[ measured ] a jump through 2 junctions over %.0f s (%d steps, stopped at %s arrivals): end forces "
              "within %.2e of the staircase at %d times (largest %.1f)\n", t_end, steps, "the ends'", worst, samples,
              largest);
  EXPECT_GT(largest, 300.0);
  EXPECT_LT(worst, 1e-12 * largest);
}

// WaveChain stepped by hand (fixed steps, halved where the stored waves fail their check) and the same chain inside
// SimulateNetwork (stepped by the Simulator, its schedule knots and the chain's end arrivals as breakpoints) carry a
// pipe-and-BHA chain with dampers on its inner nodes and Kelvin-Voigt dashpots across its pieces; the top's speed
// ramped up, held and ramped half down (kinks at 1/16, 3/16, 5/16 and 7/16 s), the bit clamped. The string's force on
// the top agrees between them through about ten round trips. (Until stop 30 the network had an engine of its own, one
// history of all waves with echoes followed through every node: this test checked the two engines against each
// other, 3.7e-8 of 1474.)
TEST(WaveChain, AgreesWithTheWaveNetworkOnADampedTwoSectionChain) {
  ChainSpec spec = Uniform(6, 300.0, 0.05);
  spec.z[4] = spec.z[5] = 900.0, spec.tau[4] = spec.tau[5] = 0.03;
  spec.kv.assign(6, 0.0);
  for (int k = 0; k < 6; ++k) spec.kv[k] = 0.004 * spec.z[k] / spec.tau[k];  // eta = 4 ms
  for (int j = 1; j < 6; ++j) spec.damping[j] = 20.0 * j;
  const std::vector<double> knots{0.0625, 0.1875, 0.3125, 0.4375};
  const model::Schedule speed({{0.0, 0.0}, {knots[0], 0.0}, {knots[1], 1.0}, {knots[2], 1.0}, {knots[3], 0.5}});

  Network net;
  Node top;
  top.name = "top";
  top.drive = Drive::kPrescribedSpeed;
  top.setpoint = speed;
  net.nodes.push_back(top);
  for (int k = 0; k < 6; ++k) {
    net.sections.push_back({0, spec.tau[k], spec.z[k], spec.kv[k]});
    Node node;
    node.name = k + 1 < 6 ? "inner" : "bit";
    if (k + 1 < 6) node.ground_damping = spec.damping[k + 1];
    else node.drive = Drive::kPrescribedSpeed, node.setpoint = model::Schedule(0.0);
    net.nodes.push_back(node);
  }
  NetworkRunOptions options;
  options.t_end_s = 2.0;
  options.output_interval_s = 1.0 / 64;
  options.integrator.abs_tol = options.integrator.rel_tol = 1e-11;
  const NetworkRun run = SimulateNetwork(net, options);
  const NetworkTrajectory& tr = run.trajectory;

  // WaveChain as its callers step it: steps of at most 1/1024 s (ending on every knot and sample), cut short where a
  // kink reaches a node (end_kinks: with Kelvin-Voigt dashpots every node's arrivals) and where the stored waves fail
  // their check, down to 1e-7 s. A few steps that start on a knot of the top's speed or on one of its arrivals still
  // fail the check down to that floor (up to 1e3 at steps of 1e-7 s, the start's rates against the rest of the step);
  // they are taken as they are, and the forces agree.
  WaveChain chain(spec, 0.0, 0.0);
  const double h = 1.0 / 1024;
  std::vector<double> end_kinks;
  double worst = 0, largest = 0, worst_check = 0;
  std::size_t sample = 0;
  for (double t0 = 0; t0 < 2.0 - 1e-12;) {
    double t1 = std::min(2.0, (std::floor(t0 / h + 1e-9) + 1) * h);
    for (double kink : end_kinks)
      if (kink > t0 + 1e-12 && kink < t1) t1 = kink;
    chain.ForgetStart();  // every start computed anew, at its right limits (a kink may arrive on a step's start)
    auto at = [&](double t) { return ChainEnds{speed.Value(t), 0.0}; };
    auto prepare = [&](double end) {
      const double step_h = end - t0;
      return chain.Prepare({t0, end, at(t0), {speed.Slope(t0), 0.0}, at(t0 + 0.25 * step_h), at(t0 + 0.5 * step_h),
                            at(end), {speed.SlopeBefore(end), 0.0}},
                           1e-11, 1e-11);
    };
    double check = prepare(t1);
    for (; check > 1 && t1 - t0 > 1e-7; check = prepare(t1)) t1 = t0 + 0.5 * (t1 - t0);  // a redone step
    worst_check = std::max(worst_check, check);
    chain.Commit(t0, t1, 0.5, end_kinks);
    end_kinks.erase(std::remove_if(end_kinks.begin(), end_kinks.end(), [&](double k) { return k <= t1 + 1e-12; }),
                    end_kinks.end());
    for (; sample < tr.time_s.size() && tr.time_s[sample] <= t1; ++sample) {
      const double t = tr.time_s[sample];
      const double force = -chain.EndForces(t, integration::Side::kLeft, at(t)).top;
      worst = std::max(worst, std::abs(force - tr.top_torque_nm[sample]));
      largest = std::max(largest, std::abs(force));
    }
    t0 = t1;
  }
  std::printf("[ measured ] WaveChain by hand against SimulateNetwork, 6 pieces in 2 sections with dampers and dashpots, %zu "
              "samples over 2 s: top force within %.3g of each other (largest %.1f); worst check of the stored waves %.2g"
              "\n", sample, worst, largest, worst_check);
  EXPECT_EQ(sample, tr.time_s.size());
  EXPECT_GT(largest, 100.0);
  EXPECT_LT(worst, 1e-9 * largest);
}

// What the network on WaveChain cannot carry is refused, naming the node: an inner node with inertia or friction (the
// chain's inner nodes are massless dampers), and a massless top with friction (it would be ignored).
TEST(WaveChain, TheNetworkRefusesWhatItsChainCannotCarry) {
  auto network = [](Node inner, Node top) {
    Network net;
    top.name = "top", inner.name = "junction";
    Node bit;
    bit.name = "bit", bit.inertia = 89;
    net.sections = {{100, 0.05, 300, 0}, {100, 0.02, 900, 0}};
    net.nodes = {top, inner, bit};
    return net;
  };
  Node prescribed;
  prescribed.drive = Drive::kPrescribedSpeed, prescribed.setpoint = model::Schedule(1.0);
  EXPECT_NO_THROW(network(Node(), prescribed).Validate());
  auto refused = [](const Network& net, const std::string& node) {
    try {
      net.Validate();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what()).find("'" + node + "'") != std::string::npos;
    }
    return false;
  };
  Node heavy;
  heavy.inertia = 10;
  EXPECT_TRUE(refused(network(heavy, prescribed), "junction"));
  Node rubbing;
  rubbing.friction = cases::ReadFrictionLaw({{"law", "viscous"}, {"c_Nms_per_rad", 10.0}}, "/f");
  EXPECT_TRUE(refused(network(rubbing, prescribed), "junction"));
  Node massless_top_with_friction;
  massless_top_with_friction.drive = Drive::kTorque, massless_top_with_friction.setpoint = model::Schedule(100.0);
  massless_top_with_friction.friction = rubbing.friction;
  EXPECT_TRUE(refused(network(Node(), massless_top_with_friction), "top"));
}

}  // namespace
}  // namespace drillwave::waves
