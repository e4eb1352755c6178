#include "drillwave/analysis/periodic_orbits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/validity.hpp"
#include "drillwave/integration/simulator.hpp"

namespace drillwave::analysis {

using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double FdStep(double v) { return 1e-7 * std::max(1.0, std::abs(v)); }

// The integrator's Process for a field with its sensitivity: state (x, Phi column-major). The mode is the only thing
// that changes; the saltation matrix maps Phi across every switch.
class OrbitProcess : public integration::WithoutHistory {
 public:
  using State = std::vector<double>;

  OrbitProcess(const PiecewiseSmoothField& field, int mode, bool sensitivity)
      : field_(field), n_(field.Dimension()), mode_(mode), sensitivity_(sensitivity) {}

  int Dimension() const { return n_ + (sensitivity_ ? n_ * n_ : 0); }
  int mode() const { return mode_; }
  int switches() const { return switches_; }

  void Derivatives(const State& s, State& ds, double) const {
    const VectorXd x = Eigen::Map<const VectorXd>(s.data(), n_);
    Eigen::Map<VectorXd>(ds.data(), n_) = field_.Derivatives(mode_, x);
    if (!sensitivity_) return;
    Eigen::Map<MatrixXd>(ds.data() + n_, n_, n_) =
        field_.Jacobian(mode_, x) * Eigen::Map<const MatrixXd>(s.data() + n_, n_, n_);
  }
  void BeginStep(double) {}
  int NumWitnesses() const { return field_.NumSwitches(); }
  double Witness(int k, double, const State& s) const {
    return field_.Switch(mode_, k, Eigen::Map<const VectorXd>(s.data(), n_));
  }
  bool OnEvent(int k, double, State& s) {
    VectorXd x = Eigen::Map<const VectorXd>(s.data(), n_);
    const int after = field_.ModeAfter(mode_, k, x);
    if (after == mode_) return false;
    if (sensitivity_) {
      const VectorXd f_minus = field_.Derivatives(mode_, x);
      const Eigen::RowVectorXd n = field_.SwitchGradient(mode_, k, x);
      const double rate = n.dot(f_minus);
      if (!(std::abs(rate) > 0))
        throw NumericalError("grazing switch: the flow is tangent to switching surface " + std::to_string(k) +
                                 " (no saltation matrix exists)",
                             0, s);
      field_.Project(after, x);
      const VectorXd f_plus = field_.Derivatives(after, x);
      const MatrixXd saltation = MatrixXd::Identity(n_, n_) + (f_plus - f_minus) * n / rate;
      Eigen::Map<MatrixXd> phi(s.data() + n_, n_, n_);
      phi = saltation * phi;
    } else {
      field_.Project(after, x);
    }
    Eigen::Map<VectorXd>(s.data(), n_) = x;
    mode_ = after;
    ++switches_;
    return true;
  }
  double NextBreakpoint() const { return kInf; }
  void OnBreakpoint(double) {}

 private:
  const PiecewiseSmoothField& field_;
  int n_;
  int mode_;
  bool sensitivity_;
  int switches_ = 0;
};

// Phase condition reference: the field's direction at x_ref.
VectorXd FieldAt(const PiecewiseSmoothField& f, const VectorXd& x) { return f.Derivatives(f.ModeAt(x), x); }

}  // namespace

MatrixXd PiecewiseSmoothField::Jacobian(int mode, const VectorXd& x) const {
  const int n = Dimension();
  MatrixXd j(n, n);
  VectorXd xp = x, xm = x;
  for (int c = 0; c < n; ++c) {
    const double h = FdStep(x[c]);
    xp[c] = x[c] + h, xm[c] = x[c] - h;
    j.col(c) = (Derivatives(mode, xp) - Derivatives(mode, xm)) / (2 * h);
    xp[c] = xm[c] = x[c];
  }
  return j;
}

Eigen::RowVectorXd PiecewiseSmoothField::SwitchGradient(int mode, int k, const VectorXd& x) const {
  const int n = Dimension();
  Eigen::RowVectorXd g(n);
  VectorXd xp = x, xm = x;
  for (int c = 0; c < n; ++c) {
    const double h = FdStep(x[c]);
    xp[c] = x[c] + h, xm[c] = x[c] - h;
    g[c] = (Switch(mode, k, xp) - Switch(mode, k, xm)) / (2 * h);
    xp[c] = xm[c] = x[c];
  }
  return g;
}

