// Features a chaotic model can be asked to reproduce: each is checked on signals whose answer is known (a sine's
// period and amplitude, the content above 2 Hz, a delayed copy's lag, white noise's level), and the distance on twins
// and on a changed signal.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/diagnosis/features.hpp"

namespace drillwave::diagnosis {
namespace {


// An empty 100-Hz recording of these channels.
Recording Empty(const std::vector<std::string>& names) {
  Recording r;
  r.source = "synthetic";
  r.sample_interval_s = 0.01;
  r.names = names;
  r.channels.resize(names.size());
  return r;
}

// 100 Hz, `seconds` long: a bit speed oscillating with `period` about 60 rpm, a surface torque leading it by
// `lag`, white noise of `noise` std on both.
Recording Oscillation(double seconds, double period, double lag, double noise, unsigned seed, double amplitude = 30) {
  Recording r = Empty({"bit_rpm", "top_torque_kNm"});
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, noise);
  for (int i = 0; i < static_cast<int>(seconds * 100); ++i) {
    const double t = 0.01 * i;
    r.time_s.push_back(t);
    r.channels[0].push_back(60 + amplitude * std::sin(2 * kPi * (t - lag) / period) + n(rng));
    r.channels[1].push_back(5 + 1 * std::sin(2 * kPi * t / period) + 0.01 * n(rng));
  }
  return r;
}

// A period is read to 5 % of itself and to no better than five samples: a clean 0.378-s oscillation (the UFRJ rig's)
// logged at 1 kHz has the 5 % scale (0.0189 s); logged at 100 Hz, as the synthetic recordings are, the five samples'
// 0.05 s.
TEST(Features, APeriodsScaleIsFivePercentOrFiveSamples) {
  for (const double dt : {0.001, 0.01}) {
    Recording r = Empty({"bit_rpm"});
    r.sample_interval_s = dt;
    for (int i = 0; i * dt < 30; ++i) {
      r.time_s.push_back(i * dt);
      r.channels[0].push_back(60 + 50 * std::sin(2 * kPi * i * dt / 0.378));
    }
    const FeatureSet features = MeasureFeatures(r, 2, 28);
    const Feature* period = features.Find("period_s");
    ASSERT_NE(period, nullptr);
    EXPECT_NEAR(period->value, 0.378, 0.005) << dt;
    EXPECT_DOUBLE_EQ(period->scale, dt < 0.005 ? 0.05 * period->value : 0.05) << dt;
  }
}

TEST(Features, PeriodLagAndLevelsOfAKnownOscillation) {
  const Recording r = Oscillation(120, 3.2, 0.7, 0.5, 1);
  const FeatureSet f = MeasureFeatures(r, 10, 110);
  EXPECT_NEAR(f.Value("period_s"), 3.2, 0.02);
  EXPECT_NEAR(f.Value("torque_to_bit_lag_s"), 0.7, 0.02);
  EXPECT_NEAR(f.Value("bit_rpm mean"), 60, 0.1);
  EXPECT_NEAR(f.Value("bit_rpm std"), 30 / std::sqrt(2.0), 0.2);  // a sine's std, the noise mostly smoothed away
  EXPECT_EQ(f.Value("stick_fraction"), 0.0);                      // never below 5 % of 60 rpm
  // The line at the rotation frequency (1 Hz at 60 rpm) is absent from a 3.2-s oscillation.
  EXPECT_LT(f.Value("bit_rpm rotation_amplitude"), 1.0);
}

// A lab rig's laws read off its channels: a bit sticking and slipping under friction that falls 0.01 N m per rpm while
// slipping, driven through a drive whose speed droops 40 rpm per N m. The slopes are the laws' (up to the noise and
// the 50-ms smoothing), and absent without a channel named as the torque on bit.
TEST(Features, TheFrictionSlopeAndTheDrivesDroopOfARig) {
  Recording r = Empty({"top_rpm", "bit_rpm", "tob_Nm"});
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < 6000; ++i) {
    const double t = 0.01 * i, phase = std::fmod(t, 0.8) / 0.8;
    const double bit = phase < 0.2 ? 0.0 : 160 * std::sin(kPi * (phase - 0.2) / 0.8);  // stuck a fifth of the time
    const double tob = phase < 0.2 ? 2.0 + 5 * phase : 3.0 - 0.01 * bit + 0.02 * n(rng);
    r.time_s.push_back(t);
    r.channels[0].push_back(150 - 40 * tob + 0.5 * n(rng));
    r.channels[1].push_back(bit);
    r.channels[2].push_back(tob);
  }
  FeatureOptions o;
  EXPECT_FALSE(std::isfinite(MeasureFeatures(r, 0, 60, o).Value(kFrictionSlope)));
  o.bit_torque = "tob_Nm";
  const FeatureSet f = MeasureFeatures(r, 0, 60, o);
  EXPECT_NEAR(f.Value(kFrictionSlope), -0.01, 0.001);
  EXPECT_NEAR(f.Value(kDriveDroop), -40, 1);
}

