#include "drillwave/bitrock/heterogeneity.hpp"

#include <atomic>
#include <cmath>
#include <random>
#include <stdexcept>

#include "drillwave/core/constants.hpp"

namespace drillwave::bitrock {
namespace {

// The top 53 bits of a draw as a fraction in (0, 1] (std::uniform_real_distribution's and std::normal_distribution's
// algorithms are the library's own; these are the same everywhere).
double Uniform(std::mt19937_64& draw) { return static_cast<double>((draw() >> 11) + 1) * 0x1.0p-53; }
double StandardNormal(std::mt19937_64& draw) {  // Box-Muller, the cosine branch
  const double radius = std::sqrt(-2 * std::log(Uniform(draw)));
  return radius * std::cos(2 * kPi * Uniform(draw));
}
}  // namespace

StrengthHeterogeneity::StrengthHeterogeneity(double std, double correlation, std::uint64_t seed, int modes) {
  if (!(std >= 0) || !std::isfinite(std))
    throw std::invalid_argument("strength heterogeneity: std must be finite and >= 0");
  if (!(correlation > 0) || !std::isfinite(correlation))
    throw std::invalid_argument("strength heterogeneity: correlation length must be finite and > 0");
  if (modes < 1) throw std::invalid_argument("strength heterogeneity: at least one mode");
  static std::atomic<std::uint64_t> fields{0};
  id_ = ++fields;
  std_ = std;
  amplitude_ = std * std::sqrt(2.0 / modes);
  std::mt19937_64 draw(seed);
  wavenumbers_.resize(modes);
  phases_.resize(modes);
  for (int k = 0; k < modes; ++k) {
    wavenumbers_[k] = StandardNormal(draw) / correlation;
    phases_[k] = 2 * kPi * Uniform(draw);
  }
}

double StrengthHeterogeneity::Deviation(double z) const {
  // One state is asked for the same depth many times (the right-hand side, then each of the bit's event witnesses),
  // and the sum of cosines is the bit's dearest term: each thread keeps its last answer. g is a pure function of the
  // field and z, so the result is the same bit for bit.
  thread_local struct {
    std::uint64_t field = 0;
    double z = 0, g = 0;
  } last;
  if (last.field == id_ && last.z == z) return last.g;
  double g = 0;
  for (std::size_t k = 0; k < phases_.size(); ++k) g += std::cos(wavenumbers_[k] * z + phases_[k]);
  g *= amplitude_;
  last = {id_, z, g};
  return g;
}

}  // namespace drillwave::bitrock
