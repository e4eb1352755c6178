// Friction laws: values against numbers computed by hand (Python, from the formulas in the seeds), symmetry,
// static limits, derivatives against finite differences, JSON round trips, scaling and bad input naming the field.
#include "drillwave/bitrock/friction.hpp"

#include <cmath>
#include <cstdlib>
#include <initializer_list>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "drillwave/cases/friction_json.hpp"
#include "drillwave/core/error.hpp"

namespace drillwave::bitrock {
namespace {

using nlohmann::json;

const json kStribeck = {{"law", "stribeck"}, {"W_N", 97347},    {"R_m", 0.155575},
                        {"mu_c", 0.5},       {"mu_s", 0.8},     {"gamma_b", 0.9},
                        {"nu_f_rad_s", 1.0}, {"c_b_Nms_per_rad", 0.03}};
const json kHumped = {{"law", "humped"},           {"T_sl_Nm", 0.3},           {"T_1_Nm", -0.2},
                      {"T_2_Nm", 0.15},            {"omega_1_s_per_rad", 2.0}, {"omega_2_s_per_rad", 0.3},
                      {"b_l_Nms_per_rad", 0.01},   {"delta_T_sl_Nm", 0.02}};
// The UFRJ rig's disc (torque on bit 2.7 N m near rest falling by 0.08 N m per rad/s), with a floor beyond 27.5 rad/s.
const json kLinearWeakening = {{"law", "linear_weakening"}, {"T_0_Nm", 2.7},     {"T_s_Nm", 3.0},
                               {"weakening_Nms_per_rad", 0.08}, {"T_min_Nm", 0.5}, {"c_Nms_per_rad", 0.01}};
const json kUpperDisc = {{"law", "asymmetric_coulomb_viscous"}, {"T_s_Nm", 0.3212}, {"delta_T_s_Nm", 0.0095},
                         {"b_Nms_per_rad", 1.9833}, {"delta_b_Nms_per_rad", 0.0167}};

// One full (every field given) example of every law, in the order of FrictionLaw::Law.
std::vector<json> EveryLaw() {
  return {
      {{"law", "viscous"}, {"c_Nms_per_rad", 3.0}},
      {{"law", "coulomb"}, {"T_c_Nm", 10.0}, {"T_s_Nm", 12.0}, {"c_Nms_per_rad", 0.5}},
      kStribeck,
      {{"law", "sqrt_regularized"}, {"amplitude_Nm", 100.0}, {"alpha", 1.0}, {"epsilon_rad_s", 0.1}},
      {{"law", "tanh_hump"}, {"amplitude_Nm", 100.0}, {"beta", 1.0}, {"gamma1", 2.0}, {"gamma2", 0.5}},
      {{"law", "rational"}, {"p_Nm", 100.0}, {"k", 0.5}, {"zeta", 0.01}},
      kHumped,
      kUpperDisc,
      {{"law", "tanh_hump_printed"}, {"amplitude_Nm", 100.0}, {"beta", 1.0}, {"gamma1", 2.0}, {"gamma2", 0.5}},
      {{"law", "squared_sqrt_cutting"}, {"a4_N", 2e5}, {"depth_of_cut_m", 0.001}, {"alpha", 1.5}, {"epsilon_rad_s", 0.2}},
      kLinearWeakening,
  };
}

FrictionLaw Law(const json& j) { return cases::ReadFrictionLaw(j, "/f"); }

json With(json j, const std::string& key, const json& value) {
  j[key] = value;
  return j;
}

json Without(json j, const std::string& key) {
  j.erase(key);
  return j;
}

// Fourth-order central difference; h small enough for truncation, large enough for round-off.
double CentralDifference(const FrictionLaw& f, double w, double h) {
  return (8 * (f.SlipTorque(w + h) - f.SlipTorque(w - h)) - (f.SlipTorque(w + 2 * h) - f.SlipTorque(w - 2 * h))) /
         (12 * h);
}

TEST(FrictionLaw, ViscousAndCoulombValues) {
  const FrictionLaw viscous = Law(EveryLaw()[0]);
  EXPECT_FALSE(viscous.IsSetValued());
  EXPECT_DOUBLE_EQ(viscous.SlipTorque(2.0), 6.0);
  EXPECT_DOUBLE_EQ(viscous.SlipTorque(0.0), 0.0);
  EXPECT_DOUBLE_EQ(viscous.SlipTorqueDerivative(-5.0), 3.0);
  EXPECT_EQ(viscous.StaticPositive(), 0.0);
  EXPECT_EQ(viscous.StaticNegative(), 0.0);

  const FrictionLaw coulomb = Law(EveryLaw()[1]);
  EXPECT_TRUE(coulomb.IsSetValued());
  EXPECT_DOUBLE_EQ(coulomb.SlipTorque(2.0), 11.0);
  EXPECT_DOUBLE_EQ(coulomb.SlipTorque(-2.0), -11.0);
  EXPECT_DOUBLE_EQ(coulomb.SlipTorque(1e-12), 10.0 + 0.5e-12);
  EXPECT_DOUBLE_EQ(coulomb.StaticPositive(), 12.0);
  EXPECT_DOUBLE_EQ(coulomb.StaticNegative(), 12.0);
}

TEST(FrictionLaw, StribeckMatchesHandValues) {
  const FrictionLaw f = cases::ReadFrictionLaw(kStribeck, "/bit/friction");
  const double static_level = 12115.80762;  // W R mu_s = 97347 * 0.155575 * 0.8
  EXPECT_TRUE(f.IsSetValued());
  EXPECT_NEAR(f.StaticPositive(), static_level, 1e-8);
  EXPECT_NEAR(f.StaticNegative(), static_level, 1e-8);
  // At 0+ the slip torque starts at the static level (+ c_b * 0).
  EXPECT_NEAR(f.SlipTorque(1e-12), static_level, 1e-7);
  EXPECT_NEAR(f.SlipTorque(-1e-12), -static_level, 1e-7);
  EXPECT_NEAR(f.SlipTorque(2.0), 8323.463336059735, 1e-8);
  EXPECT_NEAR(f.SlipTorque(-0.5), -10469.412269304597, 1e-8);
  EXPECT_NEAR(f.SlipTorqueDerivative(2.0), -675.8912162037614, 1e-9);
  // Far from rest: the Coulomb level W R mu_c plus the viscous part c_b w.
  EXPECT_NEAR(f.SlipTorque(100.0), 7575.3797625 + 0.0, 1e-8);
  EXPECT_NEAR(f.SlipTorque(100.0), 97347 * 0.155575 * 0.5 + 0.03 * 100.0, 1e-8);
}

TEST(FrictionLaw, StribeckSpeedScale) {
  const FrictionLaw f = Law(With(kStribeck, "nu_f_rad_s", 2.0));  // decay exp(-0.9 |w| / 2)
  EXPECT_NEAR(f.SlipTorque(2.0), 9419.659680579734, 1e-8);
  EXPECT_NEAR(f.SlipTorqueDerivative(2.0), -831.2189631358804, 1e-9);
}

TEST(FrictionLaw, SmoothChapterLawsMatchHandValues) {
  const FrictionLaw sqrt_law = Law(EveryLaw()[3]);  // 100 w / sqrt(w^2 + 0.01)
  EXPECT_NEAR(sqrt_law.SlipTorque(0.1), 70.71067811865476, 1e-12);
  EXPECT_NEAR(sqrt_law.SlipTorque(3.0), 99.94449069791544, 1e-12);
  EXPECT_NEAR(sqrt_law.SlipTorqueDerivative(0.0), 1000.0, 1e-9);  // p alpha / epsilon

  const FrictionLaw tanh_law = Law(EveryLaw()[4]);  // 100 (tanh w + 2 w / (1 + 0.5 w^2))
  EXPECT_NEAR(tanh_law.SlipTorque(1.0), 209.49274892890983, 1e-11);
  EXPECT_NEAR(tanh_law.SlipTorque(0.3), 86.54752918774282, 1e-11);
  EXPECT_NEAR(tanh_law.SlipTorqueDerivative(0.0), 300.0, 1e-9);  // p beta (1 + gamma1)

  const FrictionLaw rational = Law(EveryLaw()[5]);  // 100 * 0.5 w / (0.25 w^2 + 0.01)
  EXPECT_NEAR(rational.SlipTorque(0.2), 500.0, 1e-10);  // the peak, at sqrt(zeta) / k, of height p / (2 sqrt(zeta))
  EXPECT_NEAR(rational.SlipTorqueDerivative(0.2), 0.0, 1e-9);
  EXPECT_NEAR(rational.SlipTorque(2.0), 99.00990099009901, 1e-11);
  EXPECT_NEAR(rational.SlipTorqueDerivative(0.0), 5000.0, 1e-8);  // p k / zeta

  for (const FrictionLaw& f : {sqrt_law, tanh_law, rational}) {
    EXPECT_FALSE(f.IsSetValued()) << f.Kind();
    EXPECT_EQ(f.SlipTorque(0.0), 0.0) << f.Kind();
    EXPECT_EQ(f.StaticPositive(), 0.0) << f.Kind();
    EXPECT_EQ(f.StaticNegative(), 0.0) << f.Kind();
  }
}

// Chapter eq. 2.30 as printed: F(0) = beta gamma1, a jump at rest that the law holds as its static range.
TEST(FrictionLaw, PrintedTanhHumpMatchesHandValuesAndHoldsItsRestLevel) {
  const FrictionLaw f = Law(EveryLaw()[8]);  // 100 (tanh |w| + 2 / (1 + 0.5 w^2)) sign w
  EXPECT_TRUE(f.IsSetValued());
  EXPECT_NEAR(f.SlipTorque(0.3), 220.51882105377155, 1e-11);
  EXPECT_NEAR(f.SlipTorque(-2.0), -163.06942467424835, 1e-11);
  EXPECT_NEAR(f.SlipTorqueDerivative(1.0), -46.89145472748627, 1e-11);
  EXPECT_NEAR(f.SlipTorque(1e-9), 200.0, 1e-6);  // p beta gamma1
  EXPECT_DOUBLE_EQ(f.StaticPositive(), 200.0);
  EXPECT_DOUBLE_EQ(f.StaticNegative(), 200.0);
  EXPECT_NEAR(f.SlipTorque(50.0), 100.0 * (std::tanh(50.0) + 2 / 1251.0), 1e-12);  // towards p beta
}

// Chapter eq. 2.33 with F of eq. 2.29: T = a4 d alpha^2 w |w| / (w^2 + epsilon^2); half its level at w = epsilon.
TEST(FrictionLaw, SquaredSqrtCuttingMatchesHandValues) {
  const FrictionLaw f = Law(EveryLaw()[9]);  // 2e5 * 1e-3 * 2.25 w |w| / (w^2 + 0.04)
  EXPECT_FALSE(f.IsSetValued());
  EXPECT_NEAR(f.SlipTorque(0.2), 225.0, 1e-10);
  EXPECT_NEAR(f.SlipTorque(2.0), 445.54455445544556, 1e-10);
  EXPECT_NEAR(f.SlipTorque(-0.1), -90.0, 1e-10);
  EXPECT_EQ(f.SlipTorque(0.0), 0.0);
  EXPECT_EQ(f.SlipTorqueDerivative(0.0), 0.0);  // F^2 ~ w^2: no torque slope at rest
  EXPECT_NEAR(f.SlipTorqueDerivative(0.2), 450.0 * 2 * 0.2 * 0.04 / (0.08 * 0.08), 1e-9);
}

// Slip T = max(T_0 - s |w|, T_min) sign w + c w: the linear fall, the floor, stiction above the slip branch.
TEST(FrictionLaw, LinearWeakeningFallsLinearlyToItsFloor) {
  const FrictionLaw f = Law(kLinearWeakening);
  EXPECT_TRUE(f.IsSetValued());
  EXPECT_DOUBLE_EQ(f.StaticPositive(), 3.0);
  EXPECT_DOUBLE_EQ(f.StaticNegative(), 3.0);
  EXPECT_NEAR(f.SlipTorque(1e-12), 2.7, 1e-11);  // the slip branch starts below the static level
  EXPECT_NEAR(f.SlipTorque(10.0), 2.7 - 0.8 + 0.1, 1e-14);
  EXPECT_NEAR(f.SlipTorque(-10.0), -(2.7 - 0.8 + 0.1), 1e-14);
  EXPECT_NEAR(f.SlipTorqueDerivative(10.0), -0.08 + 0.01, 1e-15);
  EXPECT_NEAR(f.SlipTorque(40.0), 0.5 + 0.4, 1e-14);  // on the floor (beyond 27.5 rad/s): only c w still grows
  EXPECT_NEAR(f.SlipTorqueDerivative(40.0), 0.01, 1e-15);
  const FrictionLaw defaults = Law({{"law", "linear_weakening"}, {"T_0_Nm", 2.0}, {"weakening_Nms_per_rad", 0.1}});
  EXPECT_EQ(defaults.StaticPositive(), 2.0);   // T_s defaults to T_0
  EXPECT_EQ(defaults.SlipTorque(30.0), 0.0);   // the floor defaults to 0: never a torque that drives the disc
}

TEST(FrictionLaw, HumpedLowerDiscLaw) {
  const FrictionLaw f = cases::ReadFrictionLaw(kHumped, "/lower");
  EXPECT_TRUE(f.IsSetValued());
  EXPECT_NEAR(f.StaticPositive(), 0.32, 1e-15);  // T_sl + delta
  EXPECT_NEAR(f.StaticNegative(), 0.28, 1e-15);  // T_sl - delta
  // The seed's logistic steps 1 - 2/(1 + e^(omega |w|)), evaluated in Python.
  EXPECT_NEAR(f.SlipTorque(1.0), 0.2000139238523447, 1e-14);
  EXPECT_NEAR(f.SlipTorque(-1.0), -0.16001392385234472, 1e-14);
  EXPECT_NEAR(f.SlipTorque(0.5), 0.2438055221511229, 1e-14);
  // The slip branches start at the two static limits.
  EXPECT_NEAR(f.SlipTorque(1e-12), 0.32, 1e-11);
  EXPECT_NEAR(f.SlipTorque(-1e-12), -0.28, 1e-11);
  // The hump: T_1 < 0 makes the torque fall after break-away (minimum near 1.58 rad/s), then it rises again.
  EXPECT_LT(f.SlipTorqueDerivative(0.5), 0.0);
  EXPECT_LT(f.SlipTorqueDerivative(1.5), 0.0);
  EXPECT_GT(f.SlipTorqueDerivative(1.7), 0.0);
  EXPECT_GT(f.SlipTorqueDerivative(20.0), 0.0);
}

TEST(FrictionLaw, AsymmetricUpperDiscLawHasTwoStaticLimits) {
  const FrictionLaw f = cases::ReadFrictionLaw(kUpperDisc, "/upper");
  EXPECT_TRUE(f.IsSetValued());
  EXPECT_NEAR(f.StaticPositive(), 0.3307, 1e-15);  // T_s + dT_s
  EXPECT_NEAR(f.StaticNegative(), 0.3117, 1e-15);  // T_s - dT_s
  EXPECT_NEAR(f.SlipTorque(1.0), 0.3307 + 2.0, 1e-14);
  EXPECT_NEAR(f.SlipTorque(-1.0), -0.3117 - 1.9666, 1e-14);
  EXPECT_NEAR(f.SlipTorque(1e-12), 0.3307, 1e-11);
  EXPECT_NEAR(f.SlipTorque(-1e-12), -0.3117, 1e-11);
  EXPECT_NEAR(f.SlipTorqueDerivative(0.5), 2.0, 1e-14);
  EXPECT_NEAR(f.SlipTorqueDerivative(-0.5), 1.9666, 1e-14);
}

TEST(FrictionLaw, SetValuedLawsAreConsistentAtRest) {
  for (const json& j : EveryLaw()) {
    const FrictionLaw f = Law(j);
    if (!f.IsSetValued()) continue;
    EXPECT_GE(f.StaticNegative(), 0.0) << f.Kind();
    EXPECT_GE(f.StaticPositive(), 0.0) << f.Kind();
    // Exactly at rest the slip torque is 0, inside the static range (documented; callers must not rely on it).
    EXPECT_EQ(f.SlipTorque(0.0), 0.0) << f.Kind();
    // The slip branches start inside the static range: break-away never needs less than sliding.
    EXPECT_LE(f.SlipTorque(1e-12), f.StaticPositive() + 1e-9) << f.Kind();
    EXPECT_GE(f.SlipTorque(-1e-12), -f.StaticNegative() - 1e-9) << f.Kind();
  }
}

TEST(FrictionLaw, TorqueOpposesMotion) {
  for (const json& j : EveryLaw()) {
    const FrictionLaw f = Law(j);
    for (double w : {-50.0, -3.0, -0.4, -1e-6, 1e-6, 0.4, 3.0, 50.0}) EXPECT_GT(f.SlipTorque(w) * w, 0.0) << f.Kind();
  }
}

TEST(FrictionLaw, SymmetricLawsAreOdd) {
  json symmetric_hump = kHumped;
  symmetric_hump.erase("delta_T_sl_Nm");
  std::vector<json> laws;
  for (const json& j : EveryLaw())  // all but the asymmetric upper-disc law and the humped law with delta_T_sl != 0
    if (j != kUpperDisc && j != kHumped) laws.push_back(j);
  laws.push_back(symmetric_hump);
  for (const json& j : laws) {
    const FrictionLaw f = Law(j);
    for (double w : {1e-9, 0.1, 1.0, 5.0, 40.0})
      EXPECT_NEAR(f.SlipTorque(-w), -f.SlipTorque(w), 1e-14 * std::abs(f.SlipTorque(w))) << f.Kind() << " at " << w;
    EXPECT_EQ(f.StaticPositive(), f.StaticNegative()) << f.Kind();
  }
}

TEST(FrictionLaw, DerivativesMatchFiniteDifferences) {
  for (const json& j : EveryLaw()) {
    const FrictionLaw f = Law(j);
    std::vector<double> speeds = {-7.0, -1.3, -0.25, 0.05, 0.4, 2.5, 11.0};  // not at a peak (slope 0)
    // Smooth laws are differentiable at rest too; a zero slope there (squared_sqrt_cutting, w |w| near rest, which
    // a relative tolerance cannot check) has its own test.
    if (!f.IsSetValued() && f.SlipTorqueDerivative(0.0) != 0.0) speeds.push_back(0.0);
    for (double w : speeds) {
      const double h = 1e-3 * std::max(0.01, std::min(1.0, std::abs(w)));  // never steps across w = 0
      const double exact = f.SlipTorqueDerivative(w);
      const double fd = CentralDifference(f, w, h);
      EXPECT_LT(std::abs(exact - fd), 1e-6 * std::abs(exact)) << f.Kind() << " at " << w << ": " << exact << " vs "
                                                              << fd;
    }
  }
}

TEST(FrictionLaw, JsonRoundTrip) {
  for (const json& j : EveryLaw()) {
    const FrictionLaw f = Law(j);
    EXPECT_EQ(f.Kind(), j.at("law").get<std::string>());
    EXPECT_EQ(cases::FrictionLawJson(f), j) << f.Kind();  // every field was given, so nothing is added or lost
    const FrictionLaw g = Law(cases::FrictionLawJson(f));
    EXPECT_EQ(cases::FrictionLawJson(g), cases::FrictionLawJson(f)) << f.Kind();
    EXPECT_EQ(g.StaticPositive(), f.StaticPositive()) << f.Kind();
    EXPECT_EQ(g.StaticNegative(), f.StaticNegative()) << f.Kind();
    for (double w : {-3.0, 0.7, 4.0}) EXPECT_EQ(g.SlipTorque(w), f.SlipTorque(w)) << f.Kind();
    // Through text as well: the numbers are written with enough digits to come back bit for bit.
    EXPECT_EQ(cases::FrictionLawJson(Law(json::parse(cases::FrictionLawJson(f).dump()))), cases::FrictionLawJson(f)) << f.Kind();
  }
}

TEST(FrictionLaw, OptionalFieldsTakeTheirDefaults) {
  const FrictionLaw coulomb = Law({{"law", "coulomb"}, {"T_c_Nm", 7000}});
  EXPECT_EQ(coulomb.StaticPositive(), 7000.0);  // T_s defaults to T_c
  EXPECT_EQ(coulomb.SlipTorque(3.0), 7000.0);   // c defaults to 0
  EXPECT_EQ(cases::FrictionLawJson(coulomb), json({{"law", "coulomb"}, {"T_c_Nm", 7000}, {"T_s_Nm", 7000}, {"c_Nms_per_rad", 0}}));

  json symmetric = kHumped;
  symmetric.erase("delta_T_sl_Nm");
  const FrictionLaw humped = Law(symmetric);
  EXPECT_EQ(humped.StaticPositive(), 0.3);
  EXPECT_EQ(humped.StaticNegative(), 0.3);
  EXPECT_EQ(cases::FrictionLawJson(humped).at("delta_T_sl_Nm"), 0.0);
}

TEST(FrictionLaw, ScaledScalesStaticAndSlipTorque) {
  for (const json& j : EveryLaw()) {
    const FrictionLaw f = Law(j);
    const FrictionLaw s = f.Scaled(2.5);
    EXPECT_EQ(s.Kind(), f.Kind());
    EXPECT_EQ(s.IsSetValued(), f.IsSetValued());
    EXPECT_NEAR(s.StaticPositive(), 2.5 * f.StaticPositive(), 1e-12 * f.StaticPositive()) << f.Kind();
    EXPECT_NEAR(s.StaticNegative(), 2.5 * f.StaticNegative(), 1e-12 * f.StaticNegative()) << f.Kind();
    for (double w : {-3.0, -0.01, 0.7, 4.0}) {
      EXPECT_NEAR(s.SlipTorque(w), 2.5 * f.SlipTorque(w), 1e-12 * std::abs(f.SlipTorque(w))) << f.Kind();
      EXPECT_NEAR(s.SlipTorqueDerivative(w), 2.5 * f.SlipTorqueDerivative(w),
                  1e-12 * std::abs(f.SlipTorqueDerivative(w))) << f.Kind();
    }
    EXPECT_EQ(cases::FrictionLawJson(f), j) << "Scaled() must not change the law it is called on";
  }
  const FrictionLaw f = Law(kStribeck);
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::infinity(), std::nan("")})
    EXPECT_THROW(f.Scaled(bad), std::invalid_argument) << bad;
}