TEST(Features, RotationLineOfAWhirlIsMeasured) {
  Recording r = Oscillation(60, 3.2, 0, 0.2, 2, 0);
  for (std::size_t i = 0; i < r.time_s.size(); ++i) r.channels[0][i] += 4 * std::cos(2 * kPi * 1.0 * r.time_s[i]);
  EXPECT_NEAR(MeasureFeatures(r, 0, 60).Value("bit_rpm rotation_amplitude"), 4, 0.1);
}

TEST(Features, StickFractionCountsTheTimeAtRest) {
  Recording r = Oscillation(100, 4, 0, 0.1, 3);
  // Clip the bottom of the oscillation to zero: the bit rests where 60 + 70 sin < 0, a known share of each period.
  for (double& v : r.channels[0]) v = std::max(0.0, 60 + (v - 60) * 70.0 / 30.0);
  // Stuck below 5 % of the mean speed: 60 + 70 sin < threshold over 1/2 - asin((60 - threshold) / 70) / pi of the time.
  double mean = 0;
  for (double v : r.channels[0]) mean += v / r.channels[0].size();
  const double threshold = 0.05 * mean;
  const double rest = 0.5 - std::asin((60 - threshold) / 70) / kPi;
  EXPECT_NEAR(MeasureFeatures(r, 0, 100).Value("stick_fraction"), rest, 0.005);
}

TEST(Features, TheFastPartIsTheContentAboveTwoHertzWithoutTheCyclesHarmonics) {
  // A stick-slip-like cycle of 0.35 Hz with four harmonics, all below the 2-Hz edge, and a small 5-Hz vibration: the
  // fast part is the vibration's rms alone. (A 0.5-s moving average's residual lets the harmonics through: here it
  // would read more than the vibration's rms five times over.)
  Recording r = Empty({"top_torque_kNm"});
  for (int i = 0; i < 6000; ++i) {
    const double t = 0.01 * i;
    double v = 9;
    for (int k = 1; k <= 5; ++k) v += (2.0 / k) * std::sin(2 * kPi * 0.35 * k * t + k);
    r.time_s.push_back(t);
    r.channels[0].push_back(v + 0.1 * std::sin(2 * kPi * 5 * t));
  }
  // The 5-Hz line is in the fast band's upper half (4.5-10 Hz), nothing in its lower half (2-4.5 Hz).
  EXPECT_NEAR(MeasureFeatures(r, 0, 60).Value("top_torque_kNm fast_high_std"), 0.1 / std::sqrt(2.0), 0.002);
  EXPECT_LT(MeasureFeatures(r, 0, 60).Value("top_torque_kNm fast_low_std"), 0.01);
  // A channel that is not the drive's reads the whole band in one.
  Recording bit = r;
  bit.names = {"wob_kN"};
  EXPECT_NEAR(MeasureFeatures(bit, 0, 60).Value("wob_kN fast_std"), 0.1 / std::sqrt(2.0), 0.002);
  EXPECT_FALSE(std::isfinite(MeasureFeatures(bit, 0, 60).Value("wob_kN fast_high_std")));
  // A window of a prime number of samples (4751: the spectrum is zero-padded to a power of two) reads the same.
  EXPECT_NEAR(MeasureFeatures(r, 0, 47.5).Value("top_torque_kNm fast_high_std"), 0.1 / std::sqrt(2.0), 0.002);
  for (double& v : r.channels[0]) v = 9 + 3 * std::sin(2 * kPi * 1.75 * (&v - r.channels[0].data()) * 0.01);
  EXPECT_LT(MeasureFeatures(r, 0, 60).Value("top_torque_kNm fast_low_std"), 0.01);  // a 3-kN m line at 1.75 Hz
  for (double& v : r.channels[0]) v = 9 + 0.2 * std::sin(2 * kPi * 3 * (&v - r.channels[0].data()) * 0.01);
  EXPECT_NEAR(MeasureFeatures(r, 0, 60).Value("top_torque_kNm fast_low_std"), 0.2 / std::sqrt(2.0), 0.004);
  EXPECT_LT(MeasureFeatures(r, 0, 60).Value("top_torque_kNm fast_high_std"), 0.01);  // a 3-Hz line
}

