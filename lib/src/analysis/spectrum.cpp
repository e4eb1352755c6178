#include "drillwave/analysis/spectrum.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/progress.hpp"
#include "drillwave/core/validity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

namespace drillwave::analysis {
namespace {

using Complex = std::complex<double>;

bool AllFinite(const Eigen::MatrixXd& m) { return m.allFinite(); }

// Chebyshev points of the second kind mapped to [-tau, 0] (theta_0 = 0, theta_N = -tau) and the differentiation
// matrix of the interpolating polynomial on them (Trefethen, Spectral Methods in MATLAB, cheb.m).
struct ChebyshevGrid {
  Eigen::VectorXd theta;
  Eigen::MatrixXd d;
  Eigen::VectorXd weights;  // barycentric weights
};

ChebyshevGrid MakeGrid(int n, double tau) {
  ChebyshevGrid g;
  g.theta.resize(n + 1);
  g.weights.resize(n + 1);
  Eigen::VectorXd x(n + 1), c(n + 1);
  for (int j = 0; j <= n; ++j) {
    x(j) = std::cos(kPi * j / n);
    g.theta(j) = 0.5 * tau * (x(j) - 1.0);
    c(j) = ((j == 0 || j == n) ? 2.0 : 1.0) * (j % 2 == 0 ? 1.0 : -1.0);
    g.weights(j) = (j % 2 == 0 ? 1.0 : -1.0) * ((j == 0 || j == n) ? 0.5 : 1.0);
  }
  g.d = Eigen::MatrixXd::Zero(n + 1, n + 1);
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j)
      if (i != j) g.d(i, j) = (c(i) / c(j)) / (x(i) - x(j));
    g.d(i, i) = -g.d.row(i).sum();
  }
  g.d *= 2.0 / tau;  // d/dtheta = (2 / tau) d/dx
  return g;
}

// Row of Lagrange basis values at theta (barycentric formula; a node gives a unit row).
Eigen::RowVectorXd LagrangeRow(const ChebyshevGrid& g, double theta) {
  const int m = static_cast<int>(g.theta.size());
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(m);
  for (int j = 0; j < m; ++j)
    if (std::abs(theta - g.theta(j)) <= 1e-14 * (1.0 + std::abs(theta))) {
      row(j) = 1.0;
      return row;
    }
  for (int j = 0; j < m; ++j) row(j) = g.weights(j) / (theta - g.theta(j));
  return row / row.sum();
}

