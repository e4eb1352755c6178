#include "drillwave/dynamics/contact.hpp"

#include <algorithm>
#include <cmath>

namespace drillwave::dynamics {
namespace {
// The slip branch of a set-valued law is continued to the far side of zero by its limit at zero: trial stages can
// overshoot a stop before the event that ends the regime is located.
constexpr double kTinySpeed = 1e-300;
}  // namespace

double Contact::SlipTorque(bitrock::Turn turn, double v, double scale) const {
  const bitrock::FrictionLaw& law = *law_;
  if (smoothing_rad_s_ > 0) return v == 0 ? 0.0 : scale * law.SlipTorque(v) * std::tanh(std::abs(v) / smoothing_rad_s_);
  if (!law.IsSetValued()) return scale * law.SlipTorque(v);
  return scale * law.SlipTorque(turn == bitrock::Turn::kForward ? std::max(v, kTinySpeed) : std::min(v, -kTinySpeed));
}

}  // namespace drillwave::dynamics