bool ShootingOptions::IsValid(std::string* error) const {
  return PositiveField(error, "abs_tol", abs_tol) && PositiveField(error, "rel_tol", rel_tol) &&
         PositiveField(error, "newton_tol", newton_tol) && WholeField(error, "max_newton", max_newton, 1) &&
         WholeField(error, "samples_per_period", samples_per_period, 1);
}

bool ContinuationOptions::IsValid(std::string* error) const {
  return OrderedFields(error, "p_min", p_min, "p_max", p_max, "the parameter range must end after it begins") &&
         PositiveField(error, "min_step", min_step) &&
         OrderedFields(error, "min_step", min_step, "initial_step", initial_step,
                       "the first step must lie within the step range", true) &&
         OrderedFields(error, "initial_step", initial_step, "max_step", max_step,
                       "the first step must lie within the step range", true) &&
         FiniteField(error, "max_step", max_step) && PositiveField(error, "p_scale", p_scale) &&
         WholeField(error, "max_points", max_points, 1) && PositiveField(error, "hopf_amplitude", hopf_amplitude) &&
         NonNegativeField(error, "end_amplitude", end_amplitude) &&
         WholeField(error, "amplitude_component", amplitude_component, -1) && PositiveField(error, "dp_fd", dp_fd) &&
         NestedValid(error, "shooting", shooting.IsValid(error));
}

FlowResult Flow(const PiecewiseSmoothField& field, const VectorXd& x0, double duration, bool sensitivity,
                const ShootingOptions& options) {
  ThrowIfInvalid(options);
  const int n = field.Dimension();
  VectorXd start = x0;
  const int mode = field.ModeAt(start);
  field.Project(mode, start);
  OrbitProcess process(field, mode, sensitivity);
  std::vector<double> s(process.Dimension(), 0.0);
  Eigen::Map<VectorXd>(s.data(), n) = start;
  if (sensitivity) Eigen::Map<MatrixXd>(s.data() + n, n, n).setIdentity();

  integration::IntegratorOptions io;
  io.abs_tol = options.abs_tol;
  io.rel_tol = options.rel_tol;
  io.control_history_error = false;  // no delays: nothing reads the stored interpolant
  io.initial_step = std::min(1e-3, duration / 100);
  io.max_steps = 5000000;

  FlowResult result;
  result.time_s.push_back(0);
  result.states.push_back(start);
  const double interval = duration / options.samples_per_period;
  const auto observer = integration::SampleEvery(interval, [&](double t, const std::vector<double>& state) {
    result.time_s.push_back(t);
    result.states.push_back(Eigen::Map<const VectorXd>(state.data(), n));
  });
  integration::Simulator<OrbitProcess> sim(process, io);
  const std::vector<double> end = sim.Integrate(0.0, s, duration, observer);
  result.x = Eigen::Map<const VectorXd>(end.data(), n);
  result.mode = process.mode();
  result.switches = process.switches();
  if (sensitivity) result.sensitivity = Eigen::Map<const MatrixXd>(end.data() + n, n, n);
  return result;
}

void ClassifyMultipliers(PeriodicOrbit& orbit) {
  Eigen::EigenSolver<MatrixXd> es(orbit.monodromy, false);
  const Eigen::VectorXcd mu = es.eigenvalues();
  std::vector<std::complex<double>> sorted(mu.data(), mu.data() + mu.size());
  std::sort(sorted.begin(), sorted.end(),
            [](const auto& a, const auto& b) { return std::abs(a) > std::abs(b); });
  orbit.multipliers = Eigen::Map<Eigen::VectorXcd>(sorted.data(), sorted.size());
  std::size_t trivial = 0;
  for (std::size_t i = 1; i < sorted.size(); ++i)
    if (std::abs(sorted[i] - 1.0) < std::abs(sorted[trivial] - 1.0)) trivial = i;
  orbit.max_nontrivial = 0;
  for (std::size_t i = 0; i < sorted.size(); ++i)
    if (i != trivial) orbit.max_nontrivial = std::max(orbit.max_nontrivial, std::abs(sorted[i]));
  orbit.stable = orbit.max_nontrivial < 1;
}