// Eigenvalues of the discretized infinitesimal generator: the state is the history on Chebyshev grids; rows
// 1..N of each grid differentiate it, row 0 is the system's equation at theta = 0 with delayed values and (neutral)
// delayed derivatives taken from the interpolants. Each state keeps only the history the system reads of it: over
// [-tau_j, 0], tau_j its longest delay, with nodes(tau_j) points (a state read without delay: its present value only).
// A wave integral read one short travel time late then costs a few nodes where the longest delay (the cut delay of
// the coupled model) would cost dozens.
template <typename NodesFor>
std::vector<Complex> GeneratorEigenvalues(const LinearDelaySystem& sys, NodesFor nodes_for, Progress* progress = nullptr) {
  const int n = sys.dimension();
  std::vector<double> history(n, 0.0);
  for (const DelayTerm& d : sys.delays)
    for (int j = 0; j < n; ++j) {
      const bool read = (d.retarded.size() > 0 && !d.retarded.col(j).isZero(0)) ||
                        (d.neutral.size() > 0 && !d.neutral.col(j).isZero(0));
      if (read) history[j] = std::max(history[j], d.tau);
    }
  std::vector<ChebyshevGrid> grids;  // one per distinct history length
  std::vector<double> grid_tau;
  std::vector<int> grid_of(n, -1), offset(n, 0);
  int size = 0;
  for (int j = 0; j < n; ++j) {
    offset[j] = size;
    if (history[j] == 0) {
      ++size;
      continue;
    }
    const auto same = std::find(grid_tau.begin(), grid_tau.end(), history[j]);
    if (same == grid_tau.end()) {
      grid_tau.push_back(history[j]);
      grids.push_back(MakeGrid(nodes_for(history[j]), history[j]));
    }
    grid_of[j] = static_cast<int>(std::find(grid_tau.begin(), grid_tau.end(), history[j]) - grid_tau.begin());
    size += static_cast<int>(grids[grid_of[j]].theta.size());
  }
  Eigen::MatrixXd big = Eigen::MatrixXd::Zero(size, size);
  for (int j = 0; j < n; ++j) {
    if (grid_of[j] < 0) continue;
    const ChebyshevGrid& g = grids[grid_of[j]];
    const int m = static_cast<int>(g.theta.size());
    big.block(offset[j] + 1, offset[j], m - 1, m) = g.d.bottomRows(m - 1);
  }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) big(offset[i], offset[j]) += sys.a0(i, j);
  for (const DelayTerm& d : sys.delays)
    for (int j = 0; j < n; ++j) {
      if (grid_of[j] < 0) continue;
      const ChebyshevGrid& g = grids[grid_of[j]];
      const Eigen::RowVectorXd ell = LagrangeRow(g, -d.tau);
      const Eigen::RowVectorXd ell_prime = ell * g.d;
      for (int i = 0; i < n; ++i) {
        const double a = d.retarded.size() > 0 ? d.retarded(i, j) : 0.0;
        const double b = d.neutral.size() > 0 ? d.neutral(i, j) : 0.0;
        if (a != 0) big.block(offset[i], offset[j], 1, ell.size()) += a * ell;
        if (b != 0) big.block(offset[i], offset[j], 1, ell.size()) += b * ell_prime;
      }
    }
  if (progress)
    progress->Step("eigenvalues of the generator's discretization (" + std::to_string(big.rows()) + " unknowns)");
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(big, false);
  if (solver.info() != Eigen::Success) throw std::runtime_error("eigenvalues of the discretized generator failed");
  const auto ev = solver.eigenvalues();
  return std::vector<Complex>(ev.data(), ev.data() + ev.size());
}

// The difference operator restricted to the states it acts on, one matrix per distinct neutral delay. A state whose
// column is zero in every B_k gives I - sum_k B_k e^{-s tau_k} a unit column, so the determinant is its minor: such
// states are dropped (repeatedly, as dropping a row can empty another column).
struct NeutralTerm {
  double tau;
  Eigen::MatrixXd b;
};

std::vector<NeutralTerm> DifferenceOperator(const LinearDelaySystem& sys) {
  std::vector<NeutralTerm> terms;
  for (const DelayTerm& d : sys.delays) {
    if (d.neutral.size() == 0 || d.neutral.norm() == 0) continue;
    const auto same = std::find_if(terms.begin(), terms.end(), [&](const NeutralTerm& t) { return t.tau == d.tau; });
    if (same != terms.end()) same->b += d.neutral;
    else terms.push_back({d.tau, d.neutral});
  }
  std::vector<int> core(sys.dimension());
  for (int i = 0; i < sys.dimension(); ++i) core[i] = i;
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t j = 0; j < core.size(); ++j) {
      const bool acts = std::any_of(terms.begin(), terms.end(), [&](const NeutralTerm& t) {
        return std::any_of(core.begin(), core.end(), [&](int i) { return t.b(i, core[j]) != 0; });
      });
      if (!acts) {
        core.erase(core.begin() + static_cast<std::ptrdiff_t>(j));
        changed = true;
        break;
      }
    }
  }
  for (NeutralTerm& t : terms) {
    Eigen::MatrixXd reduced(core.size(), core.size());
    for (std::size_t i = 0; i < core.size(); ++i)
      for (std::size_t j = 0; j < core.size(); ++j) reduced(i, j) = t.b(core[i], core[j]);
    t.b = reduced;
  }
  return terms;
}

