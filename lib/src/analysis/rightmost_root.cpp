#include "drillwave/analysis/rightmost_root.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "drillwave/core/constants.hpp"
#include "drillwave/core/validity.hpp"

namespace drillwave::analysis {
namespace {

using Complex = std::complex<double>;

// Reverse Cuthill-McKee order of the symmetric pattern: breadth first from a node of least degree, neighbours by
// ascending degree, then reversed.
std::vector<int> ReverseCuthillMcKee(const std::vector<std::vector<int>>& adjacent) {
  const int n = static_cast<int>(adjacent.size());
  std::vector<int> order, degree(n);
  for (int i = 0; i < n; ++i) degree[i] = static_cast<int>(adjacent[i].size());
  std::vector<bool> seen(n, false);
  while (static_cast<int>(order.size()) < n) {
    int start = -1;
    for (int i = 0; i < n; ++i)
      if (!seen[i] && (start < 0 || degree[i] < degree[start])) start = i;
    seen[start] = true;
    std::size_t head = order.size();
    order.push_back(start);
    while (head < order.size()) {
      std::vector<int> next;
      for (int j : adjacent[order[head++]])
        if (!seen[j]) seen[j] = true, next.push_back(j);
      std::sort(next.begin(), next.end(), [&](int a, int b) { return degree[a] < degree[b]; });
      order.insert(order.end(), next.begin(), next.end());
    }
  }
  std::reverse(order.begin(), order.end());
  return order;
}

// arg(b / a) in (-pi, pi] for unit phases.
double PhaseChange(Complex a, Complex b) { return std::arg(b * std::conj(a)); }

// Change of arg det Delta from a to b, steps halved until each changes the argument by at most 0.5 rad and the
// modulus by at most a factor e (a root near the segment then costs steps, not a missed turn). Steps are also at most
// longest_step(s): a root passed within one step turns the argument by about pi, which the step's other changes must
// not wrap back below 0.5 rad. False when a step falls below rounding (a root on the segment). With `moments`, also
// adds the integrals of s dln(det) and s^2 dln(det) along the segment (midpoint rule per step) to moments[0], [1].
template <typename Determinant, typename LongestStep>
bool ArgumentChange(const Determinant& det, Complex a, Complex b, LongestStep longest_step, double& change,
                    Complex* moments = nullptr) {
  const double length = std::abs(b - a);
  const Complex direction = (b - a) / length;
  CharacteristicDeterminant::Value from = det(a);
  if (!std::isfinite(from.log_modulus)) return false;
  double t = 0, h = length / 32;
  while (t < length) {
    const double step = std::min({h, length - t, longest_step(a + direction * t)});
    const Complex s = a + direction * (t + step);
    const CharacteristicDeterminant::Value to = det(s);
    if (!std::isfinite(to.log_modulus)) return false;
    const double d_arg = PhaseChange(from.phase, to.phase), d_log = to.log_modulus - from.log_modulus;
    if (std::abs(d_arg) > 0.5 || std::abs(d_log) > 1.0) {
      h = 0.5 * step;
      if (h < 1e-12 * (1.0 + std::abs(s))) return false;
      continue;
    }
    change += d_arg;
    if (moments) {
      const Complex mid = a + direction * (t + 0.5 * step), d_ln(d_log, d_arg);
      moments[0] += mid * d_ln, moments[1] += mid * mid * d_ln;
    }
    t += step;
    from = to;
    h = std::abs(d_arg) < 0.2 && std::abs(d_log) < 0.4 ? 2 * step : step;
  }
  return true;
}

// Newton's method on det Delta(s) / prod_j (s - r_j), the roots r_j already found divided out (deflation: two seeds
// cannot both end on one root when the roots moved far since the neighbouring point). The derivative of ln det Delta
// by central differences (the banded LU gives the determinant, not Delta^{-1}); the difference step shrinks with
// Newton's steps so that the root is resolved to about 1e-9 relative.
template <typename Determinant>
bool NewtonOnDeterminant(const Determinant& det, Complex& s, int iterations, const std::vector<Complex>& known) {
  double last_step = std::numeric_limits<double>::infinity();
  for (int it = 0; it < iterations; ++it) {
    const double scale = 1.0 + std::abs(s);
    const double h = std::max(1e-9 * scale, std::min(1e-5 * scale, 1e-3 * last_step));
    const auto plus = det(s + h), minus = det(s - h);
    if (!std::isfinite(plus.log_modulus) || !std::isfinite(minus.log_modulus)) return true;  // a root to rounding
    Complex log_derivative =
        Complex(plus.log_modulus - minus.log_modulus, PhaseChange(minus.phase, plus.phase)) / (2 * h);
    for (const Complex r : known) {
      if (std::abs(s - r) <= 1e-7 * scale) return false;  // on a known root
      log_derivative -= 1.0 / (s - r);
      if (r.imag() != 0) log_derivative -= 1.0 / (s - std::conj(r));
    }
    if (!std::isfinite(log_derivative.real()) || !std::isfinite(log_derivative.imag()) || log_derivative == 0.0)
      return false;
    const Complex step = 1.0 / log_derivative;
    s -= step;
    last_step = std::abs(step);
    if (!std::isfinite(s.real()) || !std::isfinite(s.imag())) return false;
    if (last_step <= 1e-9 * (1.0 + std::abs(s))) return true;
  }
  return false;
}

}  // namespace

CharacteristicDeterminant::CharacteristicDeterminant(const LinearDelaySystem& sys) : n_(sys.dimension()) {
  const int n = n_, first_derivative_only = n - sys.derivative_only_states;
  // Terms of one delay share their exponential: merged, each entry sums one product per distinct delay (a string in k
  // equal pieces has k terms of one tau). delay_sum_ keeps every term's: det Delta varies as fast as their sum.
  std::vector<std::size_t> merged;
  for (const DelayTerm& d : sys.delays) {
    delay_sum_ += d.tau;
    merged.push_back(static_cast<std::size_t>(std::find(tau_.begin(), tau_.end(), d.tau) - tau_.begin()));
    if (merged.back() == tau_.size()) tau_.push_back(d.tau);
  }
  std::vector<std::vector<bool>> used(n, std::vector<bool>(n, false));
  for (int i = 0; i < n; ++i) {
    used[i][i] = true;
    for (int j = 0; j < n; ++j) {
      used[i][j] = used[i][j] || sys.a0(i, j) != 0;
      for (const DelayTerm& d : sys.delays)
        used[i][j] = used[i][j] || (d.retarded.size() > 0 && d.retarded(i, j) != 0) ||
                     (d.neutral.size() > 0 && d.neutral(i, j) != 0);
    }
  }
  std::vector<std::vector<int>> adjacent(n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (i != j && (used[i][j] || used[j][i])) adjacent[i].push_back(j);
  const std::vector<int> order = ReverseCuthillMcKee(adjacent);
  std::vector<int> position(n);
  for (int k = 0; k < n; ++k) position[order[k]] = k;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (!used[i][j]) continue;
      Entry e{position[i], position[j], j >= first_derivative_only, i == j, sys.a0(i, j),
              std::vector<double>(tau_.size(), 0.0), std::vector<double>(tau_.size(), 0.0)};
      for (std::size_t t = 0; t < sys.delays.size(); ++t) {
        const DelayTerm& d = sys.delays[t];
        if (d.retarded.size() > 0) e.retarded[merged[t]] += d.retarded(i, j);
        if (d.neutral.size() > 0) e.neutral[merged[t]] += d.neutral(i, j);
      }
      lower_ = std::max(lower_, e.row - e.col);
      upper_ = std::max(upper_, e.col - e.row);
      entries_.push_back(std::move(e));
    }
}

double CharacteristicDeterminant::delay_sum() const { return delay_sum_; }

CharacteristicDeterminant::Value CharacteristicDeterminant::operator()(Complex s) const {
  const int n = n_, terms = static_cast<int>(tau_.size());
  Complex e[16], difference[16];
  std::vector<Complex> e_heap, difference_heap;
  Complex* ek = e;
  Complex* dk = difference;
  if (terms > 16) e_heap.resize(terms), difference_heap.resize(terms), ek = e_heap.data(), dk = difference_heap.data();
  for (int k = 0; k < terms; ++k) ek[k] = std::exp(-s * tau_[k]), dk[k] = DelayedDifference(s, tau_[k]);
  // Delta(s) entry by entry, as LinearDelaySystem::Characteristic builds it.
  std::vector<Complex> m(static_cast<std::size_t>(n) * n, Complex(0.0));
  for (const Entry& en : entries_) {
    Complex v;
    if (en.derivative_only) {
      v = en.diagonal ? 1.0 : 0.0;
      for (int k = 0; k < terms; ++k) v += dk[k] * en.retarded[k] - ek[k] * en.neutral[k];
    } else {
      v = (en.diagonal ? s : 0.0) - en.a0;
      for (int k = 0; k < terms; ++k) v -= ek[k] * (en.retarded[k] + s * en.neutral[k]);
    }
    m[static_cast<std::size_t>(en.row) * n + en.col] = v;
  }
  // Banded LU with partial pivoting: row exchanges widen the upper band to lower + upper.
  Value out{0.0, Complex(1.0)};
  for (int k = 0; k < n; ++k) {
    const int last_row = std::min(n - 1, k + lower_), last_col = std::min(n - 1, k + lower_ + upper_);
    int pivot = k;
    for (int i = k + 1; i <= last_row; ++i)
      if (std::norm(m[static_cast<std::size_t>(i) * n + k]) > std::norm(m[static_cast<std::size_t>(pivot) * n + k]))
        pivot = i;
    Complex* row_k = &m[static_cast<std::size_t>(k) * n];
    if (pivot != k) {
      Complex* row_p = &m[static_cast<std::size_t>(pivot) * n];
      for (int j = k; j <= last_col; ++j) std::swap(row_k[j], row_p[j]);
      out.phase = -out.phase;
    }
    const Complex p = row_k[k];
    const double size = std::abs(p);
    if (!(size > 0) || !std::isfinite(size)) return {-std::numeric_limits<double>::infinity(), Complex(1.0)};
    out.log_modulus += std::log(size);
    out.phase *= p / size;
    // Written out: std::complex's operator* and operator/ guard against inf and NaN by a library call each.
    const double inverse_r = p.real() / size / size, inverse_i = -p.imag() / size / size;  // 1 / p; size^2 may overflow
    for (int i = k + 1; i <= last_row; ++i) {
      Complex* row_i = &m[static_cast<std::size_t>(i) * n];
      if (row_i[k] == 0.0) continue;
      const double fr = row_i[k].real() * inverse_r - row_i[k].imag() * inverse_i;  // row_i[k] / p
      const double fi = row_i[k].real() * inverse_i + row_i[k].imag() * inverse_r;
      for (int j = k + 1; j <= last_col; ++j) {
        const double ur = row_k[j].real(), ui = row_k[j].imag();
        row_i[j] = Complex(row_i[j].real() - (fr * ur - fi * ui), row_i[j].imag() - (fr * ui + fi * ur));
      }
    }
  }
  out.phase /= std::abs(out.phase);
  return out;
}

double RootRealPartBound(const LinearDelaySystem& sys) {
  const int n = sys.dimension(), first_derivative_only = n - sys.derivative_only_states;
  // Column j of Delta Q^{-1} - I: ordinary, -(A0 + sum e_k A_k) / s - sum e_k B_k; derivative-only,
  // sum A_k (1 - e_k) / s - sum e_k B_k; with |e_k| <= e^{-sigma tau_k}, |1 - e_k| <= 2 and |s| >= sigma.
  auto largest_column_sum = [&](double sigma) {
    double largest = 0;
    for (int j = 0; j < n; ++j) {
      const bool derivative_only = j >= first_derivative_only;
      double sum = derivative_only ? 0.0 : sys.a0.col(j).cwiseAbs().sum() / sigma;
      for (const DelayTerm& d : sys.delays) {
        const double e = std::exp(-sigma * d.tau);
        if (d.retarded.size() > 0) sum += d.retarded.col(j).cwiseAbs().sum() * (derivative_only ? 2.0 : e) / sigma;
        if (d.neutral.size() > 0) sum += d.neutral.col(j).cwiseAbs().sum() * e;
      }
      largest = std::max(largest, sum);
    }
    return largest;
  };
  double sigma = 1;
  for (int i = 0; i < 2000 && largest_column_sum(sigma) >= 0.5; ++i) sigma *= 1.5;
  return sigma;
}

namespace {

// The count of CountRootsInBox, for any determinant-like function; near_step: the longest step at the left edge.
// With `sums`, also the sum of the roots in the box and of their squares (real: the roots come in conjugate pairs):
// (1 / 2 pi i) of the contour integrals of s^m dln(det), the lower half the mirror of the upper.
template <typename Determinant>
int CountRootsInBoxOf(const Determinant& det, double near_step, double re_left, double re_right, double im_max,
                      double* sums = nullptr) {
  // A delay so long that the left edge needs more than 1e5 steps (a string's few hundred; a cut delay 2 pi / (n w) at
  // a bit turning at 1e-300 rad/s, 1e300 s, would need 1e303) cannot be followed: not counted.
  constexpr double kMaxEdgeSteps = 1e5;
  if (!(im_max / near_step <= kMaxEdgeSteps)) return -1;
  // Near the left edge the steps are at most near_step; farther right the exponentials fade and the roots thin out,
  // and the steps grow with the distance.
  auto longest_step = [&](Complex s) { return near_step + 0.2 * (s.real() - re_left); };
  // Counter-clockwise upper half: (re_right, 0) up, across the top, down to (re_left, 0).
  double change = 0;
  const Complex corners[4] = {{re_right, 0}, {re_right, im_max}, {re_left, im_max}, {re_left, 0}};
  Complex moments[2] = {0.0, 0.0};
  for (int k = 0; k < 3; ++k)
    if (!ArgumentChange(det, corners[k], corners[k + 1], longest_step, change, sums ? moments : nullptr)) return -1;
  if (sums) sums[0] = moments[0].imag() / kPi, sums[1] = moments[1].imag() / kPi;  // I - conj(I) = 2i Im I
  const double count = change / kPi;  // the whole box winds twice the upper half's change
  const double whole = std::round(count);
  return std::abs(count - whole) < 0.05 && whole >= 0 ? static_cast<int>(whole) : -1;
}

}  // namespace

int CountRootsInBox(const CharacteristicDeterminant& det, double re_left, double re_right, double im_max) {
  // Near the left edge the steps turn each e^{-s tau_k} by at most 0.25 rad in all.
  const double near_step = 0.25 / std::max(1e-300, det.delay_sum());
  return CountRootsInBoxOf(det, near_step, re_left, re_right, im_max);
}

int CountRootsInBox(const CharacteristicFunction& f, double near_step, double re_left, double re_right,
                    double im_max) {
  return CountRootsInBoxOf(f, near_step, re_left, re_right, im_max);
}

// Unstable when the essential spectrum lies right of the axis; else when a root lies right of 0 (a strictly stable
// difference operator) or right of kEssentialOnAxis (one on the axis: marginal up to there), |Im s| <= im_max.
std::optional<bool> UnstableByArgumentPrinciple(const LinearDelaySystem& system, const SpectrumOptions& o) {
  std::vector<Complex> chain_starts;
  const double essential = EssentialAbscissa(system, o, chain_starts);
  if (std::isnan(essential)) return std::nullopt;
  if (essential > kEssentialOnAxis) return true;
  const double re_left = essential < -kEssentialOnAxis ? 0.0 : kEssentialOnAxis;
  const double re_right = std::max(RootRealPartBound(system), re_left + 1.0);
  const int count = CountRootsInBox(CharacteristicDeterminant(system), re_left, re_right, o.im_max);
  if (count < 0) return std::nullopt;
  return count > 0;
}

std::optional<Spectrum> AbscissaByArgumentPrinciple(const LinearDelaySystem& system, const SpectrumOptions& o,
                                                    double precision) {
  Spectrum sp;
  std::vector<Complex> chain_starts;
  sp.essential_abscissa = EssentialAbscissa(system, o, chain_starts);
  if (std::isnan(sp.essential_abscissa)) return std::nullopt;
  const CharacteristicDeterminant det(system);
  const double bound = RootRealPartBound(system), near_step = 0.25 / std::max(1e-300, det.delay_sum());
  // The roots right of the line Re s = left (|Im s| <= im_max): their count, sum and sum of squares. A line through a
  // root is moved by a fraction of the precision.
  struct Right {
    double left;
    int count;
    double sums[2];
  };
  auto right_of = [&](double re) -> std::optional<Right> {
    for (const double nudge : {0.0, 0.3, -0.3}) {
      Right r{re + nudge * precision, 0, {0, 0}};
      r.count = CountRootsInBoxOf(det, near_step, r.left, std::max(bound, r.left + 1.0), o.im_max, r.sums);
      if (r.count >= 0) return r;
    }
    return std::nullopt;
  };
  // One real root or one pair right of the line: the sums place it (a pair's sum is 2 Re r, its squares' 2 (Re^2 -
  // Im^2)) and Newton's method refines it; nullopt where the sums say two real roots or Newton leaves the box.
  auto rightmost_of = [&](const Right& r) -> std::optional<double> {
    const double re = r.count == 1 ? r.sums[0] : 0.5 * r.sums[0], im2 = re * re - 0.5 * r.sums[1];
    if (!(r.count == 1 || (r.count == 2 && im2 > 0))) return std::nullopt;
    Complex s(re, r.count == 1 ? 1e-3 * (1.0 + std::abs(re)) : std::sqrt(im2));
    if (!NewtonOnDeterminant(det, s, o.newton_iterations, {})) return std::nullopt;
    const bool real = std::abs(s.imag()) <= 1e-7 * (1.0 + std::abs(s));
    if ((r.count == 1) != real || !(s.real() > r.left) || std::abs(s.imag()) > o.im_max) return std::nullopt;
    return s.real();
  };
  // A bracket lo < abscissa <= hi: right of the bound no root; leftward from 0 the step doubles down to re_min.
  std::optional<Right> lo = right_of(0.0);
  double hi = std::max(bound, 1.0);
  if (!lo) return std::nullopt;
  for (double step = 0.125; lo->count == 0; step *= 2) {
    hi = lo->left;
    if (lo->left <= o.re_min) {  // no root in the region
      sp.spectral_abscissa = -std::numeric_limits<double>::infinity();
      SetVerdict(sp);
      return sp;
    }
    if (!(lo = right_of(std::max(o.re_min, lo->left - step)))) return std::nullopt;
  }
  // Halved until one real root or one pair lies right of lo, placed by its sums; else to the precision.
  std::optional<double> abscissa = rightmost_of(*lo);
  while (!abscissa && hi - lo->left > precision) {
    const std::optional<Right> mid = right_of(0.5 * (lo->left + hi));
    if (!mid) return std::nullopt;
    if (mid->count == 0) {
      hi = mid->left;
    } else {
      lo = mid;
      abscissa = rightmost_of(*lo);
    }
  }
  sp.spectral_abscissa = abscissa.value_or(0.5 * (lo->left + hi));
  SetVerdict(sp);
  return sp;
}

bool NewtonOnFunction(const CharacteristicFunction& f, std::complex<double>& s, int iterations,
                      const std::vector<std::complex<double>>& known) {
  return NewtonOnDeterminant(f, s, iterations, known);
}

SeededSpectrum SpectrumFromSeeds(const LinearDelaySystem& sys, const std::vector<Complex>& seeds,
                                 const SpectrumOptions& o, std::optional<double> known_essential_abscissa) {
  sys.Validate();
  ThrowIfInvalid(o);
  SeededSpectrum out;
  Spectrum& sp = out.spectrum;
  std::vector<Complex> chain_starts;
  sp.essential_abscissa =
      known_essential_abscissa ? *known_essential_abscissa : EssentialAbscissa(sys, o, chain_starts);
  sp.candidates = static_cast<int>(seeds.size());
  const CharacteristicDeterminant det(sys);
  std::vector<Complex> found;
  // A real seed starts a little above the axis (Newton from a real start on a real function stays real, and two real
  // roots that met since the neighbouring point are a complex pair now); a complex seed that ends on the axis starts
  // once more (deflated: the pair may have split into two real roots).
  auto newton_from = [&](Complex s) {
    if (s.imag() < 0) s = std::conj(s);
    if (s.imag() == 0) s += Complex(0.0, 0.05 * (1.0 + std::abs(s)));
    if (!NewtonOnDeterminant(det, s, o.newton_iterations, found)) return false;
    if (s.imag() < 0) s = std::conj(s);
    if (std::abs(s.imag()) < 1e-9 * (1.0 + std::abs(s))) s = {s.real(), 0.0};
    if (s.real() < o.re_min || s.imag() > o.im_max) return false;
    if (std::any_of(found.begin(), found.end(), [&](Complex r) { return std::abs(r - s) <= 1e-7 * (1.0 + std::abs(s)); }))
      return false;
    found.push_back(s);
    return s.imag() == 0;
  };
  for (const Complex seed : seeds)
    if (newton_from(seed) && seed.imag() != 0) newton_from(seed);
  SortRightmostFirst(found);
  sp.spectral_abscissa = -std::numeric_limits<double>::infinity();
  if (found.empty()) return out;
  // The rightmost as ComputeSpectrum refines it; a start it does not converge from is no certified root.
  Complex rightmost = found.front();
  if (!RefineRoot(sys, rightmost, o)) return out;
  if (std::abs(rightmost.imag()) < 1e-9 * (1.0 + std::abs(rightmost))) rightmost = {rightmost.real(), 0.0};
  if (rightmost.imag() < 0) rightmost = std::conj(rightmost);
  found.front() = rightmost;
  SortRightmostFirst(found);
  if (found.front() != rightmost || rightmost.real() < o.re_min || rightmost.imag() > o.im_max) return out;
  for (Complex s : found) sp.roots.push_back({s, std::numeric_limits<double>::quiet_NaN()});
  sp.refined = static_cast<int>(found.size());
  sp.spectral_abscissa = rightmost.real();
  SetVerdict(sp);

  // The box: its left edge a little left of the rightmost root, its right edge beyond every root.
  const double re_left = rightmost.real() - 1e-3 * (1.0 + std::abs(rightmost.real()));
  const double re_right = std::max(RootRealPartBound(sys), rightmost.real() + 1.0);
  int expected = 0;
  for (Complex s : found)
    if (s.real() > re_left) expected += s.imag() == 0 ? 1 : 2;
  out.certified = CountRootsInBox(det, re_left, re_right, o.im_max) == expected;

  return out;
}

}  // namespace drillwave::analysis
