// The wear flats' contact law (bitrock/contact_law.hpp): each friction function F against its closed form, its limits
// at r -> 0 and r -> inf and its slope (the linearization's) against finite differences; eq. 2.33's cutting torque;
// the regularized law tending to the sign as eps -> 0; and the RGD law's forces and steady torque with each.
#include "drillwave/bitrock/contact_law.hpp"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "drillwave/bitrock/rgd.hpp"
#include "drillwave/core/constants.hpp"

namespace drillwave::bitrock {
namespace {

ContactLaw Regularized(double alpha, double eps, CuttingTorque cutting = CuttingTorque::kRgd) {
  return ContactLaw(FrictionLaw(SqrtRegularized{1.0, alpha, eps}), cutting);
}
ContactLaw Hump(double beta, double gamma1, double gamma2, CuttingTorque cutting = CuttingTorque::kRgd) {
  return ContactLaw(FrictionLaw(TanhHump{1.0, beta, gamma1, gamma2}), cutting);
}
ContactLaw PrintedHump(double beta, double gamma1, double gamma2) {
  return ContactLaw(FrictionLaw(TanhHumpPrinted{{1.0, beta, gamma1, gamma2}}), CuttingTorque::kRgd);
}

// Central difference of f at r, step h.
template <class Fn>
double Derivative(const Fn& f, double r, double h = 1e-5) {
  return (f(r + h) - f(r - h)) / (2 * h);
}

// The slope against central differences of F at r > 0, to `tol` relative to the slope's scale `scale`.
void ExpectSlopeIsTheDerivative(const ContactLaw& law, double r, double scale) {
  EXPECT_NEAR(law.Slope(r), Derivative([&](double x) { return law.F(x); }, r), 1e-8 * scale) << "r = " << r;
  EXPECT_EQ(law.Slope(-r), law.Slope(r)) << "r = " << r;  // F and F' of |w|
}

TEST(ContactLaw, SetValuedDefaultIsRgdsSign) {
  const ContactLaw rgd;
  EXPECT_FALSE(rgd.has_function());
  for (double w : {-3.0, 1e-9, 6.0}) {
    EXPECT_EQ(rgd.F(w), 1.0);
    EXPECT_EQ(rgd.Slope(w), 0.0);
    EXPECT_EQ(rgd.CutTorque(1234.5, w), 1234.5);  // RGD's cutting torque, untouched
  }
  EXPECT_EQ(rgd.AtRest(), 1.0);
  EXPECT_EQ(rgd.CutTorqueAtRest(1234.5), 1234.5);
  EXPECT_EQ(rgd.CutTorqueSlope(1234.5, 6.0), 0.0);
}

// Eq. 2.29: F(r) = alpha r / sqrt(r^2 + eps^2); F ~ (alpha / eps) r at rest, alpha - alpha eps^2 / (2 r^2) far from
// it; F'(r) = alpha eps^2 / (r^2 + eps^2)^(3/2).
TEST(ContactLaw, RegularizedIsItsClosedFormWithItsLimitsAndSlope) {
  const double alpha = 1.2, eps = 0.1;
  const ContactLaw law = Regularized(alpha, eps);
  for (double r : {0.01, 0.1, 0.7, 6.283185307}) {
    EXPECT_NEAR(law.F(r), alpha * r / std::sqrt(r * r + eps * eps), 1e-15) << r;
    EXPECT_NEAR(law.Slope(r), alpha * eps * eps / std::pow(r * r + eps * eps, 1.5), 1e-13) << r;
    ExpectSlopeIsTheDerivative(law, r, alpha / eps);
  }
  EXPECT_EQ(law.F(0.0), 0.0);
  EXPECT_EQ(law.AtRest(), 0.0);
  EXPECT_DOUBLE_EQ(law.Slope(0.0), alpha / eps);
  const double small = 1e-4 * eps;  // r -> 0: F / r -> alpha / eps, relative error r^2 / (2 eps^2)
  EXPECT_NEAR(law.F(small) / small, alpha / eps, 1e-8 * alpha / eps);
  const double large = 1e4 * eps;  // r -> inf: F -> alpha, short by alpha eps^2 / (2 r^2)
  EXPECT_NEAR(alpha - law.F(large), alpha * eps * eps / (2 * large * large), 1e-15);
  EXPECT_EQ(law.F(-0.7), law.F(0.7));
}

// Eq. 2.30 with gamma1 r in the numerator: F(0) = 0, F'(0) = beta (1 + gamma1), F -> beta as r -> inf, and a hump
// (the Stribeck-like fall) above r = 1 / sqrt(gamma2) when gamma1 is large enough.
TEST(ContactLaw, TanhHumpIsItsClosedFormWithItsLimitsAndSlope) {
  const double beta = 0.9, gamma1 = 2.0, gamma2 = 0.5;
  const ContactLaw law = Hump(beta, gamma1, gamma2);
  for (double r : {0.05, 0.8, 1.4142, 3.0, 6.283185307}) {
    EXPECT_NEAR(law.F(r), beta * (std::tanh(r) + gamma1 * r / (1 + gamma2 * r * r)), 1e-15) << r;
    ExpectSlopeIsTheDerivative(law, r, beta * (1 + gamma1));
  }
  EXPECT_EQ(law.F(0.0), 0.0);
  EXPECT_EQ(law.AtRest(), 0.0);
  EXPECT_DOUBLE_EQ(law.Slope(0.0), beta * (1 + gamma1));
  const double large = 1e6;  // tanh is 1; the hump's tail gamma1 / (gamma2 r) is left
  EXPECT_NEAR(law.F(large) - beta, beta * gamma1 / (gamma2 * large), 1e-15);
  EXPECT_LT(law.Slope(3.0), 0.0);  // falling past the hump: velocity weakening
  EXPECT_GT(law.F(1.4142), law.F(6.283185307));
}

// Eq. 2.30 as printed: F(0+) = beta gamma1, held at rest; F -> beta as r -> inf.
TEST(ContactLaw, PrintedTanhHumpHoldsItsRestLevel) {
  const double beta = 0.9, gamma1 = 1.5, gamma2 = 0.5;
  const ContactLaw law = PrintedHump(beta, gamma1, gamma2);
  EXPECT_DOUBLE_EQ(law.AtRest(), beta * gamma1);
  EXPECT_NEAR(law.F(1e-9), beta * gamma1, 1e-8);
  for (double r : {0.3, 2.0, 6.283185307}) {
    EXPECT_NEAR(law.F(r), beta * (std::tanh(r) + gamma1 / (1 + gamma2 * r * r)), 1e-15) << r;
    ExpectSlopeIsTheDerivative(law, r, beta * (1 + gamma1));
  }
  EXPECT_NEAR(law.F(1e6), beta, 1e-11);
}

// eps -> 0: F(r) -> alpha at every r > 0 (the sign's magnitude), the shortfall alpha eps^2 / (2 r^2) falling as eps^2.
TEST(ContactLaw, RegularizedTendsToTheSignAsEpsilonVanishes) {
  const double r = 1.0;
  double shortfall_before = 0;
  for (double eps : {0.1, 0.01, 0.001}) {
    const double shortfall = 1 - Regularized(1.0, eps).F(r);
    EXPECT_NEAR(shortfall, eps * eps / (2 * r * r), 0.02 * eps * eps / (2 * r * r)) << eps;
    if (shortfall_before > 0) {
      EXPECT_NEAR(shortfall_before / shortfall, 100.0, 2.0) << eps;
    }
    shortfall_before = shortfall;
  }
}

// Eq. 2.33: the cutting torque times F^2, its slope t_c 2 F F'; at rest F(0+)^2 = 0 for a smooth F.
TEST(ContactLaw, SquaredCuttingTorqueFadesWithFSquared) {
  const double t_c = 3700, alpha = 1.0, eps = 2.0;
  const ContactLaw law = Regularized(alpha, eps, CuttingTorque::kFrictionSquared);
  for (double w : {0.5, 2.0, 6.283185307}) {
    const double f = alpha * w / std::sqrt(w * w + eps * eps);
    EXPECT_NEAR(law.CutTorque(t_c, w), t_c * f * f, 1e-11 * t_c) << w;
    EXPECT_NEAR(law.CutTorqueSlope(t_c, w), Derivative([&](double x) { return law.CutTorque(t_c, x); }, w),
                1e-7 * t_c)
        << w;
  }
  EXPECT_EQ(law.CutTorqueAtRest(t_c), 0.0);
  EXPECT_EQ(Regularized(alpha, eps).CutTorque(t_c, 2.0), t_c);  // RGD's cutting torque by default
}

TEST(ContactLaw, RefusesAFunctionWithUnitsOrAnotherLaw) {
  EXPECT_THROW(ContactLaw(FrictionLaw(SqrtRegularized{2.0, 1.0, 0.1}), CuttingTorque::kRgd), std::invalid_argument);
  EXPECT_THROW(ContactLaw(FrictionLaw(Coulomb{1.0, 1.0, 0.0}), CuttingTorque::kRgd), std::invalid_argument);
}

// --- The RGD law with a contact law -------------------------------------------------------------------------------

// BASELINE.md's nominal rock under the baseline's bit: contact force a sigma l = 48.6 kN.
RgdLaw Nominal(const ContactLaw& contact) {
  RgdLaw law;
  law.a = 0.10795, law.zeta = 0.6, law.eps = 50e6, law.sigma_l = 450e3, law.mu = 0.6, law.gamma = 1;
  law.static_mu = law.mu;
  law.contact_law = contact;
  return law;
}

RgdForces Advancing(const RgdLaw& law, Turn turn, double w, double depth) {
  RgdForces f;
  f.depth = depth, f.drive_force = 90e3, f.drive_torque = 1000;
  law.OnBottom(turn, Axial::kAdvancing, w, turn != Turn::kBackward, 0.0, f);
  return f;
}

// T = T_c + (a gamma / 2) mu F(|w|) a sigma l turning forward, -(a gamma / 2) mu F(|w|) a sigma l backward; a stuck bit
// holds [0, T_c] (a smooth F holds no friction at rest); W_f = a sigma l whatever F.
TEST(ContactLaw, RgdForcesTakeTheFrictionFunction) {
  const RgdLaw law = Nominal(Regularized(1.0, 0.1));
  const double depth = 0.0128, t_c = law.CutTorquePerDepth() * depth, t_f = 0.5 * law.a * law.mu * law.ContactForce();
  const double w = 0.05, f = w / std::sqrt(w * w + 0.01);
  const RgdForces forward = Advancing(law, Turn::kForward, w, depth);
  EXPECT_NEAR(forward.torque, t_c + t_f * f, 1e-9 * t_c);
  EXPECT_DOUBLE_EQ(forward.weight, law.CutWeightPerDepth() * depth + law.ContactForce());
  EXPECT_NEAR(Advancing(law, Turn::kBackward, -w, depth).torque, -t_f * f, 1e-9 * t_f);
  const RgdForces stuck = Advancing(law, Turn::kStuck, 0.0, depth);
  EXPECT_NEAR(stuck.static_forward, t_c, 1e-9 * t_c);
  EXPECT_EQ(stuck.static_backward, 0.0);
  // Eq. 2.33's cutting torque: faded by F^2 turning, nothing held at rest.
  const RgdLaw squared = Nominal(Regularized(1.0, 0.1, CuttingTorque::kFrictionSquared));
  EXPECT_NEAR(Advancing(squared, Turn::kForward, w, depth).torque, (t_c * f + t_f) * f, 1e-9 * t_c);
  EXPECT_EQ(Advancing(squared, Turn::kStuck, 0.0, depth).static_forward, 0.0);
}

// Steady drilling's torque with F, and its slope at the held depth of cut (what the linearization adds to the bit's
// damping) against finite differences, for each law, with RGD's and eq. 2.33's cutting torque.
TEST(ContactLaw, SteadyTorqueSlopeIsItsDerivative) {
  const double wob = 90e3, w0 = 2 * kPi;
  for (const ContactLaw& contact :
       {Regularized(1.0, 2.0), Hump(1.0, 1.0, 1.0), PrintedHump(1.0, 1.5, 0.5),
        Regularized(1.0, 2.0, CuttingTorque::kFrictionSquared), Hump(1.0, 1.0, 1.0, CuttingTorque::kFrictionSquared)}) {
    const RgdLaw law = Nominal(contact);
    const double t_c = law.CutTorquePerDepth() * law.SteadyDepth(wob);
    const double expected = t_c * contact.CutFactor(w0) + 0.5 * law.a * law.mu * contact.F(w0) * law.ContactForce();
    EXPECT_NEAR(law.SteadyTorque(wob, w0), expected, 1e-12 * expected);
    const double slope = Derivative([&](double w) { return law.SteadyTorque(wob, w); }, w0, 1e-4);
    EXPECT_NEAR(law.SteadyTorqueSlope(wob, w0), slope, 1e-6 * (std::abs(slope) + 1));
  }
  const RgdLaw rgd = Nominal(ContactLaw());
  EXPECT_EQ(rgd.SteadyTorqueSlope(wob, w0), 0.0);
  EXPECT_EQ(rgd.MuAt(w0), rgd.mu);
}

}  // namespace
}  // namespace drillwave::bitrock