// The neutral delays as integer multiples m_k of a base delay tau0 (false if they are not commensurate with
// multiples up to max_multiple).
bool CommensurateNeutral(const std::vector<NeutralTerm>& terms, int max_multiple, double& tau0,
                         std::vector<int>& multiples) {
  double smallest = terms.front().tau;
  for (const NeutralTerm& t : terms) smallest = std::min(smallest, t.tau);
  for (int q = 1; q <= max_multiple; ++q) {  // tau0 = smallest / q
    tau0 = smallest / q;
    multiples.clear();
    bool ok = true;
    for (const NeutralTerm& t : terms) {
      const double r = t.tau / tau0;
      const double k = std::round(r);
      if (std::abs(r - k) > 1e-9 * r || k > max_multiple) {
        ok = false;
        break;
      }
      multiples.push_back(static_cast<int>(k));
    }
    if (ok) return true;
  }
  return false;
}

// Roots mu = e^{s tau0} of det(mu^M I - sum_k B_k mu^{M - m_k}) (the difference operator), by a block companion
// matrix.
std::vector<Complex> DifferenceOperatorMultipliers(const std::vector<NeutralTerm>& terms,
                                                   const std::vector<int>& multiples) {
  const int n = static_cast<int>(terms.front().b.rows());
  const int big_m = *std::max_element(multiples.begin(), multiples.end());
  // Monic polynomial mu^M + sum_{j<M} C_j mu^j with C_{M - m_k} = -B_k.
  std::vector<Eigen::MatrixXd> coefficient(big_m, Eigen::MatrixXd::Zero(n, n));
  for (std::size_t k = 0; k < terms.size(); ++k) coefficient[big_m - multiples[k]] -= terms[k].b;
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(n * big_m, n * big_m);
  for (int j = 0; j + 1 < big_m; ++j) companion.block(j * n, (j + 1) * n, n, n).setIdentity();
  for (int j = 0; j < big_m; ++j) companion.block((big_m - 1) * n, j * n, n, n) = -coefficient[j];
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(companion, false);
  const auto ev = solver.eigenvalues();
  return std::vector<Complex>(ev.data(), ev.data() + ev.size());
}

// rho(sum_k B_k e^{-sigma tau_k + i theta_k}): the spectral radius of the difference operator's symbol at phases theta.
double PhaseRadius(const std::vector<NeutralTerm>& terms, double sigma, const std::vector<double>& theta) {
  Eigen::MatrixXcd m = std::exp(-sigma * terms[0].tau) * terms[0].b.cast<Complex>();
  for (std::size_t k = 1; k < terms.size(); ++k)
    m += std::polar(std::exp(-sigma * terms[k].tau), theta[k]) * terms[k].b.cast<Complex>();
  const Eigen::ComplexEigenSolver<Eigen::MatrixXcd> solver(m, false);
  return solver.eigenvalues().cwiseAbs().maxCoeff();
}

struct PhasePeak {
  double rho;                  // the largest radius found
  std::vector<double> theta;   // where
};

// sup over theta of PhaseRadius; theta_0 = 0 (a common phase leaves rho as it is). A grid over the other phases, then
// golden-section refinement of the best point one phase at a time. Returns as soon as a value reaches `enough`.
PhasePeak TorusPeak(const std::vector<NeutralTerm>& terms, double sigma, double enough) {
  const int k_count = static_cast<int>(terms.size());
  auto rho = [&](const std::vector<double>& theta) { return PhaseRadius(terms, sigma, theta); };
  // About 4096 grid points in all (at least 8 per phase): a fine grid for two delays, a coarse one for six, where
  // the maximum found (and so the abscissa) may fall slightly short.
  const int per_phase = k_count == 2 ? 128 : std::max(8, static_cast<int>(std::pow(4096.0, 1.0 / (k_count - 1))));
  std::vector<double> theta(k_count, 0.0);
  PhasePeak best{-1, theta};
  std::vector<int> index(k_count, 0);
  for (bool more = true; more;) {
    for (int k = 1; k < k_count; ++k) theta[k] = 2 * kPi * index[k] / per_phase;
    const double r = rho(theta);
    if (r > best.rho) best = {r, theta};
    if (best.rho >= enough) return best;
    more = false;
    for (int k = 1; k < k_count && !more; ++k) {
      if (++index[k] < per_phase) more = true;
      else index[k] = 0;
    }
  }
  const double golden = 0.5 * (std::sqrt(5.0) - 1);
  for (int pass = 0; pass < 3; ++pass)
    for (int k = 1; k < k_count; ++k) {
      double a = best.theta[k] - 2 * kPi / per_phase, b = best.theta[k] + 2 * kPi / per_phase;
      std::vector<double> t = best.theta;
      auto at = [&](double x) { t[k] = x; return rho(t); };
      double c = b - golden * (b - a), d = a + golden * (b - a), fc = at(c), fd = at(d);
      for (int it = 0; it < 40; ++it) {
        if (fc > fd) b = d, d = c, fd = fc, c = b - golden * (b - a), fc = at(c);
        else a = c, c = d, fc = fd, d = a + golden * (b - a), fd = at(d);
      }
      const double x = fc > fd ? c : d, f = std::max(fc, fd);
      if (f > best.rho) best.rho = f, best.theta[k] = x;
      if (best.rho >= enough) return best;
    }
  return best;
}

