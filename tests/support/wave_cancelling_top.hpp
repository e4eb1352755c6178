#pragma once
// The wave-cancelling top (model::WaveCancellation) in closed form: the reference for the linearization of both kinds
// with a top. Header-only.
#include <complex>
#include <utility>

namespace drillwave::testing {

// Its impedance Y = F / v, F the string's torque on it (Z (2 w - v) for the wave w arriving from the top section of
// impedance Z), as numerator and denominator (both times s). With E = e^{-s d} for the actuator delay d, its torque
// u = E (-F + c v + (J s + kp) (w + d_w) - kp v) cancels F and its damper c as read, the injected wave's perturbation
// is d_w = -k E v / s (the slow loop integrates -v as read), and J s v = F - c v + u. With w = (v + F / Z) / 2:
//   Y = (J s + c (1 - E) + kp E - (J s + kp) E (1 / 2 - k E / s)) / (1 - E + (J s + kp) E / (2 Z)),
// which without a delay (E = 1) is Z (1 + 2 k / s) = Z + ki / s whatever J and kp: the arriving wave absorbed, the
// integral on top.
struct WaveCancellingTop {
  double inertia, kp, corner, damping, delay;  // J, kp, k = ki / 2 Z, c, d

  std::pair<std::complex<double>, std::complex<double>> Impedance(double z, std::complex<double> s) const {
    const std::complex<double> e = std::exp(-s * delay), drive = inertia * s + kp;
    return {s * (inertia * s + damping * (1.0 - e) + kp * e) - drive * e * (0.5 * s - corner * e),
            s * (1.0 - e + drive * e / (2 * z))};
  }
};

}  // namespace drillwave::testing
