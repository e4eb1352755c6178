#pragma once
// The bottom hole's roughness at the start of a drilling run. BASELINE.md's recordings start "from the exact
// steady-drilling state plus a tiny bottom-hole roughness": the bit's state is steady drilling, but the rock surface
// the blades left before t = 0 deviates from the steady helix by h(theta) along the hole's axis, theta the angle
// around the hole. The first blade pass then cuts d0 - n h and the instability grows from there, with no disturbance
// in the inputs.
#include <cstdint>
#include <vector>

namespace drillwave::bitrock {

// h(theta) = sum_{k=1..K} c cos(k theta + phi_k), c = rms sqrt(2 / K), the phases phi_k drawn uniformly from
// [0, 2 pi) by a 64-bit Mersenne Twister seeded with `seed` (portable: the same surface on every platform). A
// random-phase trigonometric polynomial: periodic around the hole, mean exactly 0 and root mean square exactly `rms`
// over a revolution, the K modes sharing the variance equally (the shortest wavelength is a K-th of the
// circumference); over seeds, h at any angle has mean 0 and variance rms^2. Default (or rms 0): a smooth bottom.
class BottomRoughness {
 public:
  BottomRoughness() = default;
  // rms >= 0 [m], modes >= 1; throws std::invalid_argument otherwise.
  BottomRoughness(double rms, std::uint64_t seed, int modes);

  bool on() const { return amplitude_ > 0; }
  double Depth(double theta) const;  // h [m], down positive
  double Slope(double theta) const;  // dh / dtheta [m/rad]

 private:
  double amplitude_ = 0;        // c
  std::vector<double> phases_;  // phi_k, k = 1..K
};

}  // namespace drillwave::bitrock
