#include "drillwave/estimation/wave_string_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/median.hpp"
#include "drillwave/estimation/smoothing.hpp"

namespace drillwave::estimation {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<WavePiece> Pieces(const WaveStringModel& m, bool torsion) {
  std::vector<WavePiece> pieces;
  for (const WaveSection& s : m.sections) {
    const int n = std::max(1, s.subsections);
    const double piece = s.length_m / n;
    for (int i = 0; i < n; ++i)
      pieces.push_back(torsion ? WavePiece{s.torsional_impedance, piece / s.torsional_speed_m_s,
                                           s.torsional_damping_per_m * piece}
                               : WavePiece{s.axial_impedance, piece / s.axial_speed_m_s, s.axial_damping_per_m * piece});
  }
  return pieces;
}

// Half-width in samples of the smoothing window: a quarter of the bit's time constant against the string
// (inertia / impedance), the fastest the bit's speed can change while it slides; at least one sample.
int HalfWidth(double bit_time_constant_s, double dt) {
  return std::max(1, static_cast<int>(std::lround(0.25 * bit_time_constant_s / dt)));
}

// Standard deviation of x about its 5-s centred moving mean (set-point changes left out): how far it swings.
double SwingStd(const std::vector<double>& x, double dt) {
  const long n = static_cast<long>(x.size()), h = std::max(1L, std::lround(2.5 / dt));
  double sum2 = 0;
  long count = 0;
  for (long i = h; i + h < n; i += std::max(1L, h / 25)) {
    double mean = 0;
    long m = 0;
    for (long j = i - h; j <= i + h; j += std::max(1L, h / 50))
      if (std::isfinite(x[j])) mean += x[j], ++m;
    if (m == 0 || !std::isfinite(x[i])) continue;
    sum2 += std::pow(x[i] - mean / static_cast<double>(m), 2);
    ++count;
  }
  return count ? std::sqrt(sum2 / static_cast<double>(count)) : 0.0;
}

}  // namespace

std::vector<WavePiece> TorsionalPieces(const WaveStringModel& model) { return Pieces(model, true); }
std::vector<WavePiece> AxialPieces(const WaveStringModel& model) { return Pieces(model, false); }