TEST(Features, OffBottomShareIsTheTimeTheWeightOnBitIsGone) {
  // 100 kN on the bottom, nothing for 0.3 s of every second (a bounce), 1 kN of noise.
  Recording r = Empty({"wob_kN"});
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int i = 0; i < 6000; ++i) {
    r.time_s.push_back(0.01 * i);
    r.channels[0].push_back((i % 100 < 30 ? 0.0 : 100.0) + noise(rng));
  }
  // The 50-ms average (7 samples) lifts the three samples next to each edge above 5 % of the mean: 24 of 100 remain.
  EXPECT_NEAR(OffBottomShare(r, 0, 60), 0.24, 0.002);
  for (double& v : r.channels[0]) v = 100 + noise(rng);
  EXPECT_EQ(OffBottomShare(r, 0, 60), 0.0);
  EXPECT_TRUE(std::isnan(OffBottomShare(Empty({"bit_rpm"}), 0, 60)));
}

TEST(Features, NoOscillationHasNoPeriod) {
  const Recording r = Oscillation(60, 3, 0, 1.0, 4, 0);
  EXPECT_TRUE(std::isnan(MeasureFeatures(r, 0, 60).Value("period_s")));
}

TEST(Features, NoiseStdOfWhiteNoiseOnASlowOscillation) {
  for (double sigma : {0.1, 1.0, 3.0}) {
    const Recording r = Oscillation(100, 3, 0, sigma, 5);
    EXPECT_NEAR(NoiseStd(r.channels[0]), sigma, 0.05 * sigma + 0.02) << sigma;
  }
}

TEST(Features, TwinsAreAboutOneScaleApartAndAChangeIsFar) {
  const Recording a = Oscillation(120, 3.2, 0.7, 0.5, 11), b = Oscillation(120, 3.2, 0.7, 0.5, 12);
  const FeatureSet fa = MeasureFeatures(a, 10, 110), fb = MeasureFeatures(b, 10, 110);
  const double twins = FeatureDistance(fb, fa);
  EXPECT_LT(twins, 1.0);
  auto scales_off = [&](const FeatureSet& f, const std::string& name) {
    return (f.Value(name) - fa.Value(name)) / fa.Find(name)->scale;
  };
  const FeatureSet slower = MeasureFeatures(Oscillation(120, 3.6, 0.7, 0.5, 12), 10, 110);  // 12 % longer period
  EXPECT_GT(scales_off(slower, "period_s"), 2.0);
  EXPECT_GT(FeatureDistance(slower, fa), twins + 4.0 / fa.features.size());
  const FeatureSet damped = MeasureFeatures(Oscillation(120, 3.2, 0.7, 0.5, 12, 20), 10, 110);  // a third less swing
  EXPECT_LT(scales_off(damped, "bit_rpm std"), -3.0);
  EXPECT_GT(FeatureDistance(damped, fa), twins + 9.0 / fa.features.size());
}

