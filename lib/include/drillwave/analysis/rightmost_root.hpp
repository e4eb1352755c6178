#pragma once
// The rightmost characteristic roots of a linear delay system found again from nearby ones, and certified by the
// argument principle (DESIGN.md §4): the fast path of two-parameter stability maps.
//
// ComputeSpectrum finds every root in its region from the eigenvalues of a discretized generator with hundreds of
// rows (about 0.4 s for the coupled model with its string in 5 sub-sections). Between neighbouring points of a map
// the roots move little: Newton's method from the neighbour's rightmost roots finds them again, and the winding of
// det Delta(s) around the box sigma_L < Re s < sigma_R, |Im s| < im_max (sigma_L just left of the rightmost root
// found, sigma_R beyond every root) counts the roots inside. When the count equals the roots found there, the
// rightmost root is the rightmost in the region, as ComputeSpectrum would report it; otherwise the caller computes
// the full spectrum.
//
// det Delta(s) costs a banded LU: the states are ordered by reverse Cuthill-McKee, which turns a wave network's chain
// of sections into a narrow band (about 4 on either side of the diagonal for the coupled model), a few thousand
// flops where the dense LU of Delta costs tens of thousands.
#include <complex>
#include <functional>
#include <optional>
#include <vector>

#include "drillwave/analysis/spectrum.hpp"

namespace drillwave::analysis {

class CharacteristicDeterminant {
 public:
  explicit CharacteristicDeterminant(const LinearDelaySystem& system);  // system.Validate() first

  // det Delta(s) = exp(log_modulus) * phase, |phase| = 1 (log_modulus = -inf: Delta(s) is singular to rounding).
  struct Value {
    double log_modulus;
    std::complex<double> phase;
  };
  Value operator()(std::complex<double> s) const;

  int lower_bandwidth() const { return lower_; }
  int upper_bandwidth() const { return upper_; }
  double delay_sum() const;  // sum of the delay terms' tau

 private:
  struct Entry {
    int row, col;              // in the banded order
    bool derivative_only;      // a derivative-only column: I - sum B_k e_k + sum A_k (1 - e_k) / s
    bool diagonal;
    double a0;
    std::vector<double> retarded, neutral;  // per delay term
  };
  int n_ = 0, lower_ = 0, upper_ = 0;
  double delay_sum_ = 0;
  std::vector<double> tau_;  // distinct
  std::vector<Entry> entries_;
};

// An upper bound on the real parts of the characteristic roots: beyond it ||Delta(s) Q(s)^{-1} - I||_1 < 1 with
// Q = diag(s on ordinary columns, 1 on derivative-only ones).
double RootRealPartBound(const LinearDelaySystem& system);

// The number of roots (with multiplicity) in re_left < Re s < re_right, |Im s| < im_max, from the change of arg det
// Delta along the box's upper half (det Delta is real on the real axis: the lower half mirrors it). -1 when a root
// lies on the box's edge or the change of argument cannot be followed (also where the delays are so long that the
// left edge would take over 1e5 steps).
int CountRootsInBox(const CharacteristicDeterminant& det, double re_left, double re_right, double im_max);

// The same argument principle and Newton's method for a characteristic function given otherwise than as a delay
// system's determinant (e.g. the continuum string of kelvin_voigt_continuum.hpp): its value at s as log modulus and
// phase. It must be analytic in the box and real on the real axis (the lower half mirrors the upper).
using CharacteristicFunction = std::function<CharacteristicDeterminant::Value(std::complex<double>)>;
// near_step: the longest step along the box's left edge (about 0.25 / the longest travel time in the function).
int CountRootsInBox(const CharacteristicFunction& f, double near_step, double re_left, double re_right, double im_max);
// Newton from s on f / prod_j (s - r_j)(s - conj r_j), the roots `known` divided out; false without convergence
// within `iterations` or on a known root.
bool NewtonOnFunction(const CharacteristicFunction& f, std::complex<double>& s, int iterations,
                      const std::vector<std::complex<double>>& known);

// Whether the system is unstable as ComputeSpectrum's verdict would say (SetVerdict: kUnstable or not), from the
// difference operator's roots and the count of characteristic roots right of the axis alone, without finding them:
// milliseconds where the full spectrum of many sub-sections costs seconds. nullopt where it cannot tell (delays that
// are not commensurate, a root on the box's edge). Validate the system first.
std::optional<bool> UnstableByArgumentPrinciple(const LinearDelaySystem& system, const SpectrumOptions& options);

// The verdict and spectral abscissa ComputeSpectrum would give (roots with Re s >= re_min, |Im s| <= im_max) from the
// count of roots right of a vertical line, moved left until a root is right of it and then halved until one real
// root or one pair is: the contour's moments place it, Newton's method refines it (else the halving goes on to
// `precision`). `roots` stays empty. Tens of milliseconds where the full spectrum of many sub-sections costs seconds.
// nullopt where a count cannot be made (delays not commensurate, a root on a box's edge).
std::optional<Spectrum> AbscissaByArgumentPrinciple(const LinearDelaySystem& system, const SpectrumOptions& options,
                                                    double precision);

struct SeededSpectrum {
  // roots: the seeds' roots in the region (Re s >= re_min, 0 <= Im s <= im_max), distinct, rightmost first; only
  // roots.front() is refined as ComputeSpectrum refines (the others to about 1e-9, enough to seed a neighbour);
  // residuals are not computed (NaN). candidates: the seeds; refined: the roots found.
  Spectrum spectrum;
  // The argument principle confirms that no root of the region lies right of roots.front() apart from those found:
  // spectral_abscissa, its frequency and the verdict are then ComputeSpectrum's.
  bool certified = false;
};

// Newton from each seed (conjugates folded into Im s >= 0; real seeds a little above the axis), each run with the roots
// already found divided out, then the box count. Without a root found in the region, not certified.
// known_essential_abscissa: the essential abscissa when the caller has it (a neighbour's, with the same difference
// operator: LinearDelaySystem::SameDifferenceOperator); otherwise it is computed, which for several incommensurate
// neutral delays costs more than the roots.
SeededSpectrum SpectrumFromSeeds(const LinearDelaySystem& system, const std::vector<std::complex<double>>& seeds,
                                 const SpectrumOptions& options = {},
                                 std::optional<double> known_essential_abscissa = std::nullopt);

}  // namespace drillwave::analysis
