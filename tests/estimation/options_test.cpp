// The estimation options' IsValid (core/validity.hpp): the defaults pass (the sentinels -1 and -1e300 included), each
// field out of its range is named; the estimators refuse them with a ParameterError naming the field before they
// look at the signals.
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/estimation/estimate.hpp"
#include "drillwave/estimation/follow.hpp"
#include "drillwave/estimation/hybrid_observer.hpp"
#include "drillwave/estimation/lumped_observer.hpp"
#include "invalid_field.hpp"

namespace drillwave::estimation {
namespace {

using testing::InvalidField;
using testing::InvalidFieldWith;
using testing::RefusedParameter;

const double kNaN = std::nan(""), kInf = std::numeric_limits<double>::infinity();

TEST(EstimateOptions, TheDefaultsAreValidAndEachBadFieldIsNamed) {
  const EstimateOptions o;
  EXPECT_EQ(InvalidField(o), "");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.stuck_fraction = 1.5; }), "stuck_fraction");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.stuck_threshold_rad_s = kNaN; }), "stuck_threshold_rad_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.smoothing_lag_s = kInf; }), "smoothing_lag_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.model_time_offset_s = kNaN; }), "model_time_offset_s");
}

TEST(ObserverOptions, TheDefaultsAreValidAndEachBadFieldIsNamed) {
  const HybridObserverOptions hybrid;
  EXPECT_EQ(InvalidField(hybrid), "");
  EXPECT_EQ(InvalidFieldWith(hybrid, [](auto& b) { b.model_time_offset_s = kInf; }), "model_time_offset_s");
  EXPECT_EQ(InvalidFieldWith(hybrid, [](auto& b) { b.initial_bit_speed_rad_s = kNaN; }), "initial_bit_speed_rad_s");
  EXPECT_EQ(InvalidFieldWith(hybrid, [](auto& b) { b.initial_twist_rad = -kInf; }), "initial_twist_rad");
  const LumpedObserverOptions lumped;
  EXPECT_EQ(InvalidField(lumped), "");
  EXPECT_EQ(InvalidFieldWith(lumped, [](auto& b) { b.smoothing_lag_s = kNaN; }), "smoothing_lag_s");
  EXPECT_EQ(InvalidFieldWith(lumped, [](auto& b) { b.initial_twist_rad = kInf; }), "initial_twist_rad");
}

TEST(EstimateOptions, TheEstimatorsRefuseThemBeforeLookingAtTheSignals) {
  EstimateOptions o;
  o.stuck_fraction = 1.5;
  EXPECT_EQ(RefusedParameter([&] { EstimateBit(EstimatorModel{}, SurfaceSignals{}, o); }), "stuck_fraction");
  EXPECT_EQ(RefusedParameter([&] { LiveEstimator(EstimatorModel{}, o, {"time_s"}, SurfaceChannels{}); }),
            "stuck_fraction");
  HybridObserverOptions hybrid;
  hybrid.initial_twist_rad = kNaN;
  EXPECT_EQ(RefusedParameter([&] { EstimateHybrid(LumpedModel{}, SurfaceSignals{}, 0.1, hybrid); }),
            "initial_twist_rad");
  LumpedObserverOptions lumped;
  lumped.smoothing_lag_s = kNaN;
  EXPECT_EQ(RefusedParameter([&] { EstimateLumped(LumpedModel{}, SurfaceSignals{}, 0.1, lumped); }),
            "smoothing_lag_s");
}

}  // namespace
}  // namespace drillwave::estimation