TEST(FrictionLaw, ConstructorChecksTheParameters) {
  EXPECT_NO_THROW(FrictionLaw(Stribeck{97347, 0.155575, 0.5, 0.8, 0.9, 1.0, 0.03}));
  EXPECT_THROW(FrictionLaw(Stribeck{97347, 0.155575, 0.5, 0.8, 0.9, 0.0, 0.03}), std::invalid_argument);  // nu_f
  EXPECT_THROW(FrictionLaw(Stribeck{97347, 0.155575, 0.5, 0.4, 0.9, 1.0, 0.03}), std::invalid_argument);  // mu_s
  EXPECT_THROW(FrictionLaw(Viscous{-1.0}), std::invalid_argument);
  EXPECT_THROW(FrictionLaw(Coulomb{1.0, 2.0, std::nan("")}), std::invalid_argument);
  EXPECT_THROW(FrictionLaw(Viscous{std::numeric_limits<double>::infinity()}), std::invalid_argument);
  EXPECT_THROW(FrictionLaw(Humped{0.3, std::numeric_limits<double>::infinity(), 0, 1, 1, 0, 0}), std::invalid_argument);
  EXPECT_THROW(FrictionLaw(AsymmetricCoulombViscous{0.3, 0.4, 2.0, 0.0}), std::invalid_argument);
  try {
    FrictionLaw(Stribeck{97347, 0.155575, 0.5, 0.4, 0.9, 1.0, 0.03});
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("mu_s"), std::string::npos) << e.what();
  }
}

