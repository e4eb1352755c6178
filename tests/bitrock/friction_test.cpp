// Friction laws: values against hand computation, symmetry, static limits, derivatives against finite
// differences, JSON round trips and bad input naming the field.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/bitrock/friction.hpp"
#include "drillwave/core/error.hpp"

namespace drillwave::bitrock {
namespace {

const nlohmann::json kStribeck = {{"law", "stribeck"}, {"W_N", 97347},    {"R_m", 0.155575},
                                  {"mu_c", 0.5},       {"mu_s", 0.8},     {"gamma_b", 0.9},
                                  {"nu_f_rad_s", 1.0}, {"c_b_Nms_per_rad", 0.03}};

std::vector<nlohmann::json> EveryLaw() {
  return {
      {{"law", "viscous"}, {"c_Nms_per_rad", 3.0}},
      {{"law", "coulomb"}, {"T_c_Nm", 10.0}, {"T_s_Nm", 12.0}, {"c_Nms_per_rad", 0.5}},
      kStribeck,
      {{"law", "sqrt_regularized"}, {"amplitude_Nm", 100.0}, {"alpha", 1.0}, {"epsilon_rad_s", 0.1}},
      {{"law", "tanh_hump"}, {"amplitude_Nm", 100.0}, {"beta", 1.0}, {"gamma1", 2.0}, {"gamma2", 0.5}},
      {{"law", "rational"}, {"p_Nm", 100.0}, {"k", 0.5}, {"zeta", 0.01}},
      {{"law", "humped"}, {"T_sl_Nm", 0.3}, {"T_1_Nm", -0.2}, {"T_2_Nm", 0.15}, {"omega_1_s_per_rad", 2.0},
       {"omega_2_s_per_rad", 0.3}, {"b_l_Nms_per_rad", 0.01}, {"delta_T_sl_Nm", 0.02}},
      {{"law", "asymmetric_coulomb_viscous"}, {"T_s_Nm", 0.3212}, {"delta_T_s_Nm", 0.0095},
       {"b_Nms_per_rad", 1.9833}, {"delta_b_Nms_per_rad", 0.0167}},
  };
}

TEST(Friction, StribeckValues) {
  const FrictionLaw f = FrictionLaw::FromJson(kStribeck, "/bit/friction");
  const double wr = 97347 * 0.155575;
  EXPECT_TRUE(f.IsSetValued());
  EXPECT_NEAR(f.StaticPositive(), wr * 0.8, 1e-9);
  EXPECT_NEAR(f.StaticNegative(), wr * 0.8, 1e-9);
  EXPECT_NEAR(f.SlipTorque(1e-12), wr * 0.8, 1e-6);  // slip torque tends to the static level at 0+
  EXPECT_NEAR(f.SlipTorque(2.0), 0.06 + wr * (0.5 + 0.3 * std::exp(-1.8)), 1e-9);
  EXPECT_NEAR(f.SlipTorque(100.0), 3.0 + wr * 0.5, 1e-6);  // Coulomb level plus viscous at high speed
  EXPECT_NEAR(f.SlipTorque(-2.0), -f.SlipTorque(2.0), 1e-9);
}

TEST(Friction, AsymmetricUpperDiscLaw) {
  const FrictionLaw f = FrictionLaw::FromJson(EveryLaw()[7], "/upper");
  EXPECT_NEAR(f.StaticPositive(), 0.3307, 1e-12);
  EXPECT_NEAR(f.StaticNegative(), 0.3117, 1e-12);
  EXPECT_NEAR(f.SlipTorque(1.0), 0.3307 + 2.0, 1e-12);
  EXPECT_NEAR(f.SlipTorque(-1.0), -0.3117 - 1.9666, 1e-12);
}

TEST(Friction, HumpedLawHasAHumpAndItsStaticRange) {
  const FrictionLaw f = FrictionLaw::FromJson(EveryLaw()[6], "/lower");
  EXPECT_NEAR(f.StaticPositive(), 0.32, 1e-12);
  EXPECT_NEAR(f.StaticNegative(), 0.28, 1e-12);
  // T_l(w) = T_sl + T_1 tanh(w1 |w|/2) + T_2 tanh(w2 |w|/2) + b_l |w|: decreases first (T_1 < 0), then rises.
  const double w = 1.0;
  EXPECT_NEAR(f.SlipTorque(w), 0.3 - 0.2 * std::tanh(1.0) + 0.15 * std::tanh(0.15) + 0.01 + 0.02, 1e-12);
  EXPECT_LT(f.SlipTorqueDerivative(0.5), 0.0);
  EXPECT_GT(f.SlipTorqueDerivative(20.0), 0.0);
}

TEST(Friction, DerivativesMatchFiniteDifferences) {
  for (const auto& j : EveryLaw()) {
    const FrictionLaw f = FrictionLaw::FromJson(j, "/f");
    for (double w : {-7.0, -1.3, -0.2, 0.05, 0.4, 2.5, 11.0}) {
      const double h = 1e-6 * std::max(1.0, std::abs(w));
      const double fd = (f.SlipTorque(w + h) - f.SlipTorque(w - h)) / (2 * h);
      EXPECT_NEAR(f.SlipTorqueDerivative(w), fd, 1e-6 * std::max(1.0, std::abs(fd))) << f.Kind() << " at " << w;
    }
  }
}

TEST(Friction, SymmetricLawsAreOdd) {
  for (int i : {0, 1, 2, 3, 4, 5}) {
    const FrictionLaw f = FrictionLaw::FromJson(EveryLaw()[i], "/f");
    for (double w : {0.1, 1.0, 5.0}) EXPECT_NEAR(f.SlipTorque(-w), -f.SlipTorque(w), 1e-12) << f.Kind();
  }
}

TEST(Friction, JsonRoundTripAndScaling) {
  for (const auto& j : EveryLaw()) {
    const FrictionLaw f = FrictionLaw::FromJson(j, "/f");
    const FrictionLaw g = FrictionLaw::FromJson(f.ToJson(), "/f");
    EXPECT_EQ(f.Kind(), j.at("law").get<std::string>());
    const FrictionLaw s = f.Scaled(2.0);
    for (double w : {-3.0, 0.7, 4.0}) {
      EXPECT_DOUBLE_EQ(f.SlipTorque(w), g.SlipTorque(w)) << f.Kind();
      EXPECT_NEAR(s.SlipTorque(w), 2 * f.SlipTorque(w), 1e-12 * std::abs(f.SlipTorque(w)) + 1e-15) << f.Kind();
    }
    EXPECT_NEAR(s.StaticPositive(), 2 * f.StaticPositive(), 1e-12);
  }
}

void ExpectBad(nlohmann::json j, const std::string& path) {
  try {
    FrictionLaw::FromJson(j, "/bit/friction");
    ADD_FAILURE() << "accepted " << j.dump();
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), path) << e.what();
  }
}

TEST(Friction, BadInputNamesTheField) {
  auto j = kStribeck;
  j.erase("mu_s");
  ExpectBad(j, "/bit/friction/mu_s");
  j = kStribeck;
  j["mu_s"] = 0.4;  // below mu_c
  ExpectBad(j, "/bit/friction/mu_s");
  j = kStribeck;
  j["W_N"] = "heavy";
  ExpectBad(j, "/bit/friction/W_N");
  j = kStribeck;
  j["W_N"] = -1;
  ExpectBad(j, "/bit/friction/W_N");
  j = kStribeck;
  j["W_N"] = std::numeric_limits<double>::infinity();
  ExpectBad(j, "/bit/friction/W_N");
  j = kStribeck;
  j["mu_k"] = 0.3;
  ExpectBad(j, "/bit/friction/mu_k");
  ExpectBad({{"law", "magic"}}, "/bit/friction/law");
}

}  // namespace
}  // namespace drillwave::bitrock