namespace {

// The orbit through x0 with period T from a flow over one period with sensitivity.
PeriodicOrbit OrbitFromFlow(const VectorXd& x0, double period, FlowResult&& flow, int iterations) {
  PeriodicOrbit orbit;
  orbit.x0 = x0;
  orbit.period = period;
  orbit.residual = (flow.x - x0).lpNorm<Eigen::Infinity>();
  orbit.monodromy = std::move(flow.sensitivity);
  orbit.switches = flow.switches;
  orbit.time_s = std::move(flow.time_s);
  orbit.states = std::move(flow.states);
  orbit.newton_iterations = iterations;
  ClassifyMultipliers(orbit);
  return orbit;
}

}  // namespace

PeriodicOrbit FindPeriodicOrbit(const PiecewiseSmoothField& field, const VectorXd& guess, double period_guess,
                                const ShootingOptions& options) {
  ThrowIfInvalid(options);
  const int n = field.Dimension();
  if (guess.size() != n || !(period_guess > 0))
    throw std::invalid_argument("FindPeriodicOrbit: guess of the wrong size or period not > 0");
  const VectorXd x_ref = guess, f_ref = FieldAt(field, guess);
  VectorXd x = guess;
  double period = period_guess;
  for (int it = 0; it <= options.max_newton; ++it) {
    FlowResult flow = Flow(field, x, period, true, options);
    VectorXd r(n + 1);
    r.head(n) = flow.x - x;
    r[n] = f_ref.dot(x - x_ref);
    if (r.lpNorm<Eigen::Infinity>() < options.newton_tol) return OrbitFromFlow(x, period, std::move(flow), it);
    MatrixXd jac = MatrixXd::Zero(n + 1, n + 1);
    jac.topLeftCorner(n, n) = flow.sensitivity - MatrixXd::Identity(n, n);
    jac.block(0, n, n, 1) = field.Derivatives(flow.mode, flow.x);
    jac.block(n, 0, 1, n) = f_ref.transpose();
    const VectorXd delta = jac.fullPivLu().solve(-r);
    x += delta.head(n);
    period += delta[n];
    if (!(period > 0)) throw NumericalError("shooting: the period became negative", 0, {x.data(), x.data() + n});
  }
  throw NumericalError("shooting: Newton did not converge in " + std::to_string(options.max_newton) + " iterations",
                       period, {x.data(), x.data() + n});
}

MatrixXd FiniteDifferenceMonodromy(const PiecewiseSmoothField& field, const VectorXd& x0, double period, double h,
                                   const ShootingOptions& options) {
  ThrowIfInvalid(options);
  const int n = field.Dimension();
  MatrixXd m(n, n);
  for (int c = 0; c < n; ++c) {
    VectorXd xp = x0, xm = x0;
    xp[c] += h, xm[c] -= h;
    m.col(c) = (Flow(field, xp, period, false, options).x - Flow(field, xm, period, false, options).x) / (2 * h);
  }
  return m;
}

// ---- Equilibria ----------------------------------------------------------------------------------------------

namespace {

EquilibriumPoint MakeEquilibrium(const PiecewiseSmoothField& f, double p, const VectorXd& x) {
  EquilibriumPoint e;
  e.p = p;
  e.x = x;
  Eigen::EigenSolver<MatrixXd> es(f.Jacobian(f.ModeAt(x), x), false);
  std::vector<std::complex<double>> ev(es.eigenvalues().data(), es.eigenvalues().data() + x.size());
  std::sort(ev.begin(), ev.end(), [](const auto& a, const auto& b) { return a.real() > b.real(); });
  e.eigenvalues = Eigen::Map<Eigen::VectorXcd>(ev.data(), ev.size());
  e.stable = ev.front().real() < 0;
  return e;
}

// Largest real part among the complex pairs (the Hopf test function); -inf without a pair.
double ComplexAbscissa(const EquilibriumPoint& e) {
  double best = -kInf;
  for (const auto& l : e.eigenvalues)
    if (std::abs(l.imag()) > 1e-9 * std::max(1.0, std::abs(l))) best = std::max(best, l.real());
  return best;
}

// The equilibrium of family(p) closest to x (nullopt if it has none).
std::optional<EquilibriumPoint> NearestEquilibrium(const FieldFamily& family, double p, const VectorXd& x) {
  const auto f = family(p);
  std::optional<EquilibriumPoint> best;
  double dist = kInf;
  for (const VectorXd& e : f->Equilibria())
    if (e.size() == x.size() && (e - x).norm() < dist) dist = (e - x).norm(), best = MakeEquilibrium(*f, p, e);
  return best;
}

}  // namespace