// ReadFrictionLaw must reject j with an InputError at path whose message mentions each of mentions.
void ExpectRejected(const json& j, const std::string& path, std::initializer_list<std::string> mentions = {}) {
  SCOPED_TRACE(j.dump());
  try {
    cases::ReadFrictionLaw(j, "/bit/friction");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), path) << e.what();
    for (const std::string& m : mentions) EXPECT_NE(std::string(e.what()).find(m), std::string::npos) << e.what();
  }
}

TEST(FrictionLaw, BadInputNamesTheFieldTheValueAndTheRange) {
  const std::string p = "/bit/friction/";
  ExpectRejected(Without(kStribeck, "mu_s"), p + "mu_s", {"missing"});
  ExpectRejected(With(kStribeck, "mu_k", 0.3), p + "mu_k", {"unknown", "mu_s"});
  ExpectRejected(With(kStribeck, "W_N", "heavy"), p + "W_N", {"heavy", ">= 0"});
  ExpectRejected(With(kStribeck, "R_m", -3), p + "R_m", {"got -3", "> 0"});
  ExpectRejected(With(kStribeck, "W_N", -1), p + "W_N", {"got -1", ">= 0"});
  ExpectRejected(With(kStribeck, "mu_s", 0.4), p + "mu_s", {"got 0.4", ">= mu_c", "0.5"});
  ExpectRejected(With(kStribeck, "nu_f_rad_s", 0), p + "nu_f_rad_s", {"got 0", "> 0"});
  ExpectRejected(With(kStribeck, "W_N", std::strtod("1e999", nullptr)), p + "W_N", {"finite", "inf"});
  ExpectRejected(With(kLinearWeakening, "T_min_Nm", 2.8), p + "T_min_Nm", {"got 2.8", "[0, T_0_Nm]", "2.7"});
  ExpectRejected(With(kLinearWeakening, "T_min_Nm", -0.1), p + "T_min_Nm", {"got -0.1", "[0, T_0_Nm]"});
  ExpectRejected(With(kLinearWeakening, "T_s_Nm", 2.0), p + "T_s_Nm", {"got 2", ">= T_0_Nm"});
  ExpectRejected(With(kLinearWeakening, "weakening_Nms_per_rad", -0.1), p + "weakening_Nms_per_rad", {">= 0"});
  ExpectRejected(With(kStribeck, "mu_c", -std::numeric_limits<double>::infinity()), p + "mu_c", {"finite"});
  ExpectRejected(With(kStribeck, "gamma_b", std::nan("")), p + "gamma_b", {"finite"});
  ExpectRejected(With(kStribeck, "gamma_b", true), p + "gamma_b", {"boolean"});
  ExpectRejected(With(kStribeck, "gamma_b", nullptr), p + "gamma_b", {"null"});
  ExpectRejected(With(kStribeck, "gamma_b", json::array({0.9})), p + "gamma_b", {"array"});
  ExpectRejected({{"law", "coulomb"}, {"T_c_Nm", 10}, {"T_s_Nm", 8}}, p + "T_s_Nm", {">= T_c_Nm", "got 8"});
  ExpectRejected(With(kUpperDisc, "delta_T_s_Nm", 0.5), p + "delta_T_s_Nm", {"[-T_s_Nm, T_s_Nm]", "got 0.5"});
  ExpectRejected(With(kUpperDisc, "delta_b_Nms_per_rad", -2.5), p + "delta_b_Nms_per_rad", {"got -2.5"});
  ExpectRejected(With(kHumped, "delta_T_sl_Nm", -0.31), p + "delta_T_sl_Nm", {"got -0.31"});
  ExpectRejected(With(EveryLaw()[5], "zeta", 0), p + "zeta", {"> 0"});
  ExpectRejected(With(EveryLaw()[3], "epsilon_rad_s", -0.1), p + "epsilon_rad_s", {"> 0"});
  // The law itself.
  ExpectRejected(Without(kStribeck, "law"), p + "law", {"missing", "stribeck"});
  ExpectRejected({{"law", "magic"}}, p + "law", {"magic", "humped"});
  ExpectRejected({{"law", 42}}, p + "law", {"42"});
  ExpectRejected(json::array({1, 2}), "/bit/friction", {"object"});
  ExpectRejected("stribeck", "/bit/friction", {"object"});
}

