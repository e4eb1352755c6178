#include "drillwave/estimation/lumped_observer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/validity.hpp"
#include "drillwave/recordings/signals.hpp"
#include "drillwave/estimation/smoothing.hpp"

namespace drillwave::estimation {
namespace {

using Vec = Eigen::Vector4d;  // twist phi = theta_t - theta_b, top speed, bit speed, PI integral of the speed error
using Mat = Eigen::Matrix4d;
enum : int { kTwist = 0, kTop = 1, kBit = 2, kIntegral = 3 };
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

class Pendulum {
 public:
  explicit Pendulum(const LumpedModel& m) : m_(m) {}

  double ShaftTorque(const Vec& x) const {
    return m_.shaft_stiffness_Nm_per_rad * x[kTwist] + m_.shaft_damping_Nms_per_rad * (x[kTop] - x[kBit]);
  }
  double DriveTorque(const Vec& x, double t) const {
    switch (m_.drive) {
      case LumpedModel::Drive::kPiSpeed:
        return m_.kp * (m_.setpoint.Value(t) - x[kTop]) + m_.ki * x[kIntegral];
      case LumpedModel::Drive::kTorque:
        return m_.setpoint.Value(t);
      case LumpedModel::Drive::kPrescribedSpeed:  // whatever holds the speed: the top's own equation says nothing
        break;
    }
    return ShaftTorque(x) + m_.top_damping_Nms_per_rad * x[kTop];
  }

  // One explicit sub-step of length h with the bit's stick-slip switching (Filippov: stuck while the shaft's
  // torque stays within the static range). Returns whether the bit is stuck at its end.
  bool Step(Vec& x, double t, double h, bool stuck) const {
    const double shaft = ShaftTorque(x);
    x[kTop] += h * (DriveTorque(x, t) - shaft - m_.top_damping_Nms_per_rad * x[kTop]) / m_.top_inertia_kgm2;
    const double jb = m_.bit_inertia_kgm2;
    if (stuck) {
      const double limit = shaft > 0 ? m_.friction.StaticPositive() : m_.friction.StaticNegative();
      if (std::abs(shaft) > limit) {  // breaks away in the direction of the shaft's torque
        const double dir = shaft > 0 ? 1.0 : -1.0;
        x[kBit] = h * (shaft - m_.friction.SlipTorque(dir * 1e-12)) / jb;
        stuck = false;
      } else {
        x[kBit] = 0;
      }
    } else {
      const double w = x[kBit];
      const double next = w + h * (shaft - m_.bit_damping_Nms_per_rad * w - m_.friction.SlipTorque(w)) / jb;
      if (m_.friction.IsSetValued() && (w == 0 || next * w <= 0)) {
        const double limit = shaft > 0 ? m_.friction.StaticPositive() : m_.friction.StaticNegative();
        if (std::abs(shaft) <= limit) {
          x[kBit] = 0;
          stuck = true;
        } else {
          x[kBit] = next;
        }
      } else {
        x[kBit] = next;
      }
    }
    x[kTwist] += h * (x[kTop] - x[kBit]);
    x[kIntegral] += h * (m_.setpoint.Value(t) - x[kTop]);
    return stuck;
  }

  // d(x')/dx in the mode the bit is in.
  Mat Jacobian(const Vec& x, bool stuck) const {
    const double k = m_.shaft_stiffness_Nm_per_rad, c = m_.shaft_damping_Nms_per_rad;
    const double jt = m_.top_inertia_kgm2, jb = m_.bit_inertia_kgm2;
    Mat a = Mat::Zero();
    a(kTwist, kTop) = 1;
    a(kTwist, kBit) = -1;
    if (m_.drive != LumpedModel::Drive::kPrescribedSpeed) {
      const bool pi = m_.drive == LumpedModel::Drive::kPiSpeed;
      a(kTop, kTwist) = -k / jt;
      a(kTop, kTop) = (-(pi ? m_.kp : 0.0) - c - m_.top_damping_Nms_per_rad) / jt;
      a(kTop, kBit) = c / jt;
      a(kTop, kIntegral) = (pi ? m_.ki : 0.0) / jt;
    }
    if (!stuck) {
      a(kBit, kTwist) = k / jb;
      a(kBit, kTop) = c / jb;
      a(kBit, kBit) = (-c - m_.bit_damping_Nms_per_rad - m_.friction.SlipTorqueDerivative(x[kBit])) / jb;
    }
    a(kIntegral, kTop) = -1;
    return a;
  }

  // The fastest rate of the linear parts [1/s], for the sub-step.
  double FastestRate() const {
    const double k = m_.shaft_stiffness_Nm_per_rad, c = m_.shaft_damping_Nms_per_rad;
    const double jt = m_.top_inertia_kgm2, jb = m_.bit_inertia_kgm2;
    return std::max({std::sqrt(k / jt), std::sqrt(k / jb), (m_.kp + c + m_.top_damping_Nms_per_rad) / jt,
                     (c + m_.bit_damping_Nms_per_rad) / jb, std::sqrt(m_.ki / jt)});
  }

