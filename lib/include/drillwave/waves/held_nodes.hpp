#pragma once
// Massless nodes tied to their neighbours by dashpots and held by Coulomb friction: the internal nodes of a wave chain
// with Kelvin-Voigt damping and side friction. Node j (0..n-1) balances
//   d_j v_j - k_{j-1} v_{j-1} - k_j v_{j+1} = r_j - f_j,   f_j in F_j Sign(v_j)  (any value in [-F_j, F_j] at rest),
// with d_j > k_{j-1} + k_j (diagonally dominant: an M-matrix). This is the optimality condition of the strictly
// convex  min 1/2 v'Av - r'v + sum F_j |v_j|, so the solution is unique and continuous in r.
#include <vector>

namespace drillwave::waves {

struct HeldNodes {
  std::vector<double> diagonal;  // d_j, n entries
  std::vector<double> coupling;  // k_j between nodes j and j+1, n - 1 entries
  std::vector<double> friction;  // F_j >= 0, n entries

  int size() const { return static_cast<int>(diagonal.size()); }
  // The speeds v for the right-hand side r. state holds each node's motion (-1, 0 held, +1): read as the first guess
  // (a previous solution's, or all zero), written as the solution's. Primal-dual active sets: solve with the held
  // nodes at rest and the others sliding against F_j, then hold exactly the nodes whose force from the right-hand side
  // and their neighbours, q_j = r_j + k_{j-1} v_{j-1} + k_j v_{j+1}, stays within F_j; repeat until no node changes
  // (one or two rounds from a previous solution). Two-sided friction can make the sets cycle; then Gauss-Seidel sweeps
  // on each node's closed form, v_j = sign(q_j) max(|q_j| - F_j, 0) / d_j, which converge from anywhere, give the
  // next first guess. Returns the rounds of active sets taken in all (-1: Gauss-Seidel alone finished it).
  int Solve(const std::vector<double>& r, std::vector<double>& v, std::vector<signed char>& state) const;
  // The rates of the speeds for the rate of the right-hand side, with the nodes at rest held (state from Solve).
  void Rates(const std::vector<double>& r_rate, const std::vector<signed char>& state, std::vector<double>& dv) const;
  // Nothing held and no friction (Kelvin-Voigt dashpots alone): the tridiagonal system, for speeds and rates alike,
  // with the pivots FactorLinear computed once (call it after setting diagonal and coupling).
  void FactorLinear();
  void SolveLinear(const std::vector<double>& r, std::vector<double>& v) const;

 private:
  // The tridiagonal system with the held nodes' rows replaced by v_j = 0 and the sliding nodes' right-hand sides
  // lessened by their friction (Thomas algorithm; diagonally dominant, so stable without pivoting).
  void SolveWithHeld(const std::vector<double>& r, const std::vector<signed char>& state, bool with_friction,
                     std::vector<double>& v) const;
  mutable std::vector<double> pivot_ratio_;  // scratch of the Thomas algorithm
  std::vector<double> free_inv_pivot_, free_ratio_;  // FactorLinear's: every node free
};

}  // namespace drillwave::waves
