#pragma once
// Newton's method on an analytic function of one complex variable, with a central-difference derivative: how the
// stability tests find the zeros of their closed-form characteristic functions. Header-only.
#include <cmath>
#include <complex>
#include <limits>

namespace drillwave::testing {

struct NewtonZeroOptions {
  double difference_step = 1e-6;  // h = difference_step (1 + |s|)
  double tolerance = 1e-13;       // settled once |step| < tolerance (1 + |s|)
  double re_bound = std::numeric_limits<double>::infinity();  // give up once |Re s| exceeds it ...
  double im_bound = std::numeric_limits<double>::infinity();  // ... or |Im s| this
  int iterations = 100;
};

// Refines s towards a zero of f in place; false if an iterate leaves the bounds or is not finite, or if it does not
// settle within the iterations.
template <class Function>
bool NewtonZero(const Function& f, std::complex<double>& s, const NewtonZeroOptions& o = {}) {
  for (int it = 0; it < o.iterations; ++it) {
    if (std::abs(s.real()) > o.re_bound || std::abs(s.imag()) > o.im_bound) return false;
    const std::complex<double> h = o.difference_step * (1.0 + std::abs(s));
    const std::complex<double> step = f(s) / ((f(s + h) - f(s - h)) / (2.0 * h));
    s -= step;
    if (!std::isfinite(s.real()) || !std::isfinite(s.imag())) return false;
    if (std::abs(step) < o.tolerance * (1.0 + std::abs(s))) return true;
  }
  return false;
}

}  // namespace drillwave::testing
