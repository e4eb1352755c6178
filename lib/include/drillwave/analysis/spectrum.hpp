#pragma once
// Characteristic roots of linear neutral delay systems (DESIGN.md §4)
//
//   x'(t) - sum_k B_k x'(t - tau_k) = A_0 x(t) + sum_k A_k x(t - tau_k),
//   Delta(s) = s (I - sum_k B_k e^{-s tau_k}) - A_0 - sum_k A_k e^{-s tau_k},  roots: det Delta(s) = 0.
//
// Candidates come from a pseudospectral (Chebyshev) discretization of the system's infinitesimal generator
// (Breda, Maset, Vermiglio 2005) and, for neutral systems, from the asymptotic root chains of the difference
// operator; each candidate is refined by Newton's method on det Delta (step 1 / tr(Delta^{-1} Delta')), and only
// refined roots that satisfy the characteristic equation are kept. The essential spectrum of a neutral system
// (the roots of det(I - sum_k B_k e^{-s tau_k}) = 0, which the root chains approach as |Im s| grows) is reported
// separately: a neutral system is stable only if the rightmost root and that abscissa are both negative.
// Depends on Eigen only; no simulation.
#include <complex>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace drillwave::analysis {

struct DelayTerm {
  double tau = 0;            // > 0
  Eigen::MatrixXd retarded;  // A_k (n x n; empty means zero)
  Eigen::MatrixXd neutral;   // B_k (n x n; empty means zero)
};

struct LinearDelaySystem {
  Eigen::MatrixXd a0;  // n x n
  std::vector<DelayTerm> delays;

  int dimension() const { return static_cast<int>(a0.rows()); }
  bool IsNeutral() const;
  // Throws std::invalid_argument naming what is wrong (sizes, tau <= 0, non-finite entries).
  void Validate() const;
  // Delta(s) and its derivative d Delta / ds.
  Eigen::MatrixXcd Characteristic(std::complex<double> s) const;
  Eigen::MatrixXcd CharacteristicDerivative(std::complex<double> s) const;
};

struct SpectrumOptions {
  int collocation_nodes = 48;   // Chebyshev nodes N of the generator's discretization (N + 1 points)
  double re_min = -50;          // keep roots with Re s >= re_min ...
  double im_max = 200;          // ... and |Im s| <= im_max
  int newton_iterations = 60;
  double root_tolerance = 1e-10;  // relative Newton step at convergence; also the merge distance of duplicates
};

struct CharacteristicRoot {
  std::complex<double> s;
  double residual;  // smallest singular value of Delta(s) over its largest: ~ rounding for a true root
};

struct Spectrum {
  std::vector<CharacteristicRoot> roots;  // refined, distinct, Im s >= 0 only (the rest are conjugates), by Re desc
  double spectral_abscissa;               // largest Re s among the roots found (-inf if none in the region)
  // Supremum of Re s over the difference operator's roots: ln(rho)/tau for the spectral radius rho of the
  // companion matrix when the neutral delays are integer multiples of one delay; -inf for a retarded system; NaN
  // when the neutral delays are not commensurate (not computed).
  double essential_abscissa;
  bool stable;  // spectral_abscissa < 0 and essential_abscissa < 0 (false when the latter is NaN)
  int candidates = 0, refined = 0;  // how many starting points, how many converged to a root in the region
};

Spectrum ComputeSpectrum(const LinearDelaySystem& system, const SpectrumOptions& options = {});

}  // namespace drillwave::analysis
