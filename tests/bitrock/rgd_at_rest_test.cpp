// The RGD law's forces on a bit at rest (RgdLaw::OnBottom with Turn::kStuck): the cutters of a stuck bit twisted
// backward answer what presses them, never lift it; and the backward slip threshold is the holding of the contact the
// bit would have turning back. Both keep the stuck, held regime consistent where the
// coupled run once chattered between four regimes every 4e-11 s (issue 41).
#include <algorithm>

#include <gtest/gtest.h>

#include "drillwave/bitrock/rgd.hpp"

namespace {

using drillwave::bitrock::Axial;
using drillwave::bitrock::RgdForces;
using drillwave::bitrock::RgdLaw;
using drillwave::bitrock::Turn;

// BASELINE.md's nominal law: contact force a sigma l = 7.8 kN, cutting weight 3.9 MN per metre of depth.
RgdLaw Nominal() {
  RgdLaw law;
  law.a = 0.108, law.zeta = 0.6, law.eps = 60e6, law.sigma_l = 60e6 * 0.0012, law.mu = 0.6, law.gamma = 1;
  law.static_mu = law.mu;
  return law;
}

RgdForces At(const RgdLaw& law, Turn turn, Axial axial, double depth, double drive_force, double drive_torque = -500) {
  RgdForces f;
  f.depth = depth, f.drive_force = drive_force, f.drive_torque = drive_torque;
  law.OnBottom(turn, axial, turn == Turn::kStuck ? 0.0 : 6.0, turn != Turn::kBackward, 0.0, f);
  return f;
}

// After a long stick the stored depth of cut (9 cm) would take 350 kN to cut; 153 kN press the bit, twisted backward by
// 500 N m. Stuck, its cutters answer 153 kN and no more, so it is held (net force 0, inside [0, a sigma l]) instead
// of being lifted off its wear flats, which would let it turn back and stop cutting. Twisted forward, the stored
// depth's cutting weight lifts it, as it does a turning bit.
TEST(RgdAtRest, AStuckBitsCuttersPushBackNoHarderThanTheStringPresses) {
  const RgdLaw law = Nominal();
  const double deep = 0.09, pressing = 153e3;
  const RgdForces stuck = At(law, Turn::kStuck, Axial::kHeld, deep, pressing);
  EXPECT_DOUBLE_EQ(stuck.cut_weight, pressing);
  EXPECT_DOUBLE_EQ(stuck.weight, pressing);
  const double net = stuck.drive_force - stuck.cut_weight;
  EXPECT_GE(net, 0.0);
  EXPECT_LE(net, law.ContactForce());
  // On the edge of lifting (net 0), yet it lifts only when the string pulls: the held regime's margin is the drive
  // force, not the net force (with the net force, the held bit lifted at once, slipped back, fell and stuck again
  // every 4e-11 s: the Inclined string's Z-Torque behind 0.1 s, at 58.65 s).
  EXPECT_DOUBLE_EQ(stuck.lift_margin, pressing);
  // Pulled up, nothing pushes back.
  EXPECT_DOUBLE_EQ(At(law, Turn::kStuck, Axial::kHeld, deep, -1e3).cut_weight, 0.0);
  // A shallow depth asks less than the string presses: the cutting weight as it is.
  const double shallow = 2.6e-3;
  EXPECT_DOUBLE_EQ(At(law, Turn::kStuck, Axial::kHeld, shallow, pressing).cut_weight,
                   law.CutWeightPerDepth() * shallow);
  EXPECT_DOUBLE_EQ(At(law, Turn::kStuck, Axial::kHeld, shallow, pressing).lift_margin,
                   pressing - law.CutWeightPerDepth() * shallow);
  // Twisted forward, or turning, the cutting weight is the depth's, whatever presses.
  EXPECT_DOUBLE_EQ(At(law, Turn::kStuck, Axial::kHeld, deep, pressing, 500).cut_weight, law.CutWeightPerDepth() * deep);
  EXPECT_DOUBLE_EQ(At(law, Turn::kForward, Axial::kHeld, deep, pressing).cut_weight, law.CutWeightPerDepth() * deep);
}

// Held, a stuck bit's wear flats carry what its cutters do not; turning back, the cutters let go and the flats carry
// it all (up to a sigma l): the backward threshold is that contact's holding, whatever the cutters carried at rest.
TEST(RgdAtRest, TheBackwardSlipThresholdIsTheHoldingOfTheContactTurningBack) {
  const RgdLaw law = Nominal();
  for (double pressing : {3e3, 20e3, 90e3}) {
    const RgdForces held = At(law, Turn::kStuck, Axial::kHeld, 2.6e-3, pressing);
    const double flats_turning_back = std::clamp(pressing, 0.0, law.ContactForce());
    EXPECT_DOUBLE_EQ(held.static_backward, law.StaticFrictionArm() * flats_turning_back) << pressing;
    // Forward, the cutters keep their share: the threshold is the cutting torque plus the held flats' holding.
    const double flats_held = std::clamp(pressing - held.cut_weight, 0.0, law.ContactForce());
    EXPECT_DOUBLE_EQ(held.static_forward, law.CutTorquePerDepth() * 2.6e-3 + law.StaticFrictionArm() * flats_held)
        << pressing;
  }
  // Advancing, the flats carry a sigma l either way.
  const RgdForces advancing = At(law, Turn::kStuck, Axial::kAdvancing, 2.6e-3, 90e3);
  EXPECT_DOUBLE_EQ(advancing.static_backward, law.StaticFrictionArm() * law.ContactForce());
}

}  // namespace