EquilibriumBranches ContinueEquilibria(const FieldFamily& family, const std::vector<double>& grid, double p_tol) {
  EquilibriumBranches out;
  std::vector<std::optional<EquilibriumPoint>> previous;
  for (double p : grid) {
    const auto f = family(p);
    const std::vector<VectorXd> eqs = f->Equilibria();
    std::vector<std::optional<EquilibriumPoint>> current(eqs.size());
    for (std::size_t b = 0; b < eqs.size(); ++b) {
      current[b] = MakeEquilibrium(*f, p, eqs[b]);
      out.points.push_back(*current[b]);
      if (b >= previous.size() || !previous[b]) continue;
      EquilibriumPoint lo = *previous[b], hi = *current[b];
      const double a_lo = ComplexAbscissa(lo), a_hi = ComplexAbscissa(hi);
      if (!std::isfinite(a_lo) || !std::isfinite(a_hi) || (a_lo < 0) == (a_hi < 0)) continue;
      // Bisection on the sign of the pair's real part.
      bool lost = false;
      while (std::abs(hi.p - lo.p) > p_tol) {
        const double mid = 0.5 * (lo.p + hi.p);
        const auto m = NearestEquilibrium(family, mid, 0.5 * (lo.x + hi.x));
        if (!m || !std::isfinite(ComplexAbscissa(*m))) { lost = true; break; }
        ((ComplexAbscissa(*m) < 0) == (a_lo < 0) ? lo : hi) = *m;
      }
      if (lost) continue;
      const double p_h = 0.5 * (lo.p + hi.p);
      const auto ff = family(p_h);
      const auto m = NearestEquilibrium(family, p_h, lo.x);
      Eigen::EigenSolver<MatrixXd> es(ff->Jacobian(ff->ModeAt(m->x), m->x), true);
      int k = -1;
      for (int i = 0; i < es.eigenvalues().size(); ++i)
        if (es.eigenvalues()[i].imag() > 0 && (k < 0 || std::abs(es.eigenvalues()[i].real()) <
                                                            std::abs(es.eigenvalues()[k].real())))
          k = i;
      if (k < 0) continue;
      out.hopf.push_back({p_h, m->x, es.eigenvalues()[k].imag(), es.eigenvectors().col(k)});
    }
    previous = std::move(current);
  }
  return out;
}

// ---- Pseudo-arclength continuation of periodic orbits ----------------------------------------------------------

namespace {

// Unknowns z = (x0, T, q) with q = p / p_scale, so that the arclength norm weighs the parameter by its scale.
struct Continuation {
  const FieldFamily& family;
  const ContinuationOptions& o;
  int n;

  double P(const VectorXd& z) const { return z[n + 1] * o.p_scale; }

  // The orbit's residual blocks and their Jacobian in z: rows x(T) - x0 (n) and the phase condition (1).
  struct Linear {
    VectorXd r;
    MatrixXd a;  // (n + 1) x (n + 2)
    FlowResult flow;
  };
  Linear Linearize(const VectorXd& z, const VectorXd& x_ref, const VectorXd& f_ref) const {
    const double p = P(z), period = z[n];
    const VectorXd x = z.head(n);
    const auto field = family(p);
    Linear l;
    l.flow = Flow(*field, x, period, true, o.shooting);
    l.r.resize(n + 1);
    l.r.head(n) = l.flow.x - x;
    l.r[n] = f_ref.dot(x - x_ref);
    l.a = MatrixXd::Zero(n + 1, n + 2);
    l.a.topLeftCorner(n, n) = l.flow.sensitivity - MatrixXd::Identity(n, n);
    l.a.block(0, n, n, 1) = field->Derivatives(l.flow.mode, l.flow.x);
    const double dp = o.dp_fd * std::max(1.0, std::abs(p));
    const VectorXd shifted = Flow(*family(p + dp), x, period, false, o.shooting).x;
    l.a.block(0, n + 1, n, 1) = (shifted - l.flow.x) / dp * o.p_scale;
    l.a.block(n, 0, 1, n) = f_ref.transpose();
    return l;
  }