// The robust essential abscissa: sup_theta rho(...) < 1 exactly for sigma above it (Hale & Verduyn Lunel, ch. 9).
// -inf when it lies below `floor`. Each search of the torus costs thousands of eigenvalue problems, so the bisection
// runs on the phases found so far (cheap: a few eigenvalue problems a step) and the torus is searched only to
// certify its upper end: where it finds a radius of 1 or more there, its phases join the set and the bisection goes
// on above (a cutting-plane scheme; a few searches instead of one per bisection step). The bracket is exact for the
// torus search: its lower end has a found radius >= 1, its upper end a searched torus below 1.
double RobustEssentialAbscissa(const std::vector<NeutralTerm>& terms, double floor) {
  auto bound = [&](double sigma) {  // rho <= sum_k ||B_k|| e^{-sigma tau_k}
    double sum = 0;
    for (const NeutralTerm& t : terms) sum += t.b.operatorNorm() * std::exp(-sigma * t.tau);
    return sum;
  };
  double hi = 0;
  for (int i = 0; i < 200 && bound(hi) >= 1; ++i) hi = 2 * hi + 1;
  // The search starts low, at the floor (or where e^{-sigma tau} would near overflow), where the torus search ends
  // at its first points: the bisection on phases costs little however wide the bracket, a search below 1 the whole
  // torus (stepping down from the norm bound took eight of them on saldivar-bha).
  double tau_max = 0;
  for (const NeutralTerm& t : terms) tau_max = std::max(tau_max, t.tau);
  double lo = std::max(floor, std::min(hi - 1, -600 / tau_max)), step = hi - lo;
  PhasePeak peak = TorusPeak(terms, lo, 1.0);
  while (peak.rho < 1) {
    if (lo <= floor) return -std::numeric_limits<double>::infinity();
    hi = lo;
    step *= 2;
    lo = std::max(floor, hi - step);
    peak = TorusPeak(terms, lo, 1.0);
  }
  std::vector<std::vector<double>> phases{peak.theta};
  auto reaches_one = [&](double sigma) {
    for (const std::vector<double>& theta : phases)
      if (PhaseRadius(terms, sigma, theta) >= 1) return true;
    return false;
  };
  // Six digits, and 1e-10 absolute near zero where the verdict (kEssentialOnAxis) is decided.
  auto resolved = [&] { return hi - lo <= std::max(1e-10, 1e-7 * std::abs(hi)); };
  for (int search = 0; search < 100; ++search) {
    double upper = hi;
    for (int it = 0; it < 100 && upper - lo > std::max(1e-10, 1e-7 * std::abs(upper)); ++it) {
      const double mid = 0.5 * (lo + upper);
      (reaches_one(mid) ? lo : upper) = mid;
    }
    if (upper >= hi) break;  // the known phases reach 1 up to hi, whose torus is below 1
    peak = TorusPeak(terms, upper, std::numeric_limits<double>::infinity());  // its peak: the next cut
    if (peak.rho < 1) {
      hi = upper;
      break;
    }
    lo = upper;
    phases.push_back(peak.theta);
    if (resolved()) break;
  }
  return 0.5 * (lo + hi);
}

