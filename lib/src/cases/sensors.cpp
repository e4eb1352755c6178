#include "drillwave/cases/sensors.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "drillwave/core/error.hpp"
#include "drillwave/core/sampled.hpp"

namespace drillwave::cases {

using io::JsonReader;
using Range = io::Range;

namespace {

// The reading of a channel sampled at times t at any time s: the mean over [s - window, s] of its linear interpolant
// (held at the end values outside t), or for a window of 0 the interpolant at s. The running integral of the
// interpolant is kept at every sample, so a reading, delayed or not, costs two binary searches.
class WindowedReading {
 public:
  WindowedReading(const std::vector<double>& t, const std::vector<double>& values, double window_s)
      : t_(t), values_(values), window_s_(window_s), integral_(t.size(), 0.0) {
    for (std::size_t k = 1; k < t.size(); ++k)
      integral_[k] = integral_[k - 1] + 0.5 * (t[k] - t[k - 1]) * (values[k] + values[k - 1]);
  }
  // Readings are asked in time order, so each end of the window keeps its place in t (the result is the same as a
  // binary search's; the search took most of a measured channel's cost at outputs five times finer than the samples).
  double operator()(double s) {
    if (window_s_ <= 0) return InterpolateSampled(t_, values_, s);
    return (Integral(s, end_) - Integral(s - window_s_, begin_)) / window_s_;
  }