 private:
  const LumpedModel& m_;
};

std::vector<double> Despiked(const std::vector<double>& x, double dt) {
  std::vector<double> magnitude;
  for (double v : x) magnitude.push_back(std::abs(v));
  const double floor = 0.05 * recordings::Median(magnitude);
  // The inspection's setting (signals.hpp, MaskArtefacts): a window of +-0.1 s, 5 robust deviations, grown at 2.
  const int half = std::max(2, static_cast<int>(std::lround(0.1 / dt)));
  return recordings::HampelFilter(x, half, 5, floor, 2).cleaned;
}

}  // namespace

bool LumpedObserverOptions::IsValid(std::string* error) const {
  return FiniteField(error, "smoothing_lag_s", smoothing_lag_s) &&
         FiniteField(error, "model_time_offset_s", model_time_offset_s) &&
         FiniteField(error, "initial_bit_speed_rad_s", initial_bit_speed_rad_s) &&
         FiniteField(error, "initial_twist_rad", initial_twist_rad);
}

BitEstimate EstimateLumped(const LumpedModel& m, const SurfaceSignals& s, double stuck_threshold_rad_s,
                           const LumpedObserverOptions& o) {
  ThrowIfInvalid(o);
  if (s.top_speed_rad_s.empty()) throw ParameterError("from", "the lumped observer needs the top speed");
  const std::size_t n = s.time_s.size();
  const double dt = (s.time_s.back() - s.time_s.front()) / static_cast<double>(n - 1);
  const Pendulum p(m);
  BitEstimate e;
  e.time_s = s.time_s;
  e.stuck_threshold_rad_s = stuck_threshold_rad_s;
  e.method = "extended Kalman filter on the two-mass pendulum with set-valued bit friction, fixed-lag RTS smoother";

  const std::vector<double> z = o.despike ? Despiked(s.top_speed_rad_s, dt) : s.top_speed_rad_s;
  const double meas_sigma = std::max(NoiseStd(z), 1e-6 * (1 + std::abs(z.front())));
  const double static_level = std::max(m.friction.StaticPositive(), std::abs(m.friction.SlipTorque(1.0)));
  const double omega_bit = std::sqrt(m.shaft_stiffness_Nm_per_rad / m.bit_inertia_kgm2);
  // Torque uncertainties (see the header): a fifth of the friction level, correlated over 1 / omega_bit; as white
  // noise of the same low-frequency power, intensity sigma^2 * 2 / omega_bit.
  const double torque_sigma = 0.2 * std::max(static_level, 1e-9);
  const double intensity = torque_sigma * torque_sigma * 2 / omega_bit;
  const double drive_intensity = m.drive == LumpedModel::Drive::kPrescribedSpeed
                                     ? std::pow(10 * omega_bit * meas_sigma * m.top_inertia_kgm2, 2) / omega_bit
                                     : intensity;
  Mat q = Mat::Zero();
  q(kTop, kTop) = drive_intensity / (m.top_inertia_kgm2 * m.top_inertia_kgm2) * dt;
  q(kBit, kBit) = intensity / (m.bit_inertia_kgm2 * m.bit_inertia_kgm2) * dt;
  q(kTwist, kTwist) = 1e-12;
  q(kIntegral, kIntegral) = std::pow(meas_sigma, 2) * dt * dt;  // the integral of the measured speed's noise
  const double r = meas_sigma * meas_sigma;

  const int substeps = std::max(1, static_cast<int>(std::ceil(dt * p.FastestRate() / 0.1)));
  const double h = dt / substeps;

  // Start: the first measured speed for both discs, no twist, unless a test starts it elsewhere.
  Vec x;
  x << (o.initial_twist_rad > -1e299 ? o.initial_twist_rad : 0.0), z.front(),
      (o.initial_bit_speed_rad_s > -1e299 ? o.initial_bit_speed_rad_s : z.front()), 0.0;
  if (m.drive == LumpedModel::Drive::kPiSpeed && m.ki > 0) x[kIntegral] = 0;
  Mat pc = Mat::Zero();
  pc(kTwist, kTwist) = std::pow(2 * static_level / m.shaft_stiffness_Nm_per_rad, 2);
  pc(kTop, kTop) = r;
  pc(kBit, kBit) = std::pow(std::max(std::abs(z.front()), 10 * meas_sigma), 2);
  pc(kIntegral, kIntegral) = m.ki > 0 ? std::pow(static_level / m.ki, 2) : 1.0;
  bool stuck = false;

  std::vector<Vec> xf(n), xp(n);
  std::vector<Mat> pf(n), pp(n), phi(n);
  const Eigen::RowVector4d hrow(0, 1, 0, 0);
  int rejected = 0, run_rejected = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = s.time_s[k] - o.model_time_offset_s;
    if (k > 0) {  // predict from k - 1
      const Mat a = p.Jacobian(x, stuck);
      Mat step = Mat::Identity();
      const Mat one = Mat::Identity() + a * h;
      for (int i = 0; i < substeps; ++i) {
        stuck = p.Step(x, t - dt + i * h, h, stuck);
        step = one * step;
      }
      phi[k - 1] = step;
      pc = step * pc * step.transpose() + q;
    }
    xp[k] = x;
    pp[k] = pc;
    // Update with the measured top speed; a residual beyond 6 standard deviations is a glitch the despiking left,
    // unless the filter has lost the measurement for a tenth of a second.
    const double s_innov = pc(kTop, kTop) + r, nu = z[k] - x[kTop];
    if (std::isfinite(z[k]) && (nu * nu <= 36 * s_innov || run_rejected * dt > 0.1)) {
      const Eigen::Vector4d gain = pc.col(kTop) / s_innov;
      x += gain * nu;
      pc = (Mat::Identity() - gain * hrow) * pc;
      pc = 0.5 * (pc + pc.transpose()).eval();
      run_rejected = 0;
      if (stuck && std::abs(x[kBit]) > stuck_threshold_rad_s) stuck = false;  // the measurement moved it
      if (stuck) x[kBit] = 0;
    } else {
      ++rejected;
      ++run_rejected;
    }
    xf[k] = x;
    pf[k] = pc;
  }
  phi[n - 1] = Mat::Identity();

