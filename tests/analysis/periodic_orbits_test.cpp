// Periodic orbits by shooting, their Floquet multipliers and their continuation, on systems with closed forms.
#include "drillwave/analysis/periodic_orbits.hpp"
#include "drillwave/core/constants.hpp"

#include <cmath>
#include <memory>

#include <gtest/gtest.h>

namespace drillwave::analysis {
namespace {

using Eigen::VectorXd;

// Hopf normal form with a quintic term and a decaying third state:
//   r' = r (mu + a r^2 - r^4),  theta' = omega,  z' = -lambda z.
// a = -1 and no quintic term... here a and the quintic weight b are fields: r' = r (mu + a r^2 - b r^4).
// Cycles: mu + a r^2 - b r^4 = 0, period 2 pi / omega, multipliers 1, exp(T d(r')/dr), exp(-lambda T).
class NormalForm : public PiecewiseSmoothField {
 public:
  NormalForm(double mu, double a, double b, double omega, double lambda)
      : mu_(mu), a_(a), b_(b), omega_(omega), lambda_(lambda) {}
  int Dimension() const override { return 3; }
  VectorXd Derivatives(int, const VectorXd& x) const override {
    const double r2 = x[0] * x[0] + x[1] * x[1], g = mu_ + a_ * r2 - b_ * r2 * r2;
    VectorXd f(3);
    f << g * x[0] - omega_ * x[1], g * x[1] + omega_ * x[0], -lambda_ * x[2];
    return f;
  }
  std::vector<VectorXd> Equilibria() const override { return {VectorXd::Zero(3)}; }

 private:
  double mu_, a_, b_, omega_, lambda_;
};

TEST(PeriodicOrbits, HopfNormalFormCycleAndMultipliersAreTheClosedForm) {
  const double mu = 0.3, omega = 2.0, lambda = 0.7;
  const NormalForm f(mu, -1, 0, omega, lambda);  // supercritical: r = sqrt(mu)
  VectorXd guess(3);
  guess << 0.8, 0.1, 0.2;
  const PeriodicOrbit orbit = FindPeriodicOrbit(f, guess, 3.0);
  const double period = 2 * kPi / omega;
  EXPECT_NEAR(orbit.period, period, 1e-9);
  EXPECT_NEAR(std::hypot(orbit.x0[0], orbit.x0[1]), std::sqrt(mu), 1e-9);
  EXPECT_NEAR(orbit.x0[2], 0, 1e-9);
  // d(r')/dr at r^2 = mu: mu - 3 mu = -2 mu.
  ASSERT_EQ(orbit.multipliers.size(), 3);
  EXPECT_NEAR(orbit.multipliers[0].real(), 1.0, 1e-8);
  std::vector<double> rest = {orbit.multipliers[1].real(), orbit.multipliers[2].real()};
  std::sort(rest.begin(), rest.end());
  std::vector<double> exact = {std::exp(-2 * mu * period), std::exp(-lambda * period)};
  std::sort(exact.begin(), exact.end());
  EXPECT_NEAR(rest[0], exact[0], 1e-8);
  EXPECT_NEAR(rest[1], exact[1], 1e-8);
  EXPECT_TRUE(orbit.stable);
  EXPECT_NEAR(orbit.max_nontrivial, exact[1], 1e-8);
  // The variational monodromy against central differences of the flow.
  const Eigen::MatrixXd fd = FiniteDifferenceMonodromy(f, orbit.x0, orbit.period, 1e-5);
  EXPECT_LT((fd - orbit.monodromy).lpNorm<Eigen::Infinity>(), 1e-7);
}

TEST(PeriodicOrbits, SubcriticalHopfBranchFoldsWhereTheClosedFormDoes) {
  // r' = r (mu + r^2 - r^4): subcritical Hopf at mu = 0; unstable cycles r^2 = (1 - sqrt(1 + 4 mu)) / 2 for
  // mu in (-1/4, 0), fold at mu = -1/4 (r^2 = 1/2), stable cycles r^2 = (1 + sqrt(1 + 4 mu)) / 2 beyond.
  const double omega = 1.5;
  const FieldFamily family = [&](double mu) { return std::make_shared<NormalForm>(mu, 1, 1, omega, 1.0); };
  const EquilibriumBranches eq = ContinueEquilibria(family, {-0.5, -0.2, 0.1, 0.4});
  ASSERT_EQ(eq.hopf.size(), 1u);
  EXPECT_NEAR(eq.hopf[0].p, 0.0, 1e-8);
  EXPECT_NEAR(eq.hopf[0].omega, omega, 1e-6);
  EXPECT_TRUE(eq.points[1].stable);   // eigenvalues mu +- i omega, -1
  EXPECT_FALSE(eq.points[2].stable);
  ContinuationOptions o;
  o.p_min = -0.5, o.p_max = 0.3;
  o.p_scale = 0.1;
  o.initial_step = 0.02, o.max_step = 0.3;
  o.amplitude_component = 0;  // x: its maximum over the cycle is r
  const PeriodicBranch branch = ContinueFromHopf(family, eq.hopf[0], o);
  ASSERT_GT(branch.points.size(), 10u) << branch.end;
  ASSERT_EQ(branch.folds.size(), 1u) << branch.end;
  EXPECT_NEAR(branch.folds[0].p, -0.25, 1e-6);
  EXPECT_NEAR(branch.folds[0].amplitude_max, std::sqrt(0.5), 1e-5);
  EXPECT_NEAR(branch.folds[0].critical_multiplier, 1.0, 1e-4);
  int unstable = 0, stable = 0;
  for (const BranchPoint& b : branch.points) {
    const double r2 = b.orbit.x0.head(2).squaredNorm(), mu = b.p;
    const double g_prime = 2 * r2 - 4 * r2 * r2;  // r d/dr (mu + r^2 - r^4) on the cycle
    // Near the Hopf point a residual of newton_tol leaves mu uncertain by about newton_tol / (r T): checked away from it.
    if (r2 > 1e-2) {
      EXPECT_NEAR(mu + r2 - r2 * r2, 0, 1e-7) << "mu = " << mu;
    }
    EXPECT_NEAR(b.orbit.period, 2 * kPi / omega, 1e-8);
    if (std::abs(g_prime) > 1e-2) {
      EXPECT_EQ(b.orbit.stable, g_prime < 0) << "mu = " << mu << ", r^2 = " << r2;
      (b.orbit.stable ? stable : unstable)++;
    }
  }
  EXPECT_GT(stable, 3);
  EXPECT_GT(unstable, 3);
}

// Mass on a belt with Coulomb friction (static F_s > kinetic F_c): m x'' + k x = F_c sign(v_b - x'), sticking to the
// belt (x' = v_b) while |k x| <= F_s. Mode 0 slipping (x' < v_b), mode 1 stuck.
class MassOnBelt : public PiecewiseSmoothField {
 public:
  MassOnBelt(double m, double k, double fc, double fs, double vb) : m_(m), k_(k), fc_(fc), fs_(fs), vb_(vb) {}
  int Dimension() const override { return 2; }
  VectorXd Derivatives(int mode, const VectorXd& x) const override {
    VectorXd f(2);
    if (mode == 1) f << vb_, 0;
    else f << x[1], (fc_ - k_ * x[0]) / m_;
    return f;
  }
  int ModeAt(const VectorXd& x) const override { return x[1] >= vb_ && k_ * x[0] <= fs_ ? 1 : 0; }
  int NumSwitches() const override { return 1; }
  double Switch(int mode, int, const VectorXd& x) const override { return mode == 1 ? fs_ - k_ * x[0] : vb_ - x[1]; }
  int ModeAfter(int mode, int, const VectorXd&) const override { return 1 - mode; }
  void Project(int mode, VectorXd& x) const override {
    if (mode == 1) x[1] = vb_;
  }

