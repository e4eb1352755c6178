// Linearized stability of cases: steady states against their closed forms, the Hopf points of every kind against
// independent figures (Routh-Hurwitz for the two-disc set-up, the wave-network growth rates for the string, the
// measured start of linear stability of the two-mass pendulum), maps, and clear errors where no linearization
// exists.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/stability.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

using testing::LoadCase;

std::vector<OperatingPointStability> Analyze(nlohmann::json doc) { return AnalyzeStability(ParseCase(doc)); }

TEST(CaseStability, TwoDiscSteadyStateAndBranchesOfFig4) {
  nlohmann::json doc = LoadCase("two-disc-steady");
  auto at = [&](double u) {
    doc["model"]["upper_disc"]["input_voltage_V"] = u;
    return Analyze(doc);
  };
  const auto steady = at(0.3);
  ASSERT_EQ(steady.size(), 1u);
  // The same root the case's expect block holds (bisection in the case notes).
  EXPECT_NEAR(steady[0].point.steady_state.at("speed_rad_s").get<double>(), 0.2713141552, 1e-9);
  EXPECT_TRUE(steady[0].spectrum.stable);
  EXPECT_TRUE(at(0.12).empty()) << "below break-away nothing slides";
  EXPECT_FALSE(at(0.6)[0].spectrum.stable);  // e3
  EXPECT_FALSE(at(2.0)[0].spectrum.stable);
  EXPECT_TRUE(at(8.0)[0].spectrum.stable);   // e4
  // The map finds A and D where the Routh-Hurwitz test of two_disc_test.cpp and the case notes put them.
  const SweepSpec spec{"/model/upper_disc/input_voltage_V", ParseSweepValues("0.40:0.60:201", "v"), 2};
  const auto rows = StabilityMap(doc, spec);
  double a = NAN;
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (rows[i - 1].stable && !rows[i].stable) a = 0.5 * (rows[i - 1].value + rows[i].value);
  std::printf("[ measured ] two-disc stability map: e2 loses stability at u_c = %.4f V\n", a);
  EXPECT_NEAR(a, 0.4849, 1e-3);
}

TEST(CaseStability, SaldivarSteadySlidingIsStableWhileStickSlipCoexists) {
  const auto r = Analyze(LoadCase("saldivar-stickslip"));
  ASSERT_EQ(r.size(), 1u);
  const double w0 = r[0].point.steady_state.at("bit_speed_rad_s").get<double>();
  std::printf("[ measured ] saldivar at 10 rad/s: steady sliding at %.9f rad/s, rightmost root %.6f%+.6fi, "
              "essential %.6f\n", w0, r[0].spectrum.spectral_abscissa, r[0].spectrum.roots[0].s.imag(),
              r[0].spectrum.essential_abscissa);
  EXPECT_NEAR(2000 * (10 - w0), r[0].point.steady_state.at("bit_torque_Nm").get<double>(), 1e-6);
  // Linearly stable (the simulation from rest still ends in stick-slip: bistability), decay rate 0.209 1/s.
  EXPECT_TRUE(r[0].spectrum.stable);
  EXPECT_NEAR(r[0].spectrum.spectral_abscissa, -0.2094, 1e-3);
  // The chapter's NDDE coefficients, as DESIGN.md §1 works them out for this string.
  const auto& ndde = r[0].point.steady_state.at("neutral_dde");
  EXPECT_NEAR(ndde.at("impedance_Nms_per_rad").get<double>(), 299.7, 0.05);
  EXPECT_NEAR(ndde.at("round_trip_s").get<double>(), 0.7445, 5e-5);
  EXPECT_NEAR(ndde.at("upsilon").get<double>(), 0.7393, 5e-5);
  EXPECT_NEAR(ndde.at("psi_per_s").get<double>(), 3.368, 5e-4);
  EXPECT_NEAR(ndde.at("pi_per_s").get<double>(), 5.858, 5e-4);
  // The smooth case's steady state is the speed its expect block holds.
  const auto smooth = Analyze(LoadCase("saldivar-smooth"));
  ASSERT_EQ(smooth.size(), 1u);
  EXPECT_NEAR(smooth[0].point.steady_state.at("bit_speed_rad_s").get<double>(), 16.2135658705, 1e-8);
}

