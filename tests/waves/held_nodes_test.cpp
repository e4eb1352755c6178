// waves::HeldNodes: massless nodes tied by dashpots and held by Coulomb friction (a wave chain's internal nodes with
// Kelvin-Voigt damping and side friction). Checked on random chains against the optimality conditions themselves and
// against Gauss-Seidel sweeps on each node's closed form run to convergence.
#include "drillwave/waves/held_nodes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace drillwave::waves {
namespace {

HeldNodes RandomChain(int n, std::mt19937& rng, double friction_scale) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  HeldNodes h;
  for (int j = 0; j + 1 < n; ++j) h.coupling.push_back(5 * u(rng));  // dashpots up to 5 x the impedances
  for (int j = 0; j < n; ++j) {
    const double ties = (j > 0 ? h.coupling[j - 1] : 0.0) + (j + 1 < n ? h.coupling[j] : 0.0);
    h.diagonal.push_back(ties + 0.5 + u(rng));
    h.friction.push_back(u(rng) < 0.2 ? 0.0 : friction_scale * u(rng));  // some nodes without friction
  }
  return h;
}

// The friction force each node needs: f_j = r_j + k_{j-1} v_{j-1} + k_j v_{j+1} - d_j v_j, and how far it is from
// F_j Sign(v_j) (0 for a solution).
double WorstViolation(const HeldNodes& h, const std::vector<double>& r, const std::vector<double>& v) {
  const int n = h.size();
  double worst = 0;
  for (int j = 0; j < n; ++j) {
    const double f = r[j] + (j > 0 ? h.coupling[j - 1] * v[j - 1] : 0.0) +
                     (j + 1 < n ? h.coupling[j] * v[j + 1] : 0.0) - h.diagonal[j] * v[j];
    const double allowed = v[j] == 0 ? std::max(std::abs(f) - h.friction[j], 0.0)
                                     : std::abs(f - std::copysign(h.friction[j], v[j]));
    worst = std::max(worst, allowed / (1 + std::abs(r[j])));
  }
  return worst;
}

std::vector<double> GaussSeidel(const HeldNodes& h, const std::vector<double>& r) {
  const int n = h.size();
  std::vector<double> v(n, 0.0);
  for (int sweep = 0; sweep < 200000; ++sweep) {
    double change = 0;
    for (int j = 0; j < n; ++j) {
      const double q = r[j] + (j > 0 ? h.coupling[j - 1] * v[j - 1] : 0.0) + (j + 1 < n ? h.coupling[j] * v[j + 1] : 0.0);
      const double next = std::copysign(std::max(std::abs(q) - h.friction[j], 0.0), q) / h.diagonal[j];
      change = std::max(change, std::abs(next - v[j]));
      v[j] = next;
    }
    if (change < 1e-16) break;
  }
  return v;
}

TEST(HeldNodes, RandomChainsMeetTheFrictionLawAndAgreeWithGaussSeidel) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  double worst = 0, worst_gs = 0;
  int held = 0, sliding = 0, most_rounds = 0, helped = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 1 + trial % 40;
    const HeldNodes h = RandomChain(n, rng, 2.0);
    std::vector<double> r(n);
    for (double& x : r) x = 2 * normal(rng);
    std::vector<double> v;
    std::vector<signed char> state;  // from all held
    const int rounds = h.Solve(r, v, state);
    EXPECT_GE(rounds, 1) << "active sets did not settle: " << trial;
    most_rounds = std::max(most_rounds, rounds);
    helped += rounds > n + 2;
    worst = std::max(worst, WorstViolation(h, r, v));
    const std::vector<double> reference = GaussSeidel(h, r);
    for (int j = 0; j < n; ++j) {
      worst_gs = std::max(worst_gs, std::abs(v[j] - reference[j]));
      (v[j] == 0 ? held : sliding) += 1;
      EXPECT_EQ(state[j], v[j] > 0 ? 1 : v[j] < 0 ? -1 : (h.friction[j] > 0 ? 0 : state[j])) << trial << " " << j;
    }
  }
  std::printf("[ measured ] 400 random chains of 1-40 nodes (%d held, %d sliding): friction law met to %.1e, "
              "Gauss-Seidel's speeds to %.1e; at most %d rounds of active sets from all held (%d chains with Gauss-"
              "Seidel sweeps between them)\n", held, sliding, worst, worst_gs, most_rounds, helped);
  EXPECT_GT(held, 1000);
  EXPECT_GT(sliding, 1000);
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(worst_gs, 1e-10);
}

