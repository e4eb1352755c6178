#pragma once
// Noise levels and local-polynomial smoothing of sampled signals (uniform grid), NaN-aware: a window with a NaN in it
// gives NaN, so the edges where an estimate is not available stay marked.
#include <vector>

namespace drillwave::estimation {

struct Smoothed {
  std::vector<double> value, derivative;
  double noise_gain = 0;  // std of the smoothed value per unit std of white noise in the input
  double derivative_noise_gain = 0;  // the same for the derivative [1/s]
};

// Least-squares quadratic over the centred window of 2 half_width + 1 samples (Savitzky-Golay): value and first
// derivative at the centre. half_width 0 returns the input and a central-difference derivative.
Smoothed SmoothQuadratic(const std::vector<double>& x, double dt, int half_width);

// The same with a polynomial of the given order (>= 1) fitted over the window: a quartic's slope at the centre follows
// a curved signal whose slope a quadratic's (a straight line's) flattens, at more noise for the same window.
Smoothed SmoothPolynomial(const std::vector<double>& x, double dt, int half_width, int order);

// White-noise standard deviation of a sampled signal read from its successive differences (robust: 1.4826 MAD of the
// differences over sqrt 2), which the signal's own motion barely moves when it is sampled well above its bandwidth.
double NoiseStd(const std::vector<double>& x);

// The median of |x| over its finite samples (0 if none): the level a stuck threshold is a fraction of.
double MedianAbs(const std::vector<double>& x);

}  // namespace drillwave::estimation