 private:
  // From t.front() to s (negative before it); `k` the index of the first t > s last time, moved to this s's.
  double Integral(double s, std::size_t& k) const {
    if (s <= t_.front()) return (s - t_.front()) * values_.front();
    if (s >= t_.back()) return integral_.back() + (s - t_.back()) * values_.back();
    k = std::clamp<std::size_t>(k, 1, t_.size() - 1);
    while (t_[k] <= s) ++k;
    while (t_[k - 1] > s) --k;
    const double h = s - t_[k - 1], slope = (values_[k] - values_[k - 1]) / (t_[k] - t_[k - 1]);
    return integral_[k - 1] + h * (values_[k - 1] + 0.5 * slope * h);
  }
  const std::vector<double>& t_;
  const std::vector<double>& values_;
  double window_s_;
  std::vector<double> integral_;
  std::size_t begin_ = 1, end_ = 1;
};

}  // namespace

SensorSet ReadSensors(const JsonReader& block) {
  SensorSet set;
  set.seed = static_cast<unsigned long long>(block.Integer("seed", 0, 2147483647, 1));
  const JsonReader channels = block.Object("channels");
  for (const auto& item : block.Raw("channels").items()) {
    const JsonReader s = channels.Object(item.key());
    SensorModel m;
    m.channel = item.key();
    m.time_constant_s = s.Number("time_constant_s", Range::Between(0, 1e4), 0.0);
    m.window_s = s.Number("window_s", Range::Between(0, 1e4), 0.0);
    m.delay_s = s.Number("delay_s", Range::Between(0, 1e4), 0.0);
    m.hold_s = s.Number("hold_s", Range::Between(0, 1e4), 0.0);
    m.noise_std = s.Number("noise_std", Range::NonNegative(), 0.0);
    m.bits = s.Integer("bits", 0, 32, 0);
    m.downhole_noise_std = s.Number("downhole_noise_std", Range::NonNegative(), 0.0);
    if (m.bits > 0) {
      const std::vector<double> range = s.NumberArray("range", Range::Any());
      if (range.size() != 2 || !(range[0] < range[1]))
        throw InputError(s.PathOf("range"), "expected [lowest, highest] code value with lowest < highest");
      m.code_min = range[0], m.code_max = range[1];
      m.bit_rate_bps = s.Number("bit_rate_bps", Range::Positive(), 0.0);
      if (m.bit_rate_bps > 0 && s.Has("hold_s"))
        throw InputError(s.PathOf("hold_s"), "with bit_rate_bps the hold is the frame, bits / bit_rate_bps = " +
                                                 std::to_string(m.bits / m.bit_rate_bps) + " s; give one of them");
    } else {
      for (const char* key : {"range", "bit_rate_bps", "downhole_noise_std"})
        if (s.Has(key)) throw InputError(s.PathOf(key), "needs \"bits\" (1 to 32): the code it belongs to");
    }
    s.Finish();
    set.sensors.push_back(m);
  }
  block.Finish();
  return set;
}

double SensorModel::Quantized(double x) const {
  if (bits <= 0) return x;
  const double levels = std::ldexp(1.0, bits) - 1, step = (code_max - code_min) / levels;
  return code_min + step * std::clamp(std::round((x - code_min) / step), 0.0, levels);
}

std::vector<double> Measure(const SensorModel& sensor, const std::vector<double>& t, const std::vector<double>& values,
                            unsigned long long seed) {
  if (t.empty()) return {};
  // Low-pass, exact for an input held between samples; settled at the first value.
  std::vector<double> filtered(values);
  if (sensor.time_constant_s > 0)
    for (std::size_t k = 1; k < t.size(); ++k) {
      const double a = 1 - std::exp(-(t[k] - t[k - 1]) / sensor.time_constant_s);
      filtered[k] = filtered[k - 1] + a * (values[k] - filtered[k - 1]);
    }
  WindowedReading reading(t, filtered, sensor.window_s);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> measured(t.size());
  // The value a sample carries: read at the sensor, its downhole noise, its code. The downhole noise is drawn only
  // where there is one, so that a sensor without it keeps the noise stream it always had.
  auto sent_value = [&](double at) {
    const double downhole = sensor.downhole_noise_std > 0 ? sensor.downhole_noise_std * noise(rng) : 0.0;
    return sensor.Quantized(reading(at) + downhole);
  };
  const double period = sensor.SamplePeriod();
  // A coded sample is decoded when its frame has arrived: one frame after it was taken, besides the delay.
  const double latency = sensor.delay_s + (sensor.SentInFrames() ? period : 0.0);
  long held = -1;  // index of the telemetry sample last received
  double held_value = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double sent = t[k] - latency;  // when what arrives now left the sensor
    if (period > 0) {
      const long j = std::max(0L, static_cast<long>(std::floor((sent - t.front()) / period + 1e-9)));
      while (held < j) {  // draw noise for every sample, received or skipped, so the noise does not depend on the output grid
        ++held;
        const double value = sent_value(t.front() + held * period);
        held_value = value + sensor.noise_std * noise(rng);
      }
      measured[k] = held_value;
    } else {
      const double value = sent_value(sent);
      measured[k] = value + (sensor.noise_std > 0 ? sensor.noise_std * noise(rng) : 0.0);
    }
  }
  return measured;
}

void ApplySensors(const SensorSet& set, RunResult& result) {
  for (std::size_t i = 0; i < set.sensors.size(); ++i) {
    const SensorModel& sensor = set.sensors[i];
    const auto it = std::find_if(result.channels.begin(), result.channels.end(),
                                 [&](const Channel& c) { return c.name == sensor.channel; });
    if (it == result.channels.end()) {
      std::string names;
      for (const Channel& c : result.channels) names += (names.empty() ? "" : ", ") + c.name;
      throw InputError("/sensors/channels/" + sensor.channel, "this model has no such channel; it has " + names);
    }
    // Each sensor its own noise stream, so adding a sensor does not change the others.
    std::vector<double> measured = Measure(sensor, result.time_s, it->values, set.seed + 7919 * i);
    for (auto& panel : result.plot_panels)
      if (std::find(panel.begin(), panel.end(), sensor.channel) != panel.end()) panel.push_back(sensor.channel + "_measured");
    result.channels.push_back({sensor.channel + "_measured", std::move(measured)});
  }
}

}  // namespace drillwave::cases
