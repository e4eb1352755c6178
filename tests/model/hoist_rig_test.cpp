// The two-mass hoisting rig (chapter eq. 2.22, model::HoistRig) with the string removed (its pull held at the steady
// hook force): its natural frequencies against the generalized eigenproblem K u = w^2 M u of the two masses, and its
// rates against that same undamped system.
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "drillwave/model/hoist_rig.hpp"

namespace drillwave::model {
namespace {

HoistRig Rig() {
  HoistRig rig;  // orders of magnitude of a land rig: a 60 t derrick, 15 t of blocks, stiff ground, softer cables
  rig.derrick_mass = 60000, rig.block_mass = 15000;
  rig.ground_stiffness = 2e8, rig.cable_stiffness = 3e7;
  return rig;
}
constexpr double kTopDriveMass = 30000;

// Eigenvalues of M^-1 K for the masses (M1, M2 + M_td) on k01 (to the ground) and k12 (between them), ascending.
std::array<double, 2> EigenFrequencies(const HoistRig& rig) {
  Eigen::Matrix2d k, m;
  k << rig.ground_stiffness + rig.cable_stiffness, -rig.cable_stiffness, -rig.cable_stiffness, rig.cable_stiffness;
  m << rig.derrick_mass, 0, 0, rig.block_mass + kTopDriveMass;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> solver(k, m);
  return {std::sqrt(solver.eigenvalues()(0)), std::sqrt(solver.eigenvalues()(1))};
}

TEST(HoistRig, NaturalFrequenciesAreTheTwoMassEigenvalues) {
  const HoistRig rig = Rig();
  const auto closed = rig.NaturalFrequencies(kTopDriveMass), eigen = EigenFrequencies(rig);
  EXPECT_NEAR(closed[0], eigen[0], 1e-12 * eigen[0]);
  EXPECT_NEAR(closed[1], eigen[1], 1e-12 * eigen[1]);
  // A cable much softer than the ground: the block swings on the cable alone, sqrt(k12 / (M2 + M_td)).
  HoistRig soft = rig;
  soft.ground_stiffness = 1e14;
  const double swing = std::sqrt(rig.cable_stiffness / (rig.block_mass + kTopDriveMass));
  EXPECT_NEAR(soft.NaturalFrequencies(kTopDriveMass)[0], swing, 1e-5 * swing);
}

// The rates (y1, y1', delta, v - V0) are linear: their Jacobian, column by column, has the eigenvalues +-i w1, +-i w2
// without damping, and with damping the real parts are negative.
std::vector<std::complex<double>> JacobianEigenvalues(const HoistRig& rig) {
  const double rop = 0.03, hook = 4e5;  // steady descent and hook force: the string's pull holds H0
  Eigen::Matrix4d jac;
  for (int c = 0; c < 4; ++c) {
    HoistRig::State s{0, 0, 0};
    double v = rop;
    if (c < 3) s[c] = 1;
    else v += 1;
    const auto r = rig.Rates(s, v, rop, 0.0, false);
    const double a = rig.TopAcceleration(s, hook, v, rop, hook, kTopDriveMass);
    jac.col(c) << r[0], r[1], r[2], a;
  }
  Eigen::EigenSolver<Eigen::Matrix4d> solver(jac);
  std::vector<std::complex<double>> values(solver.eigenvalues().data(), solver.eigenvalues().data() + 4);
  std::sort(values.begin(), values.end(), [](auto a, auto b) { return a.imag() < b.imag(); });
  return values;
}

TEST(HoistRig, RatesOscillateAtTheNaturalFrequencies) {
  HoistRig rig = Rig();
  const auto w = EigenFrequencies(rig);
  const auto values = JacobianEigenvalues(rig);  // -w2, -w1, w1, w2
  EXPECT_NEAR(values[2].imag(), w[0], 1e-9 * w[0]);
  EXPECT_NEAR(values[3].imag(), w[1], 1e-9 * w[1]);
  for (const auto& v : values) EXPECT_NEAR(v.real(), 0.0, 1e-9 * w[1]);
  rig.derrick_damping = 1e5, rig.block_damping = 2e4;
  for (const auto& v : JacobianEigenvalues(rig)) EXPECT_LT(v.real(), 0.0);
}

// A lasting change of the cable tension u_F moves the derrick by du / k01 (up for more tension) and leaves the
// cable's stretch: the static solution of the rates.
TEST(HoistRig, TensionChangeMovesTheDerrickStatically) {
  HoistRig rig = Rig();
  rig.tension_change = Schedule(5e4);
  const HoistRig::State s{-5e4 / rig.ground_stiffness, 0, 0};
  const auto r = rig.Rates(s, 0.03, 0.03, 1.0, false);
  EXPECT_NEAR(r[1], 0.0, 1e-12);
  EXPECT_EQ(r[2], 0.0);
}

}  // namespace
}  // namespace drillwave::model
