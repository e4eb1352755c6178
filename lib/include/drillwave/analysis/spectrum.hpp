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
// With one neutral delay, or delays that are small multiples of one, the abscissa is exact (companion matrix of the
// difference operator). With incommensurate delays it is the abscissa robust to small changes of the delays (Hale &
// Verduyn Lunel 1993, ch. 9: the largest sigma with sup_theta rho(sum_k B_k e^{-sigma tau_k + i theta_k}) >= 1), which
// is exact for rationally independent delays and an upper bound otherwise; physical travel times are never exact.
// Up to six distinct neutral delays (beyond: NaN); the sup over the phases is searched on a grid and refined locally.
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
  // The last m states are integrals of signals that enter only through their derivatives (the waves of a network)
  // or through differences of their delayed values (the bit's angle and position in the depth of cut,
  // n (U(t) - U(t - t_n))): the system is one in those signals, so its characteristic function is det Delta(s) / s^m,
  // and the m roots at s = 0 that the integration adds are no motions. Their columns of A_0 + sum_k A_k must be zero
  // (each such column of Delta(s) / s is then I - sum_k B_k e^{-s tau_k} + sum_k A_k (1 - e^{-s tau_k}) / s, entire).
  int derivative_only_states = 0;

  int dimension() const { return static_cast<int>(a0.rows()); }
  bool IsNeutral() const;
  // The same difference operator as `other` (same delays, same neutral matrices, exactly): then the same essential
  // spectrum, which a map's neighbouring points share when the mapped parameters do not touch the reflections.
  bool SameDifferenceOperator(const LinearDelaySystem& other) const;
  // Throws std::invalid_argument naming what is wrong (sizes, tau <= 0, non-finite entries).
  void Validate() const;
  // Delta(s) (with the derivative-only columns divided by s) and its derivative d Delta / ds.
  Eigen::MatrixXcd Characteristic(std::complex<double> s) const;
  Eigen::MatrixXcd CharacteristicDerivative(std::complex<double> s) const;
};

struct SpectrumOptions {
  // Chebyshev nodes N of the generator's discretization (N + 1 points): at most this many; im_max tau_max / 2 + 16
  // when fewer (short delays).
  int collocation_nodes = 48;
  double re_min = -50;          // keep roots with Re s >= re_min ...
  double im_max = 200;          // ... and |Im s| <= im_max
  int newton_iterations = 60;
  double root_tolerance = 1e-10;  // relative Newton step at convergence; also the merge distance of duplicates

  // collocation_nodes >= 4, re_min finite, im_max and root_tolerance finite and > 0, newton_iterations >= 1
  // (core/validity.hpp).
  bool IsValid(std::string* error) const;
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
  // kMarginal: every root found has Re s <= 0 but the essential spectrum lies on the imaginary axis
  // (|essential_abscissa| <= kEssentialOnAxis: lossless reflections, e.g. an inertial or speed-imposed end on both
  // sides of a lossless string). Root chains then approach Re s = 0: no uniform exponential decay rate exists and the
  // verdict holds for the roots up to |Im s| = im_max only (at higher frequencies the chains' side of the axis decides).
  enum class Verdict { kStable, kMarginal, kUnstable } verdict = Verdict::kUnstable;
  int candidates = 0, refined = 0;  // how many starting points, how many converged to a root in the region
};

constexpr double kEssentialOnAxis = 1e-8;  // 1/s
const char* VerdictName(Spectrum::Verdict v);  // "stable", "marginal", "unstable"

// Throws std::invalid_argument for a system that is not valid (LinearDelaySystem::Validate), ParameterError for options
// that are not valid.
Spectrum ComputeSpectrum(const LinearDelaySystem& system, const SpectrumOptions& options = {});

// The pieces ComputeSpectrum is made of, for methods that find the roots otherwise (rightmost_root.hpp).
// Newton's method on det Delta from s (false: no convergence within options.newton_iterations).
bool RefineRoot(const LinearDelaySystem& system, std::complex<double>& s, const SpectrumOptions& options);
// Spectrum::essential_abscissa; appends the starting points of the difference operator's root chains (commensurate
// delays) up to options.im_max to chain_starts.
double EssentialAbscissa(const LinearDelaySystem& system, const SpectrumOptions& options,
                         std::vector<std::complex<double>>& chain_starts);
// By real part, descending (equal real parts: by imaginary part, ascending), the order of Spectrum::roots.
void SortRightmostFirst(std::vector<std::complex<double>>& roots);
// stable and verdict from spectral_abscissa and essential_abscissa.
void SetVerdict(Spectrum& spectrum);
// (1 - e^{-s tau}) / s, entire (by its series near s = 0): a derivative-only column's retarded coefficient in Delta.
std::complex<double> DelayedDifference(std::complex<double> s, double tau);

}  // namespace drillwave::analysis
