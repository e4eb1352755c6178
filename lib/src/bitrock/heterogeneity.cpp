#include "drillwave/bitrock/heterogeneity.hpp"

#include <algorithm>
#include <array>
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

// The fastest mode turns by this phase across a cell of the interpolant.
constexpr double kCellPhase = 0.5;
// Cells, and jets at their ends, each thread keeps, direct-mapped by their index (a bit goes back and forth over a
// few, and neighbouring cells share an end).
constexpr std::size_t kCachedCells = 64, kCachedEnds = 128;
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
  double fastest = 0;
  for (int k = 0; k < modes; ++k) {
    wavenumbers_[k] = StandardNormal(draw) / correlation;
    phases_[k] = 2 * kPi * Uniform(draw);
    fastest = std::max(fastest, std::abs(wavenumbers_[k]));
  }
  cell_ = fastest > 0 ? kCellPhase / fastest : correlation;
}

double StrengthHeterogeneity::ExactDeviation(double z) const {
  double g = 0;
  for (std::size_t k = 0; k < phases_.size(); ++k) g += std::cos(wavenumbers_[k] * z + phases_[k]);
  return amplitude_ * g;
}

void StrengthHeterogeneity::Jet(double z, double out[3]) const {
  double g = 0, slope = 0, curvature = 0;
  for (std::size_t k = 0; k < phases_.size(); ++k) {
    const double kappa = wavenumbers_[k], theta = kappa * z + phases_[k];
    const double c = std::cos(theta), s = std::sin(theta);
    g += c, slope -= kappa * s, curvature -= kappa * kappa * c;
  }
  out[0] = amplitude_ * g, out[1] = amplitude_ * slope, out[2] = amplitude_ * curvature;
}

double StrengthHeterogeneity::Deviation(double z) const {
  if (!std::isfinite(z)) return ExactDeviation(z);
  // The cell's quintic in s = z / h - index, from the jets at its ends (derivatives in units of the cell).
  struct Cell {
    std::uint64_t field = 0;
    std::int64_t index = 0;
    std::array<double, 6> c{};
  };
  thread_local std::array<Cell, kCachedCells> cells;
  const double u = z / cell_, floor = std::floor(u);
  const auto index = static_cast<std::int64_t>(floor);
  Cell& cell = cells[static_cast<std::uint64_t>(index) % kCachedCells];
  if (cell.field != id_ || cell.index != index) {
    struct End {
      std::uint64_t field = 0;
      std::int64_t index = 0;
      double jet[3] = {0, 0, 0};
    };
    thread_local std::array<End, kCachedEnds> ends;
    const auto end_jet = [&](std::int64_t at) -> const double* {
      End& end = ends[static_cast<std::uint64_t>(at) % kCachedEnds];
      if (end.field != id_ || end.index != at) {
        end.field = id_, end.index = at;
        Jet(static_cast<double>(at) * cell_, end.jet);
      }
      return end.jet;
    };
    const double* a = end_jet(index);  // neighbouring ends sit in different slots: both stay valid
    const double* b = end_jet(index + 1);
    const double h = cell_, p0 = a[0], p1 = b[0], d0 = a[1] * h, d1 = b[1] * h, q0 = a[2] * h * h, q1 = b[2] * h * h,
                 rise = p1 - p0;
    cell.field = id_, cell.index = index;
    cell.c = {p0,
              d0,
              0.5 * q0,
              10 * rise - 6 * d0 - 4 * d1 - 0.5 * (3 * q0 - q1),
              -15 * rise + 8 * d0 + 7 * d1 + 0.5 * (3 * q0 - 2 * q1),
              6 * rise - 3 * d0 - 3 * d1 - 0.5 * (q0 - q1)};
  }
  const double s = u - floor;
  const std::array<double, 6>& c = cell.c;
  return c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * (c[4] + s * c[5]))));
}

}  // namespace drillwave::bitrock
