// dynamics::Contact, the friction of a contact every kind with a lumped friction law uses (lumped inertias, the wave
// network's ends): a set-valued law read on the side of the slip direction (also where a trial stage overshot the
// stop), scaled by a normal load; a smoothed law that never sticks; the static range held at rest.
#include "drillwave/dynamics/contact.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace drillwave::dynamics {
namespace {

using bitrock::Turn;

// Stribeck's law on a 0.1-m bit under 40 N: kinetic 0.3, static 0.5, and a viscous term; at rest [-2, 2] N m.
bitrock::FrictionLaw StribeckLaw() {
  return bitrock::FrictionLaw(bitrock::Stribeck{40.0, 0.1, 0.3, 0.5, 1.0, 1.0, 0.2});
}

TEST(Contact, ASetValuedLawSlipsOnTheSideOfItsSlipDirectionEvenAtRestOrPastIt) {
  const bitrock::FrictionLaw law = StribeckLaw();
  const Contact contact(law);
  ASSERT_TRUE(contact.CanStick());
  const double forward_limit = law.SlipTorque(1e-300), backward_limit = law.SlipTorque(-1e-300);
  EXPECT_GT(forward_limit, 0.0);
  EXPECT_LT(backward_limit, 0.0);
  EXPECT_EQ(contact.SlipTorque(Turn::kForward, 0.0), forward_limit);    // not 0, a value in the static range
  EXPECT_EQ(contact.SlipTorque(Turn::kForward, -1e-3), forward_limit);  // a trial stage past the stop
  EXPECT_EQ(contact.SlipTorque(Turn::kBackward, 0.0), backward_limit);
  EXPECT_EQ(contact.SlipTorque(Turn::kBackward, 1e-3), backward_limit);
  EXPECT_EQ(contact.SlipTorque(Turn::kForward, 1.5), law.SlipTorque(1.5));
  EXPECT_EQ(contact.SlipTorque(Turn::kForward, 1.5, 2.5), 2.5 * law.SlipTorque(1.5));  // a normal load scales it
}

TEST(Contact, AtRestItHoldsItsLawsStaticRangeScaled) {
  const bitrock::FrictionLaw law = StribeckLaw();
  const bitrock::AtRest r = Contact(law).HeldAtRest(4.0, 2.0);
  EXPECT_EQ(r.drive, 4.0);
  EXPECT_EQ(r.range.forward, 2.0 * law.StaticPositive());
  EXPECT_EQ(r.range.backward, 2.0 * law.StaticNegative());
  EXPECT_EQ(bitrock::TurnAtRest(r), Turn::kStuck);  // 4 lies inside [-4, 4]
  EXPECT_EQ(bitrock::TurnAtRest(Contact(law).HeldAtRest(4.0)), Turn::kForward);
}

TEST(Contact, SmoothedItNeverSticksAndFadesToZeroAtRest) {
  const bitrock::FrictionLaw law = StribeckLaw();
  const Contact smoothed(law, 0.1);
  EXPECT_FALSE(smoothed.CanStick());
  EXPECT_EQ(smoothed.SlipTorque(Turn::kForward, 0.0), 0.0);
  EXPECT_NEAR(smoothed.SlipTorque(Turn::kForward, 0.05), law.SlipTorque(0.05) * std::tanh(0.5), 1e-15);
  EXPECT_NEAR(smoothed.SlipTorque(Turn::kBackward, -3.0), law.SlipTorque(-3.0) * std::tanh(30.0), 1e-12);
  const bitrock::FrictionLaw viscous(bitrock::Viscous{0.7});
  EXPECT_FALSE(Contact(viscous).CanStick());
  EXPECT_EQ(Contact(viscous).SlipTorque(Turn::kForward, -2.0), viscous.SlipTorque(-2.0));  // smooth: no side
}

}  // namespace
}  // namespace drillwave::dynamics