// A bouncing bit: the weight on bit swings with a 0.25-s bounce (a lag modulo that period says nothing about a
// delay of seconds) plus broadband forcing; the hook load answers -wob after the axial travel time, and the recorded
// weight on bit arrives `delay` late (telemetry). Noise of 1 % on each.
Recording Bouncing(double seconds, double travel, double delay, unsigned seed, double coupling = 0.3) {
  Recording r = Empty({"hookload_kN", "wob_kN"});
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  const int count = static_cast<int>(seconds * 100), back = static_cast<int>(std::lround((travel + delay) * 100));
  std::vector<double> wob(count + back);
  double broadband = 0;  // AR(1) forcing with a 0.1-s memory
  for (std::size_t i = 0; i < wob.size(); ++i) {
    broadband = 0.9 * broadband + 10 * n(rng);
    wob[i] = 150 + 100 * std::sin(2 * kPi * 0.01 * i / 0.25) + broadband;
  }
  const int travel_samples = static_cast<int>(std::lround(travel * 100));
  for (int i = 0; i < count; ++i) {
    r.time_s.push_back(0.01 * i);
    // wob[j] is the weight on bit at time 0.01 (j - back): now is j = i + back.
    r.channels[0].push_back(700 - coupling * (wob[i + back - travel_samples] - 150) + 7 * n(rng));
    r.channels[1].push_back(wob[i + back - static_cast<int>(std::lround(delay * 100))] + 1.5 * n(rng));
  }
  return r;
}

TEST(Features, TheWeightOnBitsLagBehindTheHookLoadShowsADelayLongerThanTheBouncePeriod) {
  const double travel = 0.58;  // 3000 m of pipe at 5172 m/s
  for (double delay : {0.0, 2.1, 3.5}) {
    const FeatureSet f = MeasureFeatures(Bouncing(60, travel, delay, 7), 5, 57);
    EXPECT_NEAR(f.Value("hook_to_wob_lag_s"), delay - travel, 0.015) << delay;
    EXPECT_LE(f.Find("hook_to_wob_lag_s")->scale, 0.1) << delay;  // every part of the window agrees
  }
  // A hook load that does not answer the weight on bit (noise only): no lag.
  EXPECT_TRUE(std::isnan(MeasureFeatures(Bouncing(60, travel, 2.1, 8, 0.0), 5, 57).Value("hook_to_wob_lag_s")));
}

// A steady bounce whose strength wanders (a 4-Hz bounce under an amplitude with a 0.5-s memory): the hook load's
// fast motion answers the weight on bit's after the axial travel time, and the recorded weight on bit arrives `delay`
// late. The envelopes' correlation peaks where the weight on bit follows by delay - travel.
Recording WanderingBounce(double seconds, double travel, double delay, unsigned seed) {
  Recording r = Empty({"hookload_kN", "wob_kN"});
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  const int count = static_cast<int>(seconds * 100), back = static_cast<int>(std::lround((travel + delay) * 100));
  std::vector<double> wob(count + back);
  double wander = 0;
  for (std::size_t i = 0; i < wob.size(); ++i) {
    wander = 0.98 * wander + 0.2 * n(rng);  // std 1, memory 0.5 s
    wob[i] = 150 + std::max(0.0, 60 + 40 * wander) * std::sin(2 * kPi * 0.01 * i / 0.25) + 1.5 * n(rng);
  }
  const int travel_samples = static_cast<int>(std::lround(travel * 100));
  for (int i = 0; i < count; ++i) {
    r.time_s.push_back(0.01 * i);
    r.channels[0].push_back(700 - 0.3 * (wob[i + back - travel_samples] - 150) + 7 * n(rng));
    r.channels[1].push_back(wob[i + back - static_cast<int>(std::lround(delay * 100))]);
  }
  return r;
}

