// The lumped chain (kind lumped_chain): its linearization against the closed-form frequencies of a two-inertia
// chain, a uniform pipe lumped ever finer converging at second order to the wave string's first mode, the two-mass
// pendulum as the chain without inner inertias (the same run sample for sample), the energy balance of the 4-DOF
// case, and the refusal of inconsistent arrays.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

using nlohmann::json;
using testing::LoadCase;

// A chain under a prescribed top speed (a fixed end for small motions), without friction: bit and inner inertias,
// springs only.
json FreeChain(const std::vector<double>& inner, const std::vector<double>& k, double bit_inertia) {
  return {{"name", "chain"},
          {"model",
           {{"kind", "lumped_chain"},
            {"string", {{"inertias_kgm2", inner}, {"stiffnesses_Nm_per_rad", k}}},
            {"top", {{"inertia_kgm2", 1000.0}, {"type", "prescribed_speed"}, {"speed_rad_s", 10.0}}},
            {"bit", {{"inertia_kgm2", bit_inertia}}}}},
          {"simulation", {{"duration_s", 1.0}}}};
}

// The chain's natural frequencies [rad/s], ascending: the imaginary parts of its linearization's eigenvalues.
std::vector<double> Frequencies(const json& doc) {
  const auto points = ParseCase(doc).model->Linearize();
  EXPECT_EQ(points.size(), 1u);
  const Eigen::VectorXcd roots = Eigen::EigenSolver<Eigen::MatrixXd>(points.at(0).system.a0).eigenvalues();
  std::vector<double> w;
  for (const auto& s : roots)
    if (s.imag() > 0) w.push_back(s.imag());
  std::sort(w.begin(), w.end());
  return w;
}

TEST(LumpedChain, NaturalFrequenciesOfAFixedFreeChainAreTheClosedForm) {
  // top (fixed) - k - J - k - J: w^2 = (k / J) (3 -+ sqrt 5) / 2.
  const double j = 470, k = 900;
  const std::vector<double> w = Frequencies(FreeChain({j}, {k, k}, j));
  ASSERT_EQ(w.size(), 2u);
  EXPECT_NEAR(w[0], std::sqrt(k / j * (3 - std::sqrt(5.0)) / 2), 1e-12 * w[0]);
  EXPECT_NEAR(w[1], std::sqrt(k / j * (3 + std::sqrt(5.0)) / 2), 1e-12 * w[1]);
}

TEST(LumpedChain, AUniformPipeLumpedFinerConvergesToTheWaveStringAtSecondOrder) {
  // The Saldivar pipe (saldivar-stickslip.json) fixed at the top with its bit inertia below. The wave string's first
  // mode: x tan x = rho J L / J_b with x = w L / c.
  const double g = 79.3e9, rho = 8000, polar = 1.19e-5, length = 1172, bit = 89;
  const double c = std::sqrt(g / rho), ratio = rho * polar * length / bit;
  double lo = 0, hi = 1.5707963;  // the root below pi / 2
  for (int i = 0; i < 200; ++i) ((lo + hi) / 2 * std::tan((lo + hi) / 2) < ratio ? lo : hi) = (lo + hi) / 2;
  const double exact = (lo + hi) / 2 * c / length;
  std::vector<double> errors;
  for (int n : {8, 16, 32}) {
    // n springs of G J / (L / n); the n - 1 inner nodes carry a piece's inertia, the bit its own and half a piece.
    const double piece = rho * polar * length / n;
    const std::vector<double> w = Frequencies(
        FreeChain(std::vector<double>(n - 1, piece), std::vector<double>(n, g * polar * n / length), bit + piece / 2));
    errors.push_back(std::abs(w.front() - exact) / exact);
  }
  std::printf("[ chain ] first mode %.6f rad/s; relative error at 8, 16, 32 pieces: %.3g, %.3g, %.3g\n", exact,
              errors[0], errors[1], errors[2]);
  EXPECT_GT(errors[0] / errors[1], 3.6);
  EXPECT_LT(errors[0] / errors[1], 4.4);
  EXPECT_GT(errors[1] / errors[2], 3.8);
  EXPECT_LT(errors[1] / errors[2], 4.2);
  EXPECT_LT(errors[2], 2e-3);
}