TEST(CaseStability, TwoMassSmoothRotationIsStableFromAbout4RadPerS) {
  const nlohmann::json doc = LoadCase("two-mass-stickslip");
  const SweepSpec spec{"/model/top/speed_rad_s/knots/1/1", ParseSweepValues("3.5:4.5:101", "v"), 2};
  const auto rows = StabilityMap(doc, spec);
  double crossing = NAN;
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (!rows[i - 1].stable && rows[i].stable) crossing = 0.5 * (rows[i - 1].value + rows[i].value);
  std::printf("[ measured ] two-mass (prescribed top speed): smooth rotation stable from %.3f rad/s\n", crossing);
  EXPECT_NEAR(crossing, 4.12, 0.01);
  // A PI-driven top adds the integral state: the steady state is at the set-point, and a Coulomb bit (no velocity
  // weakening) keeps it stable.
  const auto pi = Analyze(LoadCase("two-mass-pi-coulomb"));
  ASSERT_EQ(pi.size(), 1u);
  EXPECT_EQ(pi[0].point.state_names.back(), "pi_integral_rad");
  EXPECT_NEAR(pi[0].point.steady_state.at("speed_rad_s").get<double>(), 5.0, 1e-12);
  EXPECT_TRUE(pi[0].spectrum.stable);
}

TEST(CaseStability, KindsWithoutALinearizationSaySo) {
  try {
    Analyze(LoadCase("jeffcott-unbalance"));
    FAIL() << "the Jeffcott rotor has no linearization";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/model/kind");
  }
  // Every top of the torsional string linearizes now: the force-controlled bar (torque top) has its steady states.
  EXPECT_NO_THROW(Analyze(LoadCase("bar-step")));
}

// The motor tops linearize with their own states: an induction motor's fluxes, a compliant gear's motor speed and
// twist (tests/analysis/network_stability_test.cpp checks their roots).
TEST(CaseStability, MotorAndGearTopsAddTheirStates) {
  auto has_state = [](const OperatingPointStability& p, const std::string& name) {
    return std::find(p.point.state_names.begin(), p.point.state_names.end(), name) != p.point.state_names.end();
  };
  const auto induction = Analyze(LoadCase("induction-motor-stickslip"));
  ASSERT_FALSE(induction.empty());
  EXPECT_TRUE(has_state(induction.back(), "top_rotor_flux_q_Wb"));
  // On the motor's steep torque-speed curve just below the synchronous 2 pi 25.5 / 16 rad/s.
  const double synchronous = 2 * kPi * 25.5 / 16;
  const double w0 = induction.back().point.steady_state.at("bit_speed_rad_s").get<double>();
  EXPECT_LT(w0, synchronous);
  EXPECT_GT(w0, 0.95 * synchronous);
  const auto rig = Analyze(LoadCase("rig-two-mass"));
  ASSERT_EQ(rig.size(), 1u);
  EXPECT_TRUE(has_state(rig[0], "top_gear_twist_rad"));
  EXPECT_NEAR(rig[0].point.steady_state.at("bit_speed_rad_s").get<double>(), 20.0, 1e-12);
}

TEST(CaseStability, AMapStopsAtAValueWithoutALinearizationWhateverTheThreads) {
  // A string of 1e20 m puts more roots on the neutral chain than the analysis takes: the map's first value passes the
  // check before the threads start and the later ones fail in the workers.
  nlohmann::json doc = LoadCase("saldivar-stickslip");
  for (int jobs : {1, 2}) {
    try {
      StabilityMap(doc, {"/model/string/sections/0/length_m", {1172.0, 1e20, 1e21}, jobs});
      FAIL() << "a string of 1e20 m is out of range (" << jobs << " jobs)";
    } catch (const InputError& e) {
      EXPECT_EQ(e.json_path(), "/model");
      EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
    }
  }
}

// The network linearization of the collars case (two sections, no scalar form) against the one-section string: the
// collars shift the Hopf point of steady sliding; the map finds the same crossing as bisection on the spectrum.
TEST(CaseStability, CollarsCaseLinearizesAsANetwork) {
  const auto r = Analyze(LoadCase("saldivar-collars"));
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].point.state_names.size(), 5u);  // bit speed and four wave integrals
  EXPECT_LT(r[0].spectrum.essential_abscissa, 0);
  EXPECT_EQ(r[0].spectrum.verdict, analysis::Spectrum::Verdict::kStable);
}

TEST(CaseStability, OutputsAreWritten) {
  const Case c = ParseCase(LoadCase("two-disc-setup"));
  const auto dir = std::filesystem::temp_directory_path() / ("drillwave-stability-" + std::to_string(::getpid()));
  WriteStabilityOutputs(c, AnalyzeStability(c), dir.string());
  for (const char* f : {"stability.json", "roots.csv", "report.md", "case.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  const auto json = io::LoadJsonFile((dir / "stability.json").string());
  EXPECT_FALSE(json.at("operating_points").at(0).at("stable").get<bool>());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace drillwave::cases