TEST(Features, TheEnvelopesCorrelogramIsShiftedWholeByATelemetryDelay) {
  const double travel = 0.58;
  EXPECT_EQ(EnvelopeCorrelationName(1.5), "hook_wob_envelope_corr_at_+1.5s");
  EXPECT_EQ(EnvelopeCorrelationName(-0.5), "hook_wob_envelope_corr_at_-0.5s");
  const FeatureSet direct = MeasureFeatures(WanderingBounce(60, travel, 0.0, 3), 5, 57);
  const FeatureSet delayed = MeasureFeatures(WanderingBounce(60, travel, 2.1, 4), 5, 57);
  // The peak sits at the lag next to delay - travel: -0.5 s direct, +1.5 s delayed.
  EXPECT_GT(direct.Value(EnvelopeCorrelationName(-0.5)), 0.7);
  EXPECT_GT(delayed.Value(EnvelopeCorrelationName(1.5)), 0.7);
  for (double lag : {-1.0, 0.5, 1.0, 1.5, 2.0, 2.5}) EXPECT_LT(direct.Value(EnvelopeCorrelationName(lag)), 0.5) << lag;
  for (double lag : {-1.0, -0.5, 0.0, 0.5, 2.5}) EXPECT_LT(delayed.Value(EnvelopeCorrelationName(lag)), 0.5) << lag;
  // Counted in the recording's own scales, the undelayed twin is far off at the delayed peak; a twin is not.
  const FeatureSet twin = MeasureFeatures(WanderingBounce(60, travel, 2.1, 5), 5, 57);
  const Feature& at = *delayed.Find(EnvelopeCorrelationName(1.5));
  EXPECT_GT((at.value - direct.Value(at.name)) / at.scale, 3.0);
  EXPECT_LT(std::abs(at.value - twin.Value(at.name)) / at.scale, 3.0);
}

TEST(Features, AnAxialLagOnAnotherPeakCountsAsThreeScales) {
  FeatureSet recording;
  recording.features = {{"hook_to_wob_lag_s", 1.5, 0.1}, {"wob_kN std", 100, 10}};
  FeatureSet model = recording;
  model.features[0].value = 1.7;  // 2 scales
  EXPECT_NEAR(FeatureDistance(model, recording), 4.0 / 2, 1e-12);
  model.features[0].value = 5.0;  // 35 scales: another peak, counted as 3
  EXPECT_NEAR(FeatureDistance(model, recording), 9.0 / 2, 1e-12);
  model.features[1].value = 150;  // 5 scales of a level: counted in full
  EXPECT_NEAR(FeatureDistance(model, recording), (9.0 + 25.0) / 2, 1e-12);
}

// The difference of two models' distances to one recording, as the recording's noise moves it: drawn 20 000 times
// (noise of 0.3 squared scales in each feature), its spread is the one DistanceDifferenceStd predicts; a feature one
// model lacks and an axial lag on another peak are constants, and twins do not differ at all.
TEST(Features, TheDifferenceOfTwoDistancesMovesWithTheRecordingsNoiseAsPredicted) {
  FeatureSet recording;
  recording.features = {{"wob_kN std", 10, 2}, {"bit_rpm mean", 60, 3}, {"top_torque_kNm std", 1, 0.1},
                        {"period_s", 4, 0.5}, {"hook_to_wob_lag_s", 1.5, 0.1}};
  FeatureSet a = recording, b = recording;
  a.features[0].value = 13, b.features[0].value = 9;       // 1.5 and -0.5 scales
  a.features[1].value = 60, b.features[1].value = 66;      // 0 and 2
  a.features[2].value = 1.05, b.features[2].value = 1.05;  // equal: no slope
  a.features[3].value = std::nan(""), b.features[3].value = 4.2;  // a lacks the period: its term stays 9
  a.features[4].value = 9.0, b.features[4].value = 1.6;           // a's lag on another peak: held at its cap
  const double variance = 0.3;
  const double predicted = DistanceDifferenceStd(a, b, recording, variance);
  // Slopes 2 (z_a - z_b): 4, -4, 0, -2 x 0.4 (b's period alone moves), -2 x 1 (b's lag alone); over 5 terms.
  EXPECT_NEAR(predicted, std::sqrt(variance * (16 + 16 + 0 + 0.64 + 4)) / 5, 1e-12);
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, std::sqrt(variance));
  double sum = 0, square = 0;
  const int draws = 20000;
  for (int d = 0; d < draws; ++d) {
    FeatureSet noisy = recording;
    for (Feature& f : noisy.features) f.value += f.scale * noise(random);
    const double difference = FeatureDistance(a, noisy) - FeatureDistance(b, noisy);
    sum += difference, square += difference * difference;
  }
  const double mean = sum / draws, spread = std::sqrt(square / draws - mean * mean);
  // The lag's cap makes b's term bend where its noise carries it past 3 scales (rarely at 0.55 scales of noise).
  EXPECT_NEAR(spread / predicted, 1.0, 0.03);
  EXPECT_EQ(DistanceDifferenceStd(a, a, recording, variance), 0.0);
}

