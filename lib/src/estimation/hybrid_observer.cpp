#include "drillwave/estimation/hybrid_observer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/validity.hpp"
#include "drillwave/recordings/signals.hpp"
#include "drillwave/estimation/smoothing.hpp"

namespace drillwave::estimation {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The inspection's Hampel setting (signals.hpp, MaskArtefacts): +-0.1 s, 5 robust deviations, grown at 2.
constexpr double kHampelHalfWindowS = 0.1;
// A glitch with two others starting within this time of its start is part of a burst (the encoder dithering).
constexpr double kBurstReachS = 0.2;
constexpr int kBurstNeighbours = 2;
// The regime copy's pull towards the inverted speed, in units of the bit's natural frequency on the shaft.
constexpr double kPullPerNaturalFrequency = 3;

double NaturalFrequency(const LumpedModel& m) { return std::sqrt(m.shaft_stiffness_Nm_per_rad / m.bit_inertia_kgm2); }

// Half-width in samples of each of the low-pass's three boxes (a box is an eighth of the bit's period).
int BoxHalfWidth(const LumpedModel& m, double dt) {
  const double period = 2 * kPi / NaturalFrequency(m);
  return std::max(0, static_cast<int>(std::lround(period / 16 / dt)));
}

int HampelHalfWidth(double dt) { return std::max(2, static_cast<int>(std::lround(kHampelHalfWindowS / dt))); }

// Centred moving average over 2 half + 1 samples; NaN where the window leaves the series or holds a NaN.
std::vector<double> BoxAverage(const std::vector<double>& x, int half) {
  const long n = static_cast<long>(x.size()), h = half;
  std::vector<double> y(x.size(), kNaN);
  double sum = 0;
  long finite_missing = 0;
  for (long i = 0; i < n; ++i) {
    // Window [i - h, i + h]: add i + h, drop i - h - 1.
    if (i == 0) {
      for (long k = 0; k <= std::min(h, n - 1); ++k) std::isfinite(x[k]) ? sum += x[k] : ++finite_missing;
    } else {
      if (i + h < n) std::isfinite(x[i + h]) ? sum += x[i + h] : ++finite_missing;
      if (i - h - 1 >= 0) std::isfinite(x[i - h - 1]) ? sum -= x[i - h - 1] : --finite_missing;
    }
    if (i - h >= 0 && i + h < n && finite_missing == 0) y[i] = sum / static_cast<double>(2 * h + 1);
  }
  return y;
}

struct Run {
  std::size_t first, last;
};

std::vector<Run> FlaggedRuns(const std::vector<char>& flagged) {
  std::vector<Run> runs;
  for (std::size_t i = 0; i < flagged.size(); ++i) {
    if (!flagged[i]) continue;
    if (!runs.empty() && runs.back().last + 1 == i)
      runs.back().last = i;
    else
      runs.push_back({i, i});
  }
  return runs;
}

// Glitches with kBurstNeighbours others starting within kBurstReachS: restored to the raw samples.
int KeepBursts(const std::vector<double>& raw, const std::vector<char>& flagged, double dt, std::vector<double>& x) {
  const std::vector<Run> runs = FlaggedRuns(flagged);
  const auto reach = static_cast<std::size_t>(std::lround(kBurstReachS / dt));
  int kept = 0;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    int neighbours = 0;
    for (std::size_t q = r; q-- > 0 && runs[r].first - runs[q].first <= reach;) ++neighbours;
    for (std::size_t q = r + 1; q < runs.size() && runs[q].first - runs[r].first <= reach; ++q) ++neighbours;
    if (neighbours < kBurstNeighbours) continue;
    for (std::size_t i = runs[r].first; i <= runs[r].last; ++i) x[i] = raw[i], ++kept;
  }
  return kept;
}

// The pendulum's equations as the observer uses them.
class Observer {
 public:
  Observer(const LumpedModel& m, double stuck_threshold)
      : m_(m), threshold_(stuck_threshold), pull_(kPullPerNaturalFrequency * NaturalFrequency(m)) {}

  // The shaft torque the drive law reads off the top speed w and its acceleration a at model time t.
  double MeasuredShaftTorque(double w, double a, double t) const {
    const double drive = m_.drive == LumpedModel::Drive::kTorque ? m_.setpoint.Value(t)
                                                                 : m_.kp * (m_.setpoint.Value(t) - w);
    return drive - m_.top_damping_Nms_per_rad * w - m_.top_inertia_kgm2 * a;
  }

  void Start(double w, double a, double t, double twist, double bit_speed) {
    const double torque = MeasuredShaftTorque(w, a, t);
    inverted_twist_ = twist > -1e299 ? twist : torque / m_.shaft_stiffness_Nm_per_rad;
    twist_ = inverted_twist_;
    bit_ = bit_speed > -1e299 ? bit_speed : w;
    stuck_ = false;
  }

