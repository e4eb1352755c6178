#include "drillwave/waves/held_nodes.hpp"

#include <algorithm>
#include <cmath>

namespace drillwave::waves {

void HeldNodes::SolveWithHeld(const std::vector<double>& r, const std::vector<signed char>& state, bool with_friction,
                              std::vector<double>& v) const {
  const int n = size();
  v.resize(n), pivot_ratio_.resize(n);
  // Forward: row j is d_j v_j - k_{j-1} v_{j-1} - k_j v_{j+1} = rhs_j, a held row v_j = 0.
  double previous_ratio = 0, previous = 0;
  for (int j = 0; j < n; ++j) {
    if (state[j] == 0) {
      v[j] = previous = 0, pivot_ratio_[j] = previous_ratio = 0;
      continue;
    }
    const double below = j > 0 ? coupling[j - 1] : 0.0, above = j + 1 < n ? coupling[j] : 0.0;
    const double inv_pivot = 1 / (diagonal[j] - below * previous_ratio);
    const double rhs = r[j] - (with_friction ? friction[j] * state[j] : 0.0);
    v[j] = previous = (rhs + below * previous) * inv_pivot;
    pivot_ratio_[j] = previous_ratio = above * inv_pivot;
  }
  for (int j = n - 2; j >= 0; --j) v[j] += pivot_ratio_[j] * v[j + 1];
}

int HeldNodes::Solve(const std::vector<double>& r, std::vector<double>& v, std::vector<signed char>& state) const {
  const int n = size();
  state.resize(n, 0);
  auto force = [&](int j) {  // q_j: what moves node j, its neighbours' dashpots included
    return r[j] + (j > 0 ? coupling[j - 1] * v[j - 1] : 0.0) + (j + 1 < n ? coupling[j] * v[j + 1] : 0.0);
  };
  // Each node's closed form given its neighbours (one Gauss-Seidel sweep: a descent step of the convex problem).
  auto sweep = [&] {
    double change = 0, size_of_v = 0;
    for (int j = 0; j < n; ++j) {
      const double q = force(j);
      const double next = std::copysign(std::max(std::abs(q) - friction[j], 0.0), q) / diagonal[j];
      change = std::max(change, std::abs(next - v[j])), size_of_v = std::max(size_of_v, std::abs(next));
      v[j] = next;
    }
    return change <= 1e-15 * size_of_v;
  };
  auto signs_of_speeds = [&] {  // held where at rest against friction
    for (int j = 0; j < n; ++j) state[j] = v[j] > 0 ? 1 : v[j] < 0 ? -1 : friction[j] > 0 ? 0 : 1;
  };
  int rounds = 0;
  for (int attempt = 1; attempt <= 30; ++attempt) {
    for (int round = 0; round < n + 2; ++round) {
      ++rounds;
      SolveWithHeld(r, state, true, v);
      bool changed = false;
      for (int j = 0; j < n; ++j) {
        const double q = force(j);
        // (A node without friction is never held: its sign then only picks a zero friction force.)
        const signed char s = q > friction[j] ? 1 : q < -friction[j] ? -1 : friction[j] > 0 ? 0 : 1;
        changed |= s != state[j];
        state[j] = s;
      }
      if (!changed) return rounds;
    }
    // The sets cycle (two-sided friction: seen from some first guesses with strong dashpots). Gauss-Seidel sweeps
    // bring the speeds nearer the solution, and their signs are the next first guess: once they are the solution's,
    // one round confirms it.
    for (int k = 0; k < 10 * attempt; ++k)
      if (sweep()) break;
    signs_of_speeds();
  }
  // Never seen: Gauss-Seidel until the speeds stop moving.
  for (int k = 0; k < 100000; ++k)
    if (sweep()) break;
  signs_of_speeds();
  return -1;
}

void HeldNodes::Rates(const std::vector<double>& r_rate, const std::vector<signed char>& state,
                      std::vector<double>& dv) const {
  SolveWithHeld(r_rate, state, false, dv);
}

void HeldNodes::FactorLinear() {
  const int n = size();
  free_inv_pivot_.resize(n), free_ratio_.resize(n);
  double previous_ratio = 0;
  for (int j = 0; j < n; ++j) {
    const double below = j > 0 ? coupling[j - 1] : 0.0, above = j + 1 < n ? coupling[j] : 0.0;
    free_inv_pivot_[j] = 1 / (diagonal[j] - below * previous_ratio);
    free_ratio_[j] = previous_ratio = above * free_inv_pivot_[j];
  }
}

// SolveWithHeld's arithmetic with nothing held, on the stored pivots.
void HeldNodes::SolveLinear(const std::vector<double>& r, std::vector<double>& v) const {
  const int n = size();
  v.resize(n);
  double previous = 0;
  for (int j = 0; j < n; ++j) v[j] = previous = (r[j] + (j > 0 ? coupling[j - 1] : 0.0) * previous) * free_inv_pivot_[j];
  for (int j = n - 2; j >= 0; --j) v[j] += free_ratio_[j] * v[j + 1];
}

}  // namespace drillwave::waves
