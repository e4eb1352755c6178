#include "drillwave/bitrock/roughness.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

#include "drillwave/core/constants.hpp"

namespace drillwave::bitrock {
namespace {
}  // namespace

BottomRoughness::BottomRoughness(double rms, std::uint64_t seed, int modes) {
  if (!(rms >= 0) || !std::isfinite(rms)) throw std::invalid_argument("bottom roughness: rms must be finite and >= 0");
  if (modes < 1) throw std::invalid_argument("bottom roughness: at least one mode");
  amplitude_ = rms * std::sqrt(2.0 / modes);
  // The top 53 bits of each draw as a fraction of a turn (std::uniform_real_distribution's algorithm is the
  // library's own; this one is the same everywhere).
  std::mt19937_64 draw(seed);
  phases_.resize(modes);
  for (double& phase : phases_) phase = 2 * kPi * static_cast<double>(draw() >> 11) * 0x1.0p-53;
}

double BottomRoughness::Depth(double theta) const {
  double h = 0;
  for (std::size_t k = 0; k < phases_.size(); ++k) h += std::cos(static_cast<double>(k + 1) * theta + phases_[k]);
  return amplitude_ * h;
}

double BottomRoughness::Slope(double theta) const {
  double slope = 0;
  for (std::size_t k = 0; k < phases_.size(); ++k) {
    const double wavenumber = static_cast<double>(k + 1);
    slope -= wavenumber * std::sin(wavenumber * theta + phases_[k]);
  }
  return amplitude_ * slope;
}

}  // namespace drillwave::bitrock
