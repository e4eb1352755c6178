// The depth of cut of the RGD law against the stored bit motion (bitrock::CutProfile): after a bounce, against the
// previous blade pass (surface_passes = 1, BASELINE.md's d = n (U(t) - U(t - t_n)) taken literally) or the deepest of
// the last four passes (the default). Closed forms on a motion the history stores exactly (piecewise linear).
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/bitrock/rgd.hpp"
#include "drillwave/core/constants.hpp"

namespace {

using drillwave::kPi;
using drillwave::bitrock::CutProfile;
using drillwave::integration::Piece;
using drillwave::integration::Side;

constexpr int kBlades = 5;
constexpr double kOmega = 2 * kPi;  // rad/s: one blade pass every t_n = 2 pi / (n omega) = 0.2 s
constexpr double kRop = 0.01;       // m/s, also the stored prehistory's

// The bit turns steadily and drills at kRop until 1 s, lifts by 1 cm until 1.2 s (one blade pass in the air), then
// comes down 2 cm until 1.4 s. Positions down positive.
void StoreBouncedMotion(CutProfile& profile) {
  const double knots[4][2] = {{0, 0}, {1, 0.01}, {1.2, 0.0}, {1.4, 0.02}};
  for (int k = 0; k < 3; ++k) {
    const double t0 = knots[k][0], t1 = knots[k + 1][0], u0 = knots[k][1], u1 = knots[k + 1][1];
    const double v = (u1 - u0) / (t1 - t0);
    const std::vector<double> x0 = {kOmega * t0, u0}, x1 = {kOmega * t1, u1}, f = {kOmega, v},
                              mid = {kOmega * 0.5 * (t0 + t1), 0.5 * (u0 + u1)};
    profile.Commit(Piece{t0, t1, x0, f, x1, f, mid}, 0, 1, /*contact=*/false, /*last_contact_change=*/1.0, 100);
  }
}

TEST(CutProfile, AfterABounceTheRockIsThePreviousPassOrTheDeepestOfFour) {
  const double t = 1.4, phi = kOmega * t, u = 0.02;
  CutProfile literal(kBlades, kOmega, kRop, 1), deepest(kBlades, kOmega, kRop, 4);
  StoreBouncedMotion(literal);
  StoreBouncedMotion(deepest);
  double tn = 0;
  // The previous blade passed at 1.2 s, at the top of the bounce (U = 0): d = n (0.02 - 0).
  EXPECT_NEAR(literal.DepthOfCut(phi, u, t, Side::kLeft, false, 1.0, &tn), kBlades * (u - 0.0), 1e-9);
  EXPECT_NEAR(tn, 2 * kPi / (kBlades * kOmega), 1e-9);
  // The passes at 1.2, 1.0, 0.8 and 0.6 s stood at 0, 0.01, 0.008 and 0.006 m: the deepest is 0.01 m.
  EXPECT_NEAR(deepest.DepthOfCut(phi, u, t, Side::kLeft, false, 1.0), kBlades * (u - 0.01), 1e-9);
  // In contact ever since the previous pass, both read the previous pass (RGD's d).
  EXPECT_NEAR(deepest.DepthOfCut(phi, u, t, Side::kLeft, true, 1.0), kBlades * (u - 0.0), 1e-9);
}

TEST(CutProfile, InSteadyDrillingTheDepthIsTheAdvancePerBladePass) {
  for (int passes : {1, 4}) {
    CutProfile profile(kBlades, kOmega, kRop, passes);
    // Only the prehistory (steady drilling): d = n V t_n = 2 pi V / omega, whatever the passes.
    EXPECT_NEAR(profile.DepthOfCut(kOmega * 0.5, kRop * 0.5, 0.5, Side::kLeft, false, -1.0),
                2 * kPi * kRop / kOmega, 1e-9)
        << passes << " passes";
  }
}

}  // namespace