TEST(HeldNodes, AnyFirstGuessGivesTheSameSpeeds) {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_int_distribution<int> sign(-1, 1);
  const HeldNodes h = RandomChain(30, rng, 1.5);
  std::vector<double> r(30);
  for (double& x : r) x = 2 * normal(rng);
  std::vector<double> v0, v;
  std::vector<signed char> state0;
  h.Solve(r, v0, state0);
  for (int guess = 0; guess < 50; ++guess) {
    std::vector<signed char> state(30);
    for (signed char& s : state) s = static_cast<signed char>(sign(rng));
    h.Solve(r, v, state);
    for (int j = 0; j < 30; ++j) EXPECT_NEAR(v[j], v0[j], 1e-13 * (1 + std::abs(v0[j]))) << guess << " " << j;
    EXPECT_EQ(state, state0);
  }
}

TEST(HeldNodes, WithoutFrictionItIsTheTridiagonalSolve) {
  std::mt19937 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  HeldNodes h = RandomChain(25, rng, 0.0);
  std::vector<double> r(25), v;
  for (double& x : r) x = normal(rng);
  std::vector<signed char> state;
  h.Solve(r, v, state);
  for (int j = 0; j < 25; ++j) {  // every row of the balance, with no friction force
    const double row = h.diagonal[j] * v[j] - (j > 0 ? h.coupling[j - 1] * v[j - 1] : 0.0) -
                       (j + 1 < 25 ? h.coupling[j] * v[j + 1] : 0.0);
    EXPECT_NEAR(row, r[j], 1e-13 * (1 + std::abs(r[j])));
  }
  // The linear solve on pivots factored once (a wave chain's Kelvin-Voigt nodes without side friction) is the same
  // arithmetic: the same speeds to the bit.
  h.FactorLinear();
  std::vector<double> linear;
  h.SolveLinear(r, linear);
  EXPECT_EQ(linear, v);
}

// Between changes of the held set the speeds are linear in the right-hand side: Rates is their exact derivative.
TEST(HeldNodes, RatesAreTheDerivativeOfTheSpeeds) {
  std::mt19937 rng(8);
  std::normal_distribution<double> normal(0.0, 1.0);
  const HeldNodes h = RandomChain(20, rng, 1.0);
  std::vector<double> r(20), r_rate(20);
  for (double& x : r) x = 2 * normal(rng);
  for (double& x : r_rate) x = normal(rng);
  std::vector<double> v, v_plus, v_minus, dv;
  std::vector<signed char> state, s_plus, s_minus;
  h.Solve(r, v, state);
  const double e = 1e-7;
  std::vector<double> rp = r, rm = r;
  for (int j = 0; j < 20; ++j) rp[j] += e * r_rate[j], rm[j] -= e * r_rate[j];
  h.Solve(rp, v_plus, s_plus);
  h.Solve(rm, v_minus, s_minus);
  ASSERT_EQ(s_plus, state);  // no node changes within +-e
  ASSERT_EQ(s_minus, state);
  h.Rates(r_rate, state, dv);
  int moving = 0;
  for (int j = 0; j < 20; ++j) {
    EXPECT_NEAR(dv[j], (v_plus[j] - v_minus[j]) / (2 * e), 1e-7) << j;
    moving += dv[j] != 0;
  }
  EXPECT_GT(moving, 3);
}

}  // namespace
}  // namespace drillwave::waves