  // Fixed-lag RTS: the estimate for k from the filter at k + lag smoothed back to k.
  const double lag_s = o.smoothing_lag_s >= 0 ? o.smoothing_lag_s : 2 * kPi / omega_bit;
  const std::size_t lag = static_cast<std::size_t>(std::lround(lag_s / dt));
  std::vector<Mat> gain(n, Mat::Zero());
  for (std::size_t k = 0; k + 1 < n; ++k)
    gain[k] = pf[k] * phi[k].transpose() * pp[k + 1].ldlt().solve(Mat::Identity());
  e.bit_speed_rad_s.assign(n, kNaN);
  e.bit_speed_band_rad_s.assign(n, kNaN);
  std::vector<double> shaft(n, kNaN), shaft_sigma(n, kNaN);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t last = std::min(n - 1, k + lag);
    Vec xs = xf[last];
    Mat ps = pf[last];
    for (std::size_t j = last; j-- > k;) {
      xs = xf[j] + gain[j] * (xs - xp[j + 1]);
      ps = pf[j] + gain[j] * (ps - pp[j + 1]) * gain[j].transpose();
    }
    e.bit_speed_rad_s[k] = xs[kBit];
    e.bit_speed_band_rad_s[k] = 2 * std::sqrt(std::max(ps(kBit, kBit), 0.0));
    shaft[k] = p.ShaftTorque(xs);
    const Eigen::Vector4d dshaft(m.shaft_stiffness_Nm_per_rad, m.shaft_damping_Nms_per_rad,
                                 -m.shaft_damping_Nms_per_rad, 0);
    shaft_sigma[k] = std::sqrt(std::max(dshaft.dot(ps * dshaft), 0.0));
  }
  // Torque on bit from the bit's balance, J_b w_b' = T_shaft - T_bit, the derivative over a tenth of the bit's period.
  const int half = std::max(1, static_cast<int>(std::lround(0.1 * 2 * kPi / omega_bit / dt)));
  const Smoothed speed = SmoothQuadratic(e.bit_speed_rad_s, dt, half);
  e.bit_torque_Nm.assign(n, kNaN);
  e.bit_torque_band_Nm.assign(n, kNaN);
  e.stuck.assign(n, 0);
  e.wob_N.assign(n, m.weight_on_bit_N);
  e.wob_band_N.assign(n, kNaN);
  for (std::size_t k = 0; k < n; ++k) {
    const double accel = std::isfinite(speed.derivative[k]) ? speed.derivative[k] : 0.0;
    e.bit_torque_Nm[k] = shaft[k] - m.bit_inertia_kgm2 * accel;
    e.bit_torque_band_Nm[k] = 2 * shaft_sigma[k];
    e.stuck[k] = std::abs(e.bit_speed_rad_s[k]) < stuck_threshold_rad_s;
  }
  e.latency_s = static_cast<double>(lag) * dt;
  e.notes.push_back("top speed noise " + ReadableNumber(meas_sigma) + " rad/s (successive differences, after " +
                    (o.despike ? std::string("despiking") : std::string("no despiking")) + "); " +
                    std::to_string(rejected) + " samples rejected as glitches by the filter");
  e.notes.push_back("drive and friction torques uncertain by " + ReadableNumber(torque_sigma) + " N m; " +
                    std::to_string(substeps) + " sub-steps per sample; smoothing lag " + ReadableNumber(e.latency_s) +
                    " s");
  e.notes.push_back("weight on bit: the case's constant (the pendulum has no axial motion); bands: two standard "
                    "deviations of the smoother");
  return e;
}

}  // namespace drillwave::estimation