  // Corrector: Newton on the orbit equations plus tangent . (z - z_pred) = 0. Returns false if it does not converge.
  bool Correct(VectorXd& z, const VectorXd& tangent, const VectorXd& x_ref, const VectorXd& f_ref, int& iterations) const {
    const VectorXd z_pred = z;
    for (iterations = 0; iterations < 10; ++iterations) {
      Linear l;
      try {
        l = Linearize(z, x_ref, f_ref);
      } catch (const NumericalError&) {
        return false;
      }
      VectorXd r(n + 2);
      r.head(n + 1) = l.r;
      r[n + 1] = tangent.dot(z - z_pred);
      if (r.lpNorm<Eigen::Infinity>() < o.shooting.newton_tol) return true;
      MatrixXd j(n + 2, n + 2);
      j.topRows(n + 1) = l.a;
      j.row(n + 1) = tangent.transpose();
      const VectorXd delta = j.fullPivLu().solve(-r);
      if (!delta.allFinite()) return false;
      z += delta;
      if (!(z[n] > 0)) return false;
    }
    return false;
  }

  // The converged point moved to the sample where the amplitude component peaks (always inside a slip phase of a
  // stick-slip cycle, so the phase condition never sits in a sticking mode), with its orbit and unit tangent
  // oriented along the secant from `previous` (a point moved to its peak in the same way, so that the two are
  // comparable).
  struct Point {
    VectorXd z, tangent;
    BranchPoint point;
  };
  Point Finish(const VectorXd& z, const VectorXd& previous) const {
    const int c = o.amplitude_component < 0 ? n - 1 : o.amplitude_component;
    const double p = P(z), period = z[n];
    const auto field = family(p);
    const FlowResult once = Flow(*field, z.head(n), period, false, o.shooting);
    std::size_t peak = 0;
    double lo = kInf, hi = -kInf;
    for (std::size_t i = 0; i < once.states.size(); ++i) {
      const double v = once.states[i][c];
      lo = std::min(lo, v);
      if (v > hi) hi = v, peak = i;
    }
    Point out;
    out.z = z;
    out.z.head(n) = once.states[peak];
    const VectorXd x_ref = out.z.head(n), f_ref = FieldAt(*field, x_ref);
    Linear l = Linearize(out.z, x_ref, f_ref);
    MatrixXd j(n + 2, n + 2);
    j.topRows(n + 1) = l.a;
    const VectorXd direction = out.z - previous;
    j.row(n + 1) = direction.transpose();
    VectorXd rhs = VectorXd::Zero(n + 2);
    rhs[n + 1] = 1;
    out.tangent = j.fullPivLu().solve(rhs).normalized();
    if (out.tangent.dot(direction) < 0) out.tangent = -out.tangent;
    out.point.p = p;
    out.point.amplitude_min = lo;
    out.point.amplitude_max = hi;
    out.point.dp_ds = out.tangent[n + 1];
    out.point.orbit = OrbitFromFlow(x_ref, period, std::move(l.flow), 0);
    return out;
  }
};

double Range(const BranchPoint& b) { return b.amplitude_max - b.amplitude_min; }

}  // namespace