double Residual(const LinearDelaySystem& sys, Complex s) {
  const Eigen::JacobiSVD<Eigen::MatrixXcd> svd(sys.Characteristic(s));
  const auto& sv = svd.singularValues();
  return sv(0) > 0 ? sv(sv.size() - 1) / sv(0) : 0.0;
}

}  // namespace

// Newton's method on det Delta(s): d/ds ln det Delta = tr(Delta^{-1} Delta').
bool RefineRoot(const LinearDelaySystem& sys, Complex& s, const SpectrumOptions& o) {
  for (int it = 0; it < o.newton_iterations; ++it) {
    const Eigen::MatrixXcd delta = sys.Characteristic(s);
    const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(delta);
    const Complex trace = lu.solve(sys.CharacteristicDerivative(s)).trace();
    // A start that is already a root to rounding makes Delta numerically singular: accept it as it is.
    if (!std::isfinite(trace.real()) || !std::isfinite(trace.imag()) || std::abs(trace) == 0)
      return Residual(sys, s) < 1e-13;
    const Complex step = 1.0 / trace;
    s -= step;
    if (!std::isfinite(s.real()) || !std::isfinite(s.imag())) return false;
    if (std::abs(step) <= o.root_tolerance * (1.0 + std::abs(s))) return true;
  }
  return false;
}

namespace {

// The difference operator's core split into blocks of states no B_k couples (connected components of the graph with
// an edge wherever some B_k(i, j) != 0); each block keeps the terms that act on it.
std::vector<std::vector<NeutralTerm>> DecoupledBlocks(const std::vector<NeutralTerm>& terms) {
  std::vector<std::vector<NeutralTerm>> blocks;
  const int n = terms.empty() ? 0 : static_cast<int>(terms.front().b.rows());
  if (n == 0) return blocks;
  std::vector<int> block(n, -1);
  int count = 0;
  for (int seed = 0; seed < n; ++seed) {
    if (block[seed] >= 0) continue;
    std::vector<int> stack{seed};
    block[seed] = count;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      for (int j = 0; j < n; ++j)
        if (block[j] < 0 && std::any_of(terms.begin(), terms.end(), [&](const NeutralTerm& t) {
              return t.b(i, j) != 0 || t.b(j, i) != 0;
            }))
          block[j] = count, stack.push_back(j);
    }
    ++count;
  }
  for (int b = 0; b < count; ++b) {
    std::vector<int> members;
    for (int i = 0; i < n; ++i)
      if (block[i] == b) members.push_back(i);
    std::vector<NeutralTerm> sub;
    for (const NeutralTerm& t : terms) {
      Eigen::MatrixXd m(members.size(), members.size());
      for (std::size_t i = 0; i < members.size(); ++i)
        for (std::size_t j = 0; j < members.size(); ++j) m(i, j) = t.b(members[i], members[j]);
      if (m.norm() > 0) sub.push_back({t.tau, m});
    }
    if (!sub.empty()) blocks.push_back(std::move(sub));
  }
  return blocks;
}