TEST(LumpedChain, TheTwoMassPendulumIsTheChainWithoutInnerInertias) {
  json pendulum = LoadCase("two-mass-stickslip");
  pendulum["simulation"]["duration_s"] = 60;
  pendulum["statistics"] = {{"window_s", {20, 60}}};
  pendulum.erase("expect");
  json chain = pendulum;
  const json shaft = pendulum["model"]["string"];
  chain["model"]["kind"] = "lumped_chain";
  chain["model"]["string"] = {{"inertias_kgm2", json::array()},
                              {"stiffnesses_Nm_per_rad", {shaft["stiffness_Nm_per_rad"]}},
                              {"dampings_Nms_per_rad", {shaft["damping_Nms_per_rad"]}}};
  const RunResult a = RunCase(ParseCase(pendulum)).result, b = RunCase(ParseCase(chain)).result;
  ASSERT_EQ(a.time_s.size(), b.time_s.size());
  EXPECT_EQ(a.channel("bit_rpm").values, b.channel("bit_rpm").values);
  EXPECT_EQ(a.channel("top_torque_Nm").values, b.channel("top_torque_Nm").values);
  EXPECT_EQ(a.summary.at("stick_fraction"), b.summary.at("stick_fraction"));
}

TEST(LumpedChain, TheFourInertiaChainKeepsItsEnergyBalanceThroughStickSlip) {
  const json doc = LoadCase("lumped-chain-4dof");
  const RunResult r = RunCase(ParseCase(doc)).result;
  EXPECT_GT(r.summary.at("stick_fraction").get<double>(), 0.05);
  for (const char* name : {"inertia_1_rpm", "inertia_2_rpm"})
    EXPECT_TRUE(std::any_of(r.channels.begin(), r.channels.end(), [&](const Channel& ch) { return ch.name == name; }))
        << name;
  EXPECT_LT(r.summary.at("energy_balance_residual_max_J").get<double>(),
            1e-5 * r.summary.at("work_in_J").get<double>());
}

// A bit's normal load (two_mass's) runs, with its channel, but is no state of the linearization: refused there.
TEST(LumpedChain, ANormalLoadRunsAndIsRefusedByTheLinearization) {
  json doc = LoadCase("lumped-chain-4dof");
  doc["simulation"]["duration_s"] = 20;
  doc["statistics"] = {{"window_s", {5, 20}}};
  doc.erase("expect");
  doc["model"]["bit"]["normal_load"] = {{"torque_gain_N_per_Nm", 1.0}, {"time_constant_s", 0.05}};
  const Case c = ParseCase(doc);
  const RunResult r = RunCase(c).result;
  EXPECT_GT(r.channel("normal_load_N").values.back(), 0.5 * 97347);
  try {
    c.model->Linearize();
    FAIL() << "the normal load is not linearized";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/model/bit/normal_load") << e.what();
  }
}

// A long chain writes every inner inertia's speed but draws six of them.
TEST(LumpedChain, ALongChainDrawsSixOfItsInnerInertias) {
  json doc = FreeChain(std::vector<double>(40, 10.0), std::vector<double>(41, 1e5), 10.0);
  doc["simulation"] = {{"duration_s", 0.5}, {"output_interval_s", 0.01}};
  const RunResult r = RunCase(ParseCase(doc)).result;
  EXPECT_NO_THROW(r.channel("inertia_40_rpm"));
  EXPECT_EQ(r.plot_panels.front().size(), 8u);  // top, six inner, bit
}

TEST(LumpedChain, RefusesArraysThatDoNotMatchNamingTheField) {
  json doc = FreeChain({470, 750}, {900, 900}, 470);
  try {
    ParseCase(doc);
    FAIL() << "two inner inertias need three couplings";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/model/string/stiffnesses_Nm_per_rad"), std::string::npos) << e.what();
  }
  doc = FreeChain({470}, {900, 900}, 470);
  doc["model"]["string"]["dampings_Nms_per_rad"] = {1.0};
  EXPECT_THROW(ParseCase(doc), InputError);
  doc = FreeChain({-470}, {900, 900}, 470);
  EXPECT_THROW(ParseCase(doc), InputError);
}

}  // namespace
}  // namespace drillwave::cases