// Humped T_1, T_2 make the hump when negative: they are not forced positive, nor is T_l(w) >= 0 checked.
TEST(FrictionLaw, HumpedStepsMayBeNegative) {
  EXPECT_NO_THROW(Law(With(With(kHumped, "T_1_Nm", -5.0), "T_2_Nm", -1.0)));
}

// Every field of every law: missing (unless optional), a string, or infinite is an error at that field.
TEST(FrictionLaw, EveryFieldIsChecked) {
  const std::set<std::string> optional = {"coulomb/T_s_Nm",           "coulomb/c_Nms_per_rad",
                                          "humped/delta_T_sl_Nm",     "linear_weakening/T_s_Nm",
                                          "linear_weakening/T_min_Nm", "linear_weakening/c_Nms_per_rad"};
  for (const json& j : EveryLaw()) {
    const std::string kind = j.at("law");
    for (const auto& item : j.items()) {
      if (item.key() == "law") continue;
      const std::string path = "/bit/friction/" + item.key();
      if (optional.count(kind + "/" + item.key()) == 0) ExpectRejected(Without(j, item.key()), path, {"missing"});
      ExpectRejected(With(j, item.key(), "1.0"), path, {"\"1.0\""});
      ExpectRejected(With(j, item.key(), std::numeric_limits<double>::infinity()), path, {"finite"});
    }
    ExpectRejected(With(j, "typo_Nm", 1.0), "/bit/friction/typo_Nm", {"unknown", kind});
  }
}