// Essential abscissa of one block of the difference operator; with commensurate delays also the starting points of
// its root chains (appended to starts).
double BlockEssentialAbscissa(const std::vector<NeutralTerm>& terms, const SpectrumOptions& o,
                              std::vector<Complex>& starts) {
  double tau0 = 0;
  std::vector<int> multiples;
  // The companion matrix has (largest multiple) x (core states) rows: beyond a few hundred, or for incommensurate
  // delays, the robust abscissa on the torus (exact for one delay) replaces it.
  const int core = static_cast<int>(terms.front().b.rows());
  if (CommensurateNeutral(terms, std::max(1, 400 / core), tau0, multiples)) {
    double rho = 0;
    for (const Complex mu : DifferenceOperatorMultipliers(terms, multiples)) {
      const double r = std::abs(mu);
      rho = std::max(rho, r);
      if (r == 0) continue;
      // The chain of roots that approaches Re s = ln|mu| / tau0, Im s = (arg mu + 2 pi j) / tau0.
      const double re = std::log(r) / tau0;
      // The chain has about im_max tau0 / 2 pi roots in the region: refuse rather than loop for ever (tau0 = 1e300).
      if (!(o.im_max * tau0 / (2 * kPi) < 1e5))
        throw std::invalid_argument("the neutral delay " + ReadableNumber(tau0) + " s puts more than 1e5 roots of a "
                                    "chain below Im s = " + ReadableNumber(o.im_max) + "; the delay is out of range");
      for (int j = 0;; ++j) {
        const double im = (std::arg(mu) + 2 * kPi * j) / tau0;
        if (im > o.im_max) break;
        if (im >= 0) starts.emplace_back(re, im);
      }
    }
    return rho > 0 ? std::log(rho) / tau0 : -std::numeric_limits<double>::infinity();
  }
  if (terms.size() <= 6) return RobustEssentialAbscissa(terms, o.re_min);
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

bool LinearDelaySystem::IsNeutral() const {
  for (const DelayTerm& d : delays)
    if (d.neutral.size() > 0 && d.neutral.norm() > 0) return true;
  return false;
}

bool LinearDelaySystem::SameDifferenceOperator(const LinearDelaySystem& other) const {
  if (dimension() != other.dimension() || delays.size() != other.delays.size()) return false;
  for (std::size_t k = 0; k < delays.size(); ++k) {
    const DelayTerm &a = delays[k], &b = other.delays[k];
    const bool a_zero = a.neutral.size() == 0 || a.neutral.isZero(0), b_zero = b.neutral.size() == 0 || b.neutral.isZero(0);
    if (a_zero != b_zero) return false;
    if (!a_zero && (a.tau != b.tau || a.neutral != b.neutral)) return false;
  }
  return true;
}

void LinearDelaySystem::Validate() const {
  const auto n = a0.rows();
  if (n < 1 || a0.cols() != n) throw std::invalid_argument("A_0 must be a non-empty square matrix");
  if (!AllFinite(a0)) throw std::invalid_argument("A_0 has a non-finite entry");
  // Entries beyond 1e100 overflow the characteristic matrix and the eigenvalue solver (roots at -inf, "stable").
  if (a0.cwiseAbs().maxCoeff() > 1e100)
    throw std::invalid_argument("A_0 has an entry of magnitude " + ReadableNumber(a0.cwiseAbs().maxCoeff()) +
                                "; beyond 1e100 the roots overflow");
  for (std::size_t k = 0; k < delays.size(); ++k) {
    const DelayTerm& d = delays[k];
    const std::string which = "delay term " + std::to_string(k);
    if (!(d.tau > 0) || !std::isfinite(d.tau)) throw std::invalid_argument(which + ": tau must be finite and > 0");
    for (const Eigen::MatrixXd* m : {&d.retarded, &d.neutral}) {
      if (m->size() == 0) continue;
      if (m->rows() != n || m->cols() != n) throw std::invalid_argument(which + ": matrix is not n x n");
      if (!AllFinite(*m)) throw std::invalid_argument(which + ": non-finite entry");
    }
  }
  const int m = derivative_only_states;
  if (m < 0 || m > n) throw std::invalid_argument("derivative_only_states must be in 0..n");
  // A_0 + sum_k A_k must vanish in those columns (to rounding: the sum of terms of either sign).
  Eigen::MatrixXd sum = a0.rightCols(m), size = a0.rightCols(m).cwiseAbs();
  for (const DelayTerm& d : delays)
    if (d.retarded.size() > 0) sum += d.retarded.rightCols(m), size += d.retarded.rightCols(m).cwiseAbs();
  if (((sum.cwiseAbs() - 1e-12 * size).array() > 0).any())
    throw std::invalid_argument("a derivative-only state has a non-zero column in A_0 + sum_k A_k");
}

// (1 - e^{-s tau}) / s and its derivative in s, by their series near s = 0 (where both forms lose digits).
Complex DelayedDifference(Complex s, double tau) {
  const Complex z = s * tau;
  if (std::abs(z) < 1e-3) return tau * (1.0 - z / 2.0 + z * z / 6.0 - z * z * z / 24.0);
  return (1.0 - std::exp(-z)) / s;
}

namespace {
Complex DelayedDifferenceDerivative(Complex s, double tau) {
  const Complex z = s * tau;
  if (std::abs(z) < 1e-3) return tau * tau * (-0.5 + z / 3.0 - z * z / 8.0 + z * z * z / 30.0);
  const Complex e = std::exp(-z);
  return (z * e - (1.0 - e)) / (s * s);
}
}  // namespace

Eigen::MatrixXcd LinearDelaySystem::Characteristic(Complex s) const {
  const int n = dimension(), m = derivative_only_states;
  // I - sum_k B_k e^{-s tau_k} in the derivative-only columns (their A columns are zero, so Delta's is s times that).
  Eigen::MatrixXcd delta = Eigen::MatrixXcd::Identity(n, n);
  delta.leftCols(n - m) *= s;
  delta.leftCols(n - m) -= a0.leftCols(n - m).cast<Complex>();
  for (const DelayTerm& d : delays) {
    const Complex e = std::exp(-s * d.tau);
    if (d.neutral.size() > 0) {
      delta.leftCols(n - m) -= (s * e) * d.neutral.leftCols(n - m).cast<Complex>();
      delta.rightCols(m) -= e * d.neutral.rightCols(m).cast<Complex>();
    }
    if (d.retarded.size() > 0) {
      delta.leftCols(n - m) -= e * d.retarded.leftCols(n - m).cast<Complex>();
      delta.rightCols(m) += DelayedDifference(s, d.tau) * d.retarded.rightCols(m).cast<Complex>();
    }
  }
  return delta;
}

Eigen::MatrixXcd LinearDelaySystem::CharacteristicDerivative(Complex s) const {
  const int n = dimension(), m = derivative_only_states;
  Eigen::MatrixXcd derivative = Eigen::MatrixXcd::Zero(n, n);
  derivative.leftCols(n - m).setIdentity();
  for (const DelayTerm& d : delays) {
    const Complex e = std::exp(-s * d.tau);
    if (d.neutral.size() > 0) {
      derivative.leftCols(n - m) -= (e * (1.0 - s * d.tau)) * d.neutral.leftCols(n - m).cast<Complex>();
      derivative.rightCols(m) += (d.tau * e) * d.neutral.rightCols(m).cast<Complex>();
    }
    if (d.retarded.size() > 0) {
      derivative.leftCols(n - m) += (d.tau * e) * d.retarded.leftCols(n - m).cast<Complex>();
      derivative.rightCols(m) += DelayedDifferenceDerivative(s, d.tau) * d.retarded.rightCols(m).cast<Complex>();
    }
  }
  return derivative;
}

const char* VerdictName(Spectrum::Verdict v) {
  switch (v) {
    case Spectrum::Verdict::kStable: return "stable";
    case Spectrum::Verdict::kMarginal: return "marginal";
    case Spectrum::Verdict::kUnstable: return "unstable";
  }
  return "unstable";
}

bool SpectrumOptions::IsValid(std::string* error) const {
  return WholeField(error, "collocation_nodes", collocation_nodes, 4) && FiniteField(error, "re_min", re_min) &&
         PositiveField(error, "im_max", im_max) && WholeField(error, "newton_iterations", newton_iterations, 1) &&
         PositiveField(error, "root_tolerance", root_tolerance);
}

Spectrum ComputeSpectrum(const LinearDelaySystem& sys, const SpectrumOptions& o) {
  sys.Validate();
  ThrowIfInvalid(o);
  Spectrum out;
  out.essential_abscissa = -std::numeric_limits<double>::infinity();
  Progress progress("characteristic roots of a linear system of " + std::to_string(sys.dimension()) + " states");

  // Starting points.
  std::vector<Complex> starts;
  if (sys.delays.empty()) {
    const Eigen::EigenSolver<Eigen::MatrixXd> solver(sys.a0, false);
    for (int i = 0; i < solver.eigenvalues().size(); ++i) starts.push_back(solver.eigenvalues()(i));
  } else {
    // N + 1 Chebyshev points over [-tau, 0] resolve the roots up to |Im s| of about N / tau: a short history (a string
    // split into damping sub-sections) needs far fewer nodes than the maximum, and the eigenproblem's cost grows as
    // the cube of the nodes summed over the states.
    // Histories shorter than the longest delay take 8 nodes beyond that instead of 16: their roots in the region are
    // few (a chain's roots lie 2 pi / tau apart) and Newton refines every start; the wave integrals of a string in 20
    // sub-sections are most of the states.
    double tau_max = 0;
    for (const DelayTerm& d : sys.delays) tau_max = std::max(tau_max, d.tau);
    starts = GeneratorEigenvalues(sys, [&](double tau) {
      const double wanted = 0.5 * o.im_max * tau + (tau < tau_max ? 8 : 16);
      return wanted < o.collocation_nodes ? static_cast<int>(std::ceil(wanted)) : o.collocation_nodes;
    }, &progress);
  }
  progress.Step("the essential spectrum of the difference operator");
  out.essential_abscissa = EssentialAbscissa(sys, o, starts);
  out.candidates = static_cast<int>(starts.size());

  // Refine, keep those in the region (upper half plane), merge duplicates.
  std::vector<Complex> found;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    progress.Count("Newton's method from each eigenvalue", static_cast<double>(k), static_cast<double>(starts.size()),
                   "starting points");
    Complex s = starts[k];
    if (s.imag() < 0) s = std::conj(s);
    if (s.real() < o.re_min - 10 || s.imag() > 1.5 * o.im_max) continue;
    if (!RefineRoot(sys, s, o)) continue;
    if (s.imag() < 0) s = std::conj(s);
    if (std::abs(s.imag()) < 1e-9 * (1.0 + std::abs(s))) s = {s.real(), 0.0};
    if (s.real() < o.re_min || s.imag() > o.im_max) continue;
    ++out.refined;
    const bool duplicate = std::any_of(found.begin(), found.end(), [&](Complex r) {
      return std::abs(r - s) <= 1e-7 * (1.0 + std::abs(s));
    });
    if (!duplicate) found.push_back(s);
  }
  SortRightmostFirst(found);
  for (Complex s : found) out.roots.push_back({s, Residual(sys, s)});
  out.spectral_abscissa = found.empty() ? -std::numeric_limits<double>::infinity() : found.front().real();
  SetVerdict(out);
  return out;
}