// Two models' largest difference, in the recording's scales: a level 2.5 scales apart leads; a feature only one model
// defines counts as three; the correlogram's lags count as one feature, their rms.
TEST(Features, TheLargestDifferenceOfTwoModelsIsCountedInTheRecordingsScales) {
  FeatureSet recording;
  recording.features = {{"wob_kN std", 10, 2}, {"period_s", 4, 0.5}};
  FeatureSet a = recording, b = recording;
  a.features[0].value = 15;  // 2.5 scales from b
  EXPECT_NEAR(LargestDifferenceInScales(a, b, recording), 2.5, 1e-12);
  EXPECT_NEAR(LargestDifferenceInScales(b, a, recording), 2.5, 1e-12);
  a.features[1].value = std::nan("");  // a does not oscillate
  EXPECT_NEAR(LargestDifferenceInScales(a, b, recording), 3.0, 1e-12);
  EXPECT_EQ(LargestDifferenceInScales(b, b, recording), 0.0);
  recording.features = {{EnvelopeCorrelationName(0), 0.9, 0.05}, {EnvelopeCorrelationName(0.5), 0.5, 0.05}};
  a = recording, b = recording;
  a.features[0].value += 0.2, a.features[1].value -= 0.1;  // 4 and 2 scales: rms sqrt(10)
  EXPECT_NEAR(LargestDifferenceInScales(a, b, recording), std::sqrt(10.0), 1e-12);
}

TEST(Features, TheCorrelogramCountsAsOneFeature) {
  FeatureSet recording;
  recording.features = {{"wob_kN std", 100, 10},
                        {EnvelopeCorrelationName(0), 0.5, 0.05},
                        {EnvelopeCorrelationName(1), 0.1, 0.05},
                        {EnvelopeCorrelationName(2), std::nan(""), 0.05}};
  FeatureSet model = recording;
  model.features[1].value = 0.6;  // 2 scales
  model.features[2].value = 0.3;  // 4 scales
  model.features[0].value = 130;  // 3 scales
  // Two features: the std (9) and the correlogram, the mean over its two defined lags ((4 + 16) / 2).
  EXPECT_NEAR(FeatureDistance(model, recording), (9.0 + 10.0) / 2, 1e-12);
  EXPECT_EQ(FeatureCount(recording), 2.0);
  // Reported as one: the rms of its lags' differences, the largest at 1 s.
  const CorrelogramDifference difference = CompareCorrelograms(model, recording);
  EXPECT_NEAR(difference.rms_scales, std::sqrt(10.0), 1e-12);
  EXPECT_EQ(difference.largest_at_lag_s, 1.0);
  // A recording whose envelopes share too little (peak 0.29 < 0.3): its correlogram is not asked of the model.
  recording.features[1].value = 0.29;
  EXPECT_NEAR(FeatureDistance(model, recording), 9.0, 1e-12);
  EXPECT_EQ(FeatureCount(recording), 1.0);
  EXPECT_TRUE(std::isnan(CompareCorrelograms(model, recording).rms_scales));
}

TEST(Features, AWindowWithoutEnoughSamplesIsRefused) {
  const Recording r = Oscillation(10, 3, 0, 0.1, 6);
  EXPECT_THROW(MeasureFeatures(r, 20, 30), InputError);
}

}  // namespace
}  // namespace drillwave::diagnosis