 private:
  double m_, k_, fc_, fs_, vb_;
};

TEST(PeriodicOrbits, StickSlipOnABeltHasTheClosedFormPeriodAndSaltationMonodromy) {
  const double m = 1.3, k = 2.0, fc = 1.0, fs = 2.0, vb = 0.5;
  const MassOnBelt f(m, k, fc, fs, vb);
  // Closed form: slip is harmonic about x_c = F_c / k from x_s = F_s / k (relative speed 0) to 2 x_c - x_s, then the
  // mass rides the belt back to x_s.
  const double w = std::sqrt(k / m), y0 = (fs - fc) / k, alpha = std::atan(vb / (w * y0));
  const double period = (kPi + 2 * alpha) / w + 2 * y0 / vb;
  const double amplitude = std::hypot(y0, vb / w);
  // A guess from a transient: the state of least speed after a few cycles (mid-slip).
  const FlowResult transient = Flow(f, VectorXd::Zero(2), 5 * period, false);
  VectorXd guess = transient.states.back();
  for (std::size_t i = transient.states.size() / 2; i < transient.states.size(); ++i)
    if (transient.states[i][1] < guess[1]) guess = transient.states[i];
  const PeriodicOrbit orbit = FindPeriodicOrbit(f, guess, 1.1 * period);
  EXPECT_NEAR(orbit.period, period, 1e-8);
  EXPECT_NEAR(std::hypot(orbit.x0[0] - fc / k, orbit.x0[1] / w), amplitude, 1e-8);  // on the slip ellipse
  EXPECT_EQ(orbit.switches, 2);
  // Multipliers: the trivial 1 and 0 (sticking forgets the speed).
  EXPECT_NEAR(std::abs(orbit.multipliers[0]), 1.0, 1e-6);  // Jacobians by central differences
  EXPECT_NEAR(std::abs(orbit.multipliers[1]), 0.0, 1e-6);
  // The saltation monodromy against central differences of the event-resolved flow.
  const Eigen::MatrixXd fd = FiniteDifferenceMonodromy(f, orbit.x0, orbit.period, 1e-6);
  EXPECT_LT((fd - orbit.monodromy).lpNorm<Eigen::Infinity>(), 1e-5) << "saltation:\n"
                                                                     << orbit.monodromy << "\nfd:\n"
                                                                     << fd;
}

}  // namespace
}  // namespace drillwave::analysis