  struct Output {
    double bit_speed, inverted_speed, shaft_torque;
    bool stuck;
  };

  // One sample of length dt (the inputs held over `substeps` sub-steps).
  Output Step(double w, double a, double t, double dt, int substeps) {
    const double torque = MeasuredShaftTorque(w, a, t);
    // Implicit Euler of k phi + c phi' = T (stable, and phi = T / k for an undamped shaft).
    const double k = m_.shaft_stiffness_Nm_per_rad, c = m_.shaft_damping_Nms_per_rad;
    const double twist = (c * inverted_twist_ + dt * torque) / (c + dt * k);
    const double inverted_speed = w - (twist - inverted_twist_) / dt;
    inverted_twist_ = twist;
    const double h = dt / substeps;
    for (int i = 0; i < substeps; ++i) Regime(w, inverted_speed, h);
    return {stuck_ ? 0.0 : inverted_speed, inverted_speed, torque, stuck_};
  }

 private:
  double StaticLimit(double torque) const {
    return torque > 0 ? m_.friction.StaticPositive() : m_.friction.StaticNegative();
  }

  // The regime copy of the bit: its equation pulled towards the inverted speed, stopped by the set-valued friction.
  void Regime(double w, double inverted_speed, double h) {
    const double k = m_.shaft_stiffness_Nm_per_rad, c = m_.shaft_damping_Nms_per_rad;
    if (stuck_) {
      const double shaft = k * twist_ + c * w;
      const double dir = shaft > 0 ? 1.0 : -1.0;
      // Released when the friction can no longer hold it and the measurement shows it moving that way.
      if (std::abs(shaft) > StaticLimit(shaft) && dir * inverted_speed > threshold_) stuck_ = false;
    }
    if (!stuck_) {
      const double shaft = k * twist_ + c * (w - bit_);
      const double friction = bit_ == 0 ? m_.friction.SlipTorque((shaft > 0 ? 1.0 : -1.0) * 1e-12)
                                        : m_.friction.SlipTorque(bit_);
      const double next = bit_ + h * (shaft - m_.bit_damping_Nms_per_rad * bit_ - friction) / m_.bit_inertia_kgm2 +
                          h * pull_ * (inverted_speed - bit_);
      const bool reaches_zero = bit_ == 0 || next * bit_ <= 0;
      if (m_.friction.IsSetValued() && reaches_zero && std::abs(shaft) <= StaticLimit(shaft)) {
        stuck_ = true;
        bit_ = 0;
      } else {
        bit_ = next;
      }
    }
    if (stuck_) bit_ = 0;
    twist_ += h * (w - bit_);
  }

  const LumpedModel& m_;
  double threshold_, pull_;
  double inverted_twist_ = 0, twist_ = 0, bit_ = 0;
  bool stuck_ = false;
};

int Substeps(const LumpedModel& m, double dt) {
  const double rate = std::max({kPullPerNaturalFrequency * NaturalFrequency(m),
                                m.shaft_damping_Nms_per_rad / m.bit_inertia_kgm2,
                                m.bit_damping_Nms_per_rad / m.bit_inertia_kgm2, NaturalFrequency(m)});
  return std::max(1, static_cast<int>(std::ceil(dt * rate / 0.1)));
}

}  // namespace

bool HasInvertibleDrive(const LumpedModel& m) {
  return m.drive == LumpedModel::Drive::kTorque || (m.drive == LumpedModel::Drive::kPiSpeed && m.ki == 0);
}

TopSpeedCleaning CleanTopSpeed(const std::vector<double>& raw, double dt, const LumpedModel& m, bool despike) {
  TopSpeedCleaning c;
  std::vector<double> x = raw;
  if (despike) {
    std::vector<double> magnitude;
    for (double v : raw) magnitude.push_back(std::abs(v));
    const recordings::HampelResult h =
        recordings::HampelFilter(raw, HampelHalfWidth(dt), 5, 0.05 * recordings::Median(magnitude), 2);
    x = h.cleaned;
    c.burst_samples_kept = KeepBursts(raw, h.flagged, dt, x);
    c.glitches_masked = static_cast<int>(std::count(h.flagged.begin(), h.flagged.end(), 1)) - c.burst_samples_kept;
  }
  const int half = BoxHalfWidth(m, dt);
  c.speed = BoxAverage(BoxAverage(BoxAverage(x, half), half), half);
  c.acceleration.assign(x.size(), kNaN);
  for (std::size_t i = 1; i + 1 < x.size(); ++i) c.acceleration[i] = (c.speed[i + 1] - c.speed[i - 1]) / (2 * dt);
  return c;
}

double HybridLatency(const LumpedModel& m, double dt) {
  // Hampel's half window, the burst rule's reach (plus a glitch's length, about a tenth of it), three boxes' halves
  // and the acceleration's central difference.
  return HampelHalfWidth(dt) * dt + 1.1 * kBurstReachS + (3 * BoxHalfWidth(m, dt) + 1) * dt;
}