PeriodicBranch ContinueFromHopf(const FieldFamily& family, const HopfPoint& hopf, const ContinuationOptions& o) {
  ThrowIfInvalid(o);
  const int n = static_cast<int>(hopf.x.size());
  if (o.amplitude_component >= n)
    throw ParameterError("amplitude_component", "expected -1 (the last state) or a state in [0, " +
                                                    std::to_string(n - 1) + "], got " +
                                                    std::to_string(o.amplitude_component));
  Continuation cont{family, o, n};
  PeriodicBranch branch;

  // First point: a small circle in the critical eigenplane, at the Hopf parameter and period.
  VectorXd w = hopf.eigenvector.real();
  if (w.norm() < 0.3 * hopf.eigenvector.norm()) w = hopf.eigenvector.imag();
  w.normalize();
  VectorXd z(n + 2), tangent = VectorXd::Zero(n + 2);
  z.head(n) = hopf.x + o.hopf_amplitude * w;
  z[n] = 2 * kPi / hopf.omega;
  z[n + 1] = hopf.p / o.p_scale;
  tangent.head(n) = w;
  {
    const auto field = family(hopf.p);
    const VectorXd x_ref = z.head(n), f_ref = FieldAt(*field, x_ref);
    int its = 0;
    if (!cont.Correct(z, tangent, x_ref, f_ref, its)) {
      branch.end = "no periodic orbit found next to the Hopf point";
      return branch;
    }
  }
  VectorXd z_hopf(n + 2);
  z_hopf << hopf.x, 2 * kPi / hopf.omega, hopf.p / o.p_scale;
  Continuation::Point current = cont.Finish(z, z_hopf);
  branch.points.push_back(current.point);

  double step = o.initial_step, max_range = Range(current.point);
  const double first_period = current.point.orbit.period;
  while (static_cast<int>(branch.points.size()) < o.max_points) {
    Continuation::Point next;
    int its = 0;
    bool ok = false;
    while (!ok) {
      VectorXd trial = current.z + step * current.tangent;
      const auto field = family(cont.P(current.z));
      const VectorXd x_ref = current.z.head(n), f_ref = FieldAt(*field, x_ref);
      ok = cont.Correct(trial, current.tangent, x_ref, f_ref, its);
      if (ok) {
        next = cont.Finish(trial, current.z);
        // A corrector that lands on an equilibrium (x(T) = x0 for any T) has collapsed, not followed the branch.
        ok = Range(next.point) >= 0.3 * Range(current.point) || Range(current.point) < o.end_amplitude;
      }
      if (!ok) {
        step *= 0.5;
        if (step < o.min_step) {
          branch.end = "the corrector failed down to the smallest step at p = " + Significant(current.point.p, 8);
          return branch;
        }
      }
    }
    // Fold: dp/ds changes sign. Secant on dp/ds over the step from `current`.
    if ((current.point.dp_ds > 0) != (next.point.dp_ds > 0)) {
      double s_lo = 0, s_hi = step, d_lo = current.point.dp_ds, d_hi = next.point.dp_ds;
      Continuation::Point fold = next;
      for (int k = 0; k < 8 && std::abs(fold.point.dp_ds) > 1e-7; ++k) {
        const double s = s_lo + (s_hi - s_lo) * d_lo / (d_lo - d_hi);
        VectorXd trial = current.z + s * current.tangent;
        const auto field = family(cont.P(current.z));
        const VectorXd x_ref = current.z.head(n), f_ref = FieldAt(*field, x_ref);
        int fits = 0;
        if (!cont.Correct(trial, current.tangent, x_ref, f_ref, fits)) break;
        fold = cont.Finish(trial, current.z);
        if ((fold.point.dp_ds > 0) == (d_lo > 0)) s_lo = s, d_lo = fold.point.dp_ds;
        else s_hi = s, d_hi = fold.point.dp_ds;
      }
      // Through a Hopf point the orbits shrink to the equilibrium and p(s) turns there like at a fold; the secant
      // then locates the Hopf point.
      if (Range(fold.point) < 0.05 * max_range) {
        branch.points.push_back(fold.point);
        branch.end = "reached the equilibrium at a Hopf point, p = " + Significant(fold.point.p, 10);
        return branch;
      }
      FoldPoint f;
      f.p = fold.point.p;
      f.period = fold.point.orbit.period;
      f.amplitude_max = fold.point.amplitude_max;
      f.amplitude_min = fold.point.amplitude_min;
      // The nontrivial multiplier nearest +1 (the trivial one is the nearest of all).
      std::vector<double> dist;
      for (const auto& mu : fold.point.orbit.multipliers) dist.push_back(std::abs(mu - 1.0));
      std::vector<std::size_t> order(dist.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return dist[a] < dist[b]; });
      f.critical_multiplier = order.size() > 1 ? fold.point.orbit.multipliers[order[1]].real() : 1.0;
      branch.folds.push_back(f);
    }
    current = next;
    branch.points.push_back(current.point);
    max_range = std::max(max_range, Range(current.point));
    if (o.progress) o.progress(static_cast<int>(branch.points.size()), current.point.p, current.point.orbit.period);
    if (its <= 3) step = std::min(o.max_step, step * 1.5);
    else if (its >= 6) step *= 0.7;

    const double p = current.point.p;
    if (p < o.p_min || p > o.p_max) {
      branch.end = "left the parameter range at p = " + Significant(p, 8);
      return branch;
    }
    if (Range(current.point) < o.end_amplitude && max_range > 10 * o.end_amplitude) {
      branch.end = "reached the equilibrium at a Hopf point, p = " + Significant(p, 10);
      return branch;
    }
    if (current.point.orbit.period > 100 * first_period) {
      branch.end = "the period grows without bound (a homoclinic orbit?) at p = " + Significant(p, 8);
      return branch;
    }
  }
  branch.end = "reached the maximum number of points (" + std::to_string(o.max_points) + ")";
  return branch;
}

}  // namespace drillwave::analysis
