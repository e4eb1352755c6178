#pragma once
// Decay rate of one mode in a sampled free response, by complex demodulation. Header-only, for tests and apps/bench.
#include <cmath>
#include <complex>
#include <cstddef>
#include <vector>

namespace drillwave::testing {

// Decay rate of the mode at omega in y on [from, to] (uniform samples t): y e^{-i omega t} averaged over `period`
// leaves that mode's envelope a e^{-sigma t} (other modes at omega +- multiples of 2 pi / period average out); sigma
// from a least-squares line through its logarithm.
inline double ModalDecay(const std::vector<double>& t, const std::vector<double>& y, double omega, double period,
                         double from, double to) {
  const double dt = t[1] - t[0];
  const std::size_t width = static_cast<std::size_t>(std::lround(period / dt));
  std::vector<std::complex<double>> shifted(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) shifted[i] = y[i] * std::polar(1.0, -omega * t[i]);
  double st = 0, sy = 0, stt = 0, sty = 0, n = 0;
  for (std::size_t i = 0; i + width < t.size(); ++i) {
    const double centre = t[i] + 0.5 * width * dt;
    if (centre < from || centre > to) continue;
    std::complex<double> mean = 0;
    for (std::size_t k = i; k < i + width; ++k) mean += shifted[k];
    const double v = std::log(std::abs(mean));
    st += centre, sy += v, stt += centre * centre, sty += centre * v, n += 1;
  }
  return -(n * sty - st * sy) / (n * stt - st * st);
}

}  // namespace drillwave::testing