bool HybridObserverOptions::IsValid(std::string* error) const {
  return FiniteField(error, "model_time_offset_s", model_time_offset_s) &&
         FiniteField(error, "initial_bit_speed_rad_s", initial_bit_speed_rad_s) &&
         FiniteField(error, "initial_twist_rad", initial_twist_rad);
}

BitEstimate EstimateHybrid(const LumpedModel& m, const SurfaceSignals& s, double stuck_threshold_rad_s,
                           const HybridObserverOptions& o) {
  ThrowIfInvalid(o);
  if (s.top_speed_rad_s.empty()) throw ParameterError("from", "the hybrid observer needs the top speed");
  if (!HasInvertibleDrive(m)) throw std::invalid_argument("EstimateHybrid: the drive law does not give the torque");
  const std::size_t n = s.time_s.size();
  const double dt = (s.time_s.back() - s.time_s.front()) / static_cast<double>(n - 1);
  const TopSpeedCleaning top = CleanTopSpeed(s.top_speed_rad_s, dt, m, o.despike);
  Observer observer(m, stuck_threshold_rad_s);
  const int substeps = Substeps(m, dt);

  BitEstimate e;
  e.time_s = s.time_s;
  e.stuck_threshold_rad_s = stuck_threshold_rad_s;
  e.method = "hybrid observer on the two-mass pendulum: drive-law inversion of the top speed, stick-slip regimes";
  e.bit_speed_rad_s.assign(n, kNaN);
  e.bit_speed_band_rad_s.assign(n, kNaN);
  e.bit_torque_Nm.assign(n, kNaN);
  e.bit_torque_band_Nm.assign(n, kNaN);
  e.wob_N.assign(n, m.weight_on_bit_N);
  e.wob_band_N.assign(n, kNaN);
  e.stuck.assign(n, 0);
  std::vector<double> shaft(n, kNaN), slip_disagreement;
  bool started = false;
  for (std::size_t k = 0; k < n; ++k) {
    const double w = top.speed[k], a = top.acceleration[k], t = s.time_s[k] - o.model_time_offset_s;
    if (!std::isfinite(w) || !std::isfinite(a)) continue;
    if (!started) observer.Start(w, a, t, o.initial_twist_rad, o.initial_bit_speed_rad_s), started = true;
    const Observer::Output out = observer.Step(w, a, t, dt, substeps);
    e.bit_speed_rad_s[k] = out.bit_speed;
    e.stuck[k] = out.stuck || std::abs(out.bit_speed) < stuck_threshold_rad_s;
    shaft[k] = out.shaft_torque;
    if (!out.stuck) slip_disagreement.push_back(std::abs(out.inverted_speed - out.bit_speed));
  }
  // Band: what separates the output from the regime copy while slipping (two independent readings of the bit),
  // as a robust standard deviation.
  const double sigma = slip_disagreement.empty() ? 0.0 : 1.4826 * recordings::Median(slip_disagreement);
  const double shaft_sigma = std::max(m.kp, m.shaft_damping_Nms_per_rad) * sigma;
  // Torque on bit from the bit's balance J_b w_b' = T_shaft - T_bit, the derivative over a tenth of the bit's period.
  const int half = std::max(1, static_cast<int>(std::lround(0.1 * 2 * kPi / NaturalFrequency(m) / dt)));
  const Smoothed speed = SmoothQuadratic(e.bit_speed_rad_s, dt, half);
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(e.bit_speed_rad_s[k])) continue;
    e.bit_speed_band_rad_s[k] = e.stuck[k] ? stuck_threshold_rad_s : 2 * sigma;
    const double accel = std::isfinite(speed.derivative[k]) ? speed.derivative[k] : 0.0;
    e.bit_torque_Nm[k] = shaft[k] - m.bit_inertia_kgm2 * accel;
    e.bit_torque_band_Nm[k] = 2 * shaft_sigma;
  }
  e.latency_s = HybridLatency(m, dt);
  e.notes.push_back("top speed: " + std::to_string(top.glitches_masked) + " glitch samples masked (Hampel), " +
                    std::to_string(top.burst_samples_kept) +
                    " kept as bursts (three or more glitches within " + ReadableNumber(kBurstReachS) +
                    " s: an encoder dithering at rest), low-passed by three boxes of " +
                    ReadableNumber((2 * BoxHalfWidth(m, dt) + 1) * dt) + " s");
  e.notes.push_back("regime copy pulled towards the inverted speed at " +
                    ReadableNumber(kPullPerNaturalFrequency * NaturalFrequency(m)) + " 1/s; " +
                    std::to_string(substeps) + " sub-steps per sample; band: the inverted speed against the regime "
                    "copy while slipping (two standard deviations), the stuck threshold while stuck");
  e.notes.push_back("weight on bit: the case's constant (the pendulum has no axial motion)");
  return e;
}

}  // namespace drillwave::estimation