BitEstimate EstimateWaveString(const WaveStringModel& model, const SurfaceSignals& s, double stuck_threshold_rad_s) {
  if (s.top_torque_Nm.empty())
    throw ParameterError("from", "the wave-string estimator needs the top torque as well as the top speed (e.g. "
                               "top_rpm,top_torque_kNm,hookload_kN)");
  const std::size_t n = s.time_s.size();
  const double dt = (s.time_s.back() - s.time_s.front()) / static_cast<double>(n - 1);
  BitEstimate e;
  e.time_s = s.time_s;
  e.stuck_threshold_rad_s = stuck_threshold_rad_s;
  e.method = "downward continuation of the torsional (and axial) waves from the top's measured speed and torque";

  // The string's torque at the top: the motor's torque less what accelerates the top drive, J_td w'. A stiff PI drive
  // (the case's gain holds the speed within what the torque's swing allows) gives J w' = -(J / kp)(T_m' - ki e), so
  // T_0(t) = T_m(t + J / kp) to first order: a time advance that, unlike the derivative of the measured speed (whose
  // noise J w' multiplies by J / dt), adds no noise. A drive that lets the speed swing further than that is softer
  // than the case says (by an order of magnitude: a stiff drive's ripple is within a few times the torque's swing over
  // kp and the noise): then w' is read from the measured speed.
  const double z_bottom = TorsionalPieces(model).back().impedance;
  std::vector<double> top_string_torque = s.top_torque_Nm;
  double advance = 0;
  if (model.top_inertia_kgm2 > 0) {
    const int top_half = HalfWidth(4 * model.bit_inertia_kgm2 / z_bottom, dt);
    const Smoothed top = SmoothQuadratic(s.top_speed_rad_s, dt, top_half);
    const double swing = SwingStd(top.value, dt), torque_swing = SwingStd(s.top_torque_Nm, dt);
    const double allowed = model.top_kp > 0 ? torque_swing / model.top_kp : INFINITY;
    const double noise = NoiseStd(s.top_speed_rad_s) * top.noise_gain;
    // The advance is a first-order lag's: it holds while J / kp is short against the string's travel time (a fitted
    // soft drive's kp of 95 N m s/rad on a 2500 kg m^2 top makes it 26 s, and the stiff reading fails: dev rec05's
    // diagnosed case gave 102 rpm RMS, stuck F1 0.06).
    const double travel_time = TravelTime(TorsionalPieces(model));
    if (model.top_kp > 0 && model.top_inertia_kgm2 / model.top_kp < travel_time &&
        swing <= 10 * std::max(allowed, noise)) {
      advance = model.top_inertia_kgm2 / model.top_kp;
      top_string_torque = Shifted(s.top_torque_Nm, dt, advance);
      e.notes.push_back("stiff drive (top speed swing " + ReadableNumber(swing) + " rad/s within 10 times what kp allows, " +
                        ReadableNumber(std::max(allowed, noise)) + "): string torque at the top = the motor torque " +
                        ReadableNumber(advance) + " s later (top inertia / kp)");
    } else {
      // J_td / Z (seconds for a top drive on a pipe) multiplies the slope's noise, so the slope is a least-squares
      // quartic's over +-tau, the string's travel time: a soft top swings with the string's modes, the slowest a
      // quarter wave of period 4 tau, which a quartic over half that period follows where a quadratic's straight-line
      // slope flattens its turns (the soft-drive recordings of ../shared: bit-speed RMS 19.3 -> 9.0 rpm, stuck F1
      // 0.25 -> 0.88 on train rec18 against a quadratic over +-4 J_b / Z, docs/results.md).
      const int slope_half = std::max(2, static_cast<int>(std::lround(travel_time / dt)));
      const Smoothed top_slope = SmoothPolynomial(s.top_speed_rad_s, dt, slope_half, 4);
      for (std::size_t i = 0; i < n; ++i)
        top_string_torque[i] = s.top_torque_Nm[i] - model.top_inertia_kgm2 * top_slope.derivative[i];
      advance = slope_half * dt;
      const bool slow = model.top_kp > 0 && model.top_inertia_kgm2 / model.top_kp >= travel_time;
      e.notes.push_back(
          "soft drive (" +
          (slow ? "top inertia / kp " + ReadableNumber(model.top_inertia_kgm2 / model.top_kp) +
                      " s, not short against the string's travel time " + ReadableNumber(travel_time) + " s"
                : "top speed swing " + ReadableNumber(swing) + " rad/s, more than 10 times the " +
                      ReadableNumber(std::max(allowed, noise)) + " the case's kp allows") +
          "): the top inertia's torque from the measured speed's slope, a quartic's over +-" + ReadableNumber(advance) +
          " s (the string's travel time)");
    }
  }
  const std::vector<WavePiece> torsion = TorsionalPieces(model);
  const WaveEnd bit = ContinueDownward(s.time_s, s.top_speed_rad_s, top_string_torque, torsion);
  const int half = HalfWidth(model.bit_inertia_kgm2 / z_bottom, dt);
  const Smoothed speed = SmoothQuadratic(bit.velocity, dt, half);
  const Smoothed torque = SmoothQuadratic(bit.force, dt, half);
  e.latency_s = TravelTime(torsion) + advance + half * dt;

  // Noise carried down: the bit's speed is half the sum of two top speeds and of two torques over Z (lossless).
  const double speed_noise = NoiseStd(s.top_speed_rad_s), torque_noise = NoiseStd(s.top_torque_Nm);
  const double at_bit = std::sqrt(0.5 * (speed_noise * speed_noise + std::pow(torque_noise / z_bottom, 2)));
  const double speed_sigma = at_bit * speed.noise_gain;
  const double accel_sigma = at_bit * speed.derivative_noise_gain;
  const double torque_sigma = std::hypot(z_bottom * at_bit * torque.noise_gain, model.bit_inertia_kgm2 * accel_sigma);
  e.notes.push_back("sensor noise read from successive differences: top speed " + ReadableNumber(speed_noise) +
                    " rad/s, top torque " + ReadableNumber(torque_noise) + " N m; bands are two standard deviations "
                    "of that noise carried to the bit (model errors not included)");
  e.bit_speed_rad_s = speed.value;
  e.bit_torque_Nm.assign(n, kNaN);
  e.bit_speed_band_rad_s.assign(n, kNaN);
  e.bit_torque_band_Nm.assign(n, kNaN);
  e.stuck.assign(n, 0);
  // The direction the drive turns the string (the sign of the median top speed).
  std::vector<double> finite_top;
  for (double v : s.top_speed_rad_s)
    if (std::isfinite(v)) finite_top.push_back(v);
  const double forward = Median(std::move(finite_top)) < 0 ? -1.0 : 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(speed.value[i])) continue;
    // The bit: J_b w_b' = T(L) - torque on bit.
    e.bit_torque_Nm[i] = torque.value[i] - model.bit_inertia_kgm2 * speed.derivative[i];
    e.bit_speed_band_rad_s[i] = 2 * speed_sigma;
    e.bit_torque_band_Nm[i] = 2 * torque_sigma;
    // Stuck when the estimate does not turn forward by more than the threshold within its band: a stuck bit's
    // estimate is zero plus noise, and it swings below zero around each stop, where the smoothing rings after the
    // sudden halt (the bit itself does not turn back: the string winds up forward while the rock holds it). Counted as
    // turning, those swings cost a tenth of the stuck samples (dev rec05: 583 of 3 047, 408 of them in the first and
    // last tenth of their stick).
    e.stuck[i] = forward * speed.value[i] < stuck_threshold_rad_s + e.bit_speed_band_rad_s[i];
  }

  e.wob_N.assign(n, model.weight_on_bit_N);
  e.wob_band_N.assign(n, kNaN);
  if (s.hook_load_N.empty() || !(model.hoist_mass_kg > 0)) {
    e.notes.push_back("weight on bit: the case's steady W0 (no hook load measured)");
    return e;
  }
  // Axial: the hook load is H + M_td a_top (BASELINE.md), so the block's acceleration gives the top's velocity; its
  // slow drift (integrated noise) is removed by a leaky integral over twice the axial round trip, the slowest motion
  // the waves carry between the bit and the top.
  const std::vector<WavePiece> axial = AxialPieces(model);
  const double round_trip = 2 * TravelTime(axial);
  double hook_force = model.hook_force_N;
  if (!(hook_force > 0)) {
    double sum = 0;
    for (double h : s.hook_load_N) sum += h;
    hook_force = sum / static_cast<double>(n);
    e.notes.push_back("hook force: the recording's mean hook load (no set-point given)");
  }
  const double leak = 2 * round_trip;
  std::vector<double> top_velocity(n, 0), top_compression(n);
  double v = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dn = s.hook_load_N[i] - hook_force;
    top_compression[i] = -dn;  // the dynamic tension at the hook, as a compression carried down
    if (i > 0) v += dt * (dn / model.hoist_mass_kg - v / leak);
    top_velocity[i] = v;
  }
  const WaveEnd bottom = ContinueDownward(s.time_s, top_velocity, top_compression, axial);
  const double za_bottom = axial.back().impedance;
  const int axial_half = HalfWidth(model.bit_mass_kg / za_bottom, dt);
  const Smoothed axial_speed = SmoothQuadratic(bottom.velocity, dt, axial_half);
  const Smoothed compression = SmoothQuadratic(bottom.force, dt, axial_half);
  const double hook_noise = NoiseStd(s.hook_load_N);
  const double wob_sigma = hook_noise * std::sqrt(0.5) * 2 * compression.noise_gain;  // down- and up-going halves
  for (std::size_t i = 0; i < n; ++i) {
    // The bit: M_b a = -dN(L) - dW: the weight on bit is W0 plus the dynamic compression less the bit's inertia.
    e.wob_N[i] = model.weight_on_bit_N + compression.value[i] - model.bit_mass_kg * axial_speed.derivative[i];
    if (std::isfinite(e.wob_N[i])) e.wob_band_N[i] = 2 * wob_sigma;
  }
  e.latency_s = std::max(e.latency_s, TravelTime(axial) + axial_half * dt);
  e.notes.push_back("weight on bit: W0 plus the axial waves continued from the hook load (hook force " +
                    ReadableNumber(hook_force) + " N); hook load noise " + ReadableNumber(hook_noise) + " N");
  return e;
}

}  // namespace drillwave::estimation
