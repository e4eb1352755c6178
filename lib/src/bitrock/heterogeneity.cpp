#include "drillwave/bitrock/heterogeneity.hpp"

#include <array>
#include <atomic>
#include <cmath>
#include <random>
#include <stdexcept>

namespace drillwave::bitrock {
namespace {
constexpr double kPi = 3.14159265358979323846;

// The table: the field's Taylor polynomial of degree 14 about nodes no further apart than 1.2 / max|kappa_k|, so that
// |kappa_k (z - node)| <= 0.6 for every mode and the remainder, sum_k c (kappa_k dz)^15 / 15!, is below 1e-15 of the
// field's std: the sum itself up to rounding, smooth within a piece and continuous across nodes to rounding. (An
// interpolating table would not do: a cubic's jumping curvature at every node costs the integrator eight times the
// steps at tol 1e-7.) The sum of cosines, one cosine per mode and depth, was the bit's dearest term, a fifth of a
// coupled run; the polynomial is 14 multiply-adds. Each thread fills chunks of 64 nodes as the bit reaches them.
constexpr int kDegree = 14;
constexpr double kReach = 0.6;  // max |kappa_k (z - node)|
constexpr int kNodesPerChunk = 64;

// The top 53 bits of a draw as a fraction in (0, 1] (std::uniform_real_distribution's and std::normal_distribution's
// algorithms are the library's own; these are the same everywhere).
double Uniform(std::mt19937_64& draw) { return static_cast<double>((draw() >> 11) + 1) * 0x1.0p-53; }
double StandardNormal(std::mt19937_64& draw) {  // Box-Muller, the cosine branch
  const double radius = std::sqrt(-2 * std::log(Uniform(draw)));
  return radius * std::cos(2 * kPi * Uniform(draw));
}

struct Chunk {
  std::uint64_t field = 0;  // 0: empty
  std::int64_t first = 0;   // index of its first node
  std::array<std::array<double, kDegree + 1>, kNodesPerChunk> taylor{};  // g^(n)(node) / n!, n = 0..kDegree
};
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
  double largest = 0;
  for (int k = 0; k < modes; ++k) {
    wavenumbers_[k] = StandardNormal(draw) / correlation;
    phases_[k] = 2 * kPi * Uniform(draw);
    largest = std::max(largest, std::abs(wavenumbers_[k]));
  }
  node_spacing_ = largest > 0 ? 2 * kReach / largest : correlation;
}

double StrengthHeterogeneity::ExactDeviation(double z) const {
  double g = 0;
  for (std::size_t k = 0; k < phases_.size(); ++k) g += std::cos(wavenumbers_[k] * z + phases_[k]);
  return amplitude_ * g;
}

double StrengthHeterogeneity::Deviation(double z) const {
  const double u = z / node_spacing_;
  if (!(std::abs(u) < 1e15)) return ExactDeviation(z);  // beyond any drilled depth (or NaN): no table
  const double node = std::nearbyint(u);
  const auto index = static_cast<std::int64_t>(node);
  const std::int64_t first = static_cast<std::int64_t>(std::floor(node / kNodesPerChunk)) * kNodesPerChunk;
  // Each thread keeps the two chunks it used last (a bit bouncing across a chunk's end refills nothing). A node's
  // polynomial is a pure function of the field and the node's index, so the answer does not depend on which thread
  // or which order filled the table.
  thread_local std::array<Chunk, 2> chunks;
  thread_local int newest = 0;
  Chunk* chunk = nullptr;
  for (int c : {newest, 1 - newest})
    if (chunks[c].field == id_ && chunks[c].first == first) chunk = &chunks[c], newest = c;
  if (chunk == nullptr) {
    newest = 1 - newest;
    chunk = &chunks[newest];
    chunk->field = 0;
    for (int j = 0; j < kNodesPerChunk; ++j) {
      // g^(n)(z) = c sum_k kappa_k^n cos(kappa_k z + phi_k + n pi / 2): the cosine and sine turn in fours.
      auto& taylor = chunk->taylor[j];
      taylor.fill(0.0);
      const double zj = static_cast<double>(first + j) * node_spacing_;
      for (std::size_t k = 0; k < phases_.size(); ++k) {
        const double phase = wavenumbers_[k] * zj + phases_[k];
        const double turn[4] = {std::cos(phase), -std::sin(phase), -std::cos(phase), std::sin(phase)};
        double power = 1;  // kappa^n / n!
        for (int n = 0; n <= kDegree; ++n) {
          taylor[n] += power * turn[n % 4];
          power *= wavenumbers_[k] / (n + 1);
        }
      }
      for (double& a : taylor) a *= amplitude_;
    }
    chunk->field = id_, chunk->first = first;
  }
  const auto& taylor = chunk->taylor[static_cast<std::size_t>(index - first)];
  const double dz = z - node * node_spacing_;
  double g = taylor[kDegree];
  for (int n = kDegree - 1; n >= 0; --n) g = g * dz + taylor[n];
  return g;
}

}  // namespace drillwave::bitrock