void SortRightmostFirst(std::vector<Complex>& roots) {
  std::sort(roots.begin(), roots.end(), [](Complex a, Complex b) {
    return a.real() != b.real() ? a.real() > b.real() : a.imag() < b.imag();
  });
}

void SetVerdict(Spectrum& out) {
  out.stable = out.spectral_abscissa < 0 && out.essential_abscissa < -kEssentialOnAxis;  // NaN: not stable
  const bool on_axis = std::abs(out.essential_abscissa) <= kEssentialOnAxis;
  out.verdict = out.stable ? Spectrum::Verdict::kStable
                : on_axis && out.spectral_abscissa <= kEssentialOnAxis ? Spectrum::Verdict::kMarginal
                                                                       : Spectrum::Verdict::kUnstable;
}

double EssentialAbscissa(const LinearDelaySystem& sys, const SpectrumOptions& o, std::vector<Complex>& chain_starts) {
  double essential = -std::numeric_limits<double>::infinity();
  if (!sys.IsNeutral()) return essential;
  // Channels the difference operator does not couple (the torsional and axial waves of the coupled model) are
  // separate blocks: its roots are the blocks' roots, each block's abscissa exact when its delays are commensurate.
  for (const std::vector<NeutralTerm>& block : DecoupledBlocks(DifferenceOperator(sys))) {
    const double abscissa = BlockEssentialAbscissa(block, o, chain_starts);  // NaN (not computed) prevails
    if (std::isnan(abscissa) || abscissa > essential) essential = abscissa;
    if (std::isnan(abscissa)) break;
  }
  return essential;
}

}  // namespace drillwave::analysis