TEST(FrictionLaw, SchemaListsEveryLawWithItsFields) {
  const json schema = cases::FrictionLawSchema();
  EXPECT_EQ(schema.size(), EveryLaw().size());
  for (const json& j : EveryLaw()) {
    const FrictionLaw f = Law(j);
    ASSERT_TRUE(schema.contains(f.Kind())) << f.Kind();
    const json& s = schema.at(f.Kind());
    EXPECT_EQ(s.at("set_valued").get<bool>(), f.IsSetValued()) << f.Kind();
    EXPECT_EQ(s.contains("static"), f.IsSetValued()) << f.Kind();
    EXPECT_TRUE(s.at("torque").is_string());
    EXPECT_TRUE(s.at("source").is_string());
    std::set<std::string> schema_keys, json_keys;
    for (const auto& field : s.at("fields").items()) {
      schema_keys.insert(field.key());
      // Every field names its unit ("[-]" when dimensionless) and its range.
      const std::string text = field.value();
      EXPECT_NE(text.find('['), std::string::npos) << field.key() << ": " << text;
      EXPECT_NE(text.find("number"), std::string::npos) << field.key() << ": " << text;
    }
    const json written = cases::FrictionLawJson(f);
    for (const auto& item : written.items())
      if (item.key() != "law") json_keys.insert(item.key());
    EXPECT_EQ(schema_keys, json_keys) << f.Kind();
  }
}

}  // namespace
}  // namespace drillwave::bitrock
