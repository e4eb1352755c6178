// The sliding-mode law of a top drive (model::SlidingMode): a PI inside its boundary layer, saturated outside, and a
// surface that a rigid top reaches and holds whatever load below J eta it carries.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "drillwave/model/top_drive_law.hpp"

namespace drillwave::model {
namespace {

TEST(SlidingMode, InsideItsLayerItIsThePiOfInLayerAndOutsideItSaturates) {
  const SlidingMode law{0.2, 36, 0.36};  // lambda 1/s, eta rad/s^2, phi rad/s
  const double j = 500;
  const PiController pi = law.InLayer(j);
  EXPECT_DOUBLE_EQ(pi.kp, j * (0.2 + 36 / 0.36));
  EXPECT_DOUBLE_EQ(pi.ki, j * 36 / 0.36 * 0.2);
  for (const double error : {-0.3, -0.01, 0.0, 0.05, 0.2})  // s = e + lambda I within (-phi, phi)
    EXPECT_NEAR(law.Torque(j, error, 0.5), pi.Output(error, 0, 0.5), 1e-9 * pi.kp) << error;
  // Outside: J lambda e plus the whole reaching torque J eta, signed as the surface.
  EXPECT_DOUBLE_EQ(law.Torque(j, 2.0, 0.0), j * (0.2 * 2.0 + 36));
  EXPECT_DOUBLE_EQ(law.Torque(j, -2.0, -1.0), j * (0.2 * -2.0 - 36));
}

// A rigid top J v' = u - T under a constant command r, starting 3 rad/s slow (s = 3, ten layers out): the surface
// falls at eta - T / J until it enters the layer; inside, on the surface e = -lambda I, the error decays at lambda
// (100 s: e^-20) and the integral comes to hold T (J eta sat(lambda I / phi) = T). Explicit Euler at 0.1 ms.
TEST(SlidingMode, ARigidTopReachesItsLayerAndHoldsTheSetPointUnderALoadBelowItsReachingTorque) {
  const SlidingMode law{0.2, 36, 0.3};
  const double j = 500, load = 12000, r = 10, dt = 1e-4;  // J eta = 18 000 N m > T
  double v = 7, integral = 0, t = 0, entered = -1;
  while (t < 100) {
    const double e = r - v, s = e + law.surface_corner * integral;
    if (entered < 0 && std::abs(s) <= law.boundary_layer) entered = t;
    const double u = law.Torque(j, e, integral);
    v += dt * (u - load) / j;
    integral += dt * e;
    t += dt;
  }
  // s' = -(eta - T/J) = -12 rad/s^2 outside: from s = 3 to the layer's 0.3 in (3 - 0.3) / 12 = 0.225 s.
  EXPECT_NEAR(entered, (3 - 0.3) / (36 - load / j), 2e-3);
  EXPECT_NEAR(v, r, 1e-6);
  EXPECT_NEAR(law.Torque(j, 0, integral), load, 1e-3);
}

}  // namespace
}  // namespace drillwave::model
