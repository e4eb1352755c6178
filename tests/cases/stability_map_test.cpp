// Two-parameter stability maps: the boundary cells lie where an independent bisection on the analysis puts the Hopf
// point of the saldivar string (8.344 rad/s at I_B = 89 kg m^2, and its shift with the bit inertia), the simulated
// regime is classified from the run's statistics, and bad axes are refused naming the option.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/analysis/torsional_linearization.hpp"
#include "drillwave/cases/stability_map.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

using testing::LoadCase;

// The saldivar string built by hand (not from the case): the Hopf point of steady sliding by bisection on the
// spectral abscissa of the scalar neutral form.
double HopfTopSpeed(double bit_inertia) {
  auto abscissa = [&](double omega) {
    waves::Network net;
    net.sections.push_back(waves::Section::Torsional(1172, 79.3e9, 8000, 1.19e-5));
    waves::Node top, bit;
    top.drive = waves::Drive::kSpeedDashpot;
    top.drive_damping = 2000;
    top.setpoint = model::Schedule(omega);
    bit.inertia = bit_inertia;
    bit.friction = bitrock::FrictionLaw(bitrock::Stribeck{97347, 0.155575, 0.5, 0.8, 0.9, 1.0, 0.03});
    net.nodes = {top, bit};
    return analysis::ComputeSpectrum(analysis::LinearizeTorsionalString(net, analysis::SteadySlidingStates(net, omega).back()))
        .spectral_abscissa;
  };
  double lo = 7, hi = 12;
  for (int i = 0; i < 50; ++i) (abscissa(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  return hi;
}

TEST(StabilityMap2D, BoundaryCellsLieOnTheHopfPointsOfTheSaldivarString) {
  const nlohmann::json doc = LoadCase("saldivar-stickslip");
  const StabilityMapSpec spec{ParseMapAxis("/model/top/speed_rad_s/knots/1/1=7:11:41", doc),
                              ParseMapAxis("/model/bit/inertia_kgm2=59:119:3", doc), 2, false};
  const StabilityMapResult r = StabilityMap2D(doc, spec);
  const std::size_t nx = spec.x.values.size();
  ASSERT_EQ(r.cells.size(), nx * spec.y.values.size());
  for (std::size_t j = 0; j < spec.y.values.size(); ++j) {
    const double hopf = HopfTopSpeed(spec.y.values[j]);
    int crossings = 0;
    for (std::size_t i = 1; i < nx; ++i) {
      const StabilityMapCell &a = r.cells[j * nx + i - 1], &b = r.cells[j * nx + i];
      EXPECT_EQ(b.x, spec.x.values[i]);
      EXPECT_EQ(b.y, spec.y.values[j]);
      if (a.verdict == b.verdict) continue;
      ++crossings;
      std::printf("[ measured ] I_B = %g kg m^2: the map turns stable between %g and %g rad/s; bisection: %.6f rad/s\n",
                  b.y, a.x, b.x, hopf);
      EXPECT_EQ(a.verdict, analysis::Spectrum::Verdict::kUnstable);
      EXPECT_EQ(b.verdict, analysis::Spectrum::Verdict::kStable);
      EXPECT_LT(a.x, hopf);
      EXPECT_GE(b.x, hopf);
    }
    EXPECT_EQ(crossings, 1) << "I_B = " << spec.y.values[j];
    if (spec.y.values[j] == 89) {
      EXPECT_NEAR(hopf, 8.344, 1e-3);
    }
  }
}

TEST(StabilityMap2D, SimulatedRegimeAndOutputs) {
  nlohmann::json doc = LoadCase("saldivar-stickslip");
  doc["simulation"]["duration_s"] = 30;
  doc["statistics"]["window_s"] = {15, 30};
  const StabilityMapSpec spec{ParseMapAxis("/model/top/speed_rad_s/knots/1/1=6,20", doc),
                              ParseMapAxis("/model/top/beta_Nms_per_rad=2000,20000", doc), 2, true};
  const StabilityMapResult r = StabilityMap2D(doc, spec);
  for (const StabilityMapCell& c : r.cells) {
    std::printf("[ measured ] Omega = %g, beta = %g: %s, simulated %s (stick fraction %.3f)\n", c.x, c.y,
                c.steady_states ? analysis::VerdictName(c.verdict) : "no steady state", RegimeName(c.regime),
                c.stick_fraction);
    ASSERT_NE(c.regime, Regime::kNotSimulated);
    EXPECT_EQ(c.regime == Regime::kStickSlip, c.stick_fraction > 0);
  }
  EXPECT_EQ(r.cells[0].regime, Regime::kStickSlip);  // 6 rad/s under the dissipative top of the case: stick-slip
  const auto dir = std::filesystem::temp_directory_path() / ("drillwave-map2d-" + std::to_string(::getpid()));
  WriteStabilityMap2D(doc, spec, r, dir.string());
  std::ifstream csv(dir / "stability_map.csv");
  std::string line;
  int rows = -1;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 4);
  EXPECT_TRUE(std::filesystem::exists(dir / "stability_map.svg"));
  std::filesystem::remove_all(dir);
}

// The coupled kind maps its linear verdict and, with simulate, the regime of the run beside it (the baseline in 5
// sub-sections: the linear analysis of the 20 of the case costs about 10 s a point).
TEST(StabilityMap2D, AxialTorsionalMapsTheLinearVerdictAndTheSimulatedRegime) {
  nlohmann::json doc = LoadCase("baseline-60rpm");
  doc["model"]["string"]["subsections"] = 5;
  doc["simulation"]["duration_s"] = 10;
  doc["statistics"]["window_s"] = {5, 10};
  StabilityMapSpec spec{ParseMapAxis("/model/top/speed_rad_s/knots/2/1=3,12", doc),
                        ParseMapAxis("/model/hoist/weight_on_bit_N=90000", doc), 2, true};
  const StabilityMapResult r = StabilityMap2D(doc, spec);
  ASSERT_EQ(r.cells.size(), 2u);
  for (const StabilityMapCell& c : r.cells) {
    std::printf("[ measured ] baseline (5 pieces) at %g rad/s, WOB %g N: %s, rightmost root %.5f%+.5fi; simulated %s "
                "(stick fraction %.3f)\n", c.x, c.y, analysis::VerdictName(c.verdict), c.spectral_abscissa,
                c.frequency_rad_s, RegimeName(c.regime), c.stick_fraction);
    EXPECT_TRUE(c.analysed);
    EXPECT_EQ(c.steady_states, 1);
    // RGD's regenerative axial mode: steady drilling is unstable at both speeds.
    EXPECT_EQ(c.verdict, analysis::Spectrum::Verdict::kUnstable);
    EXPECT_TRUE(c.regime == Regime::kSmooth || c.regime == Regime::kStickSlip || c.regime == Regime::kBitBouncing);
  }
}

// The fast path (roots continued from the neighbouring point, certified by the argument principle) against the full
// spectrum at every point of an rpm x WOB map of the coupled model: the same verdicts, rightmost real parts and
// frequencies. The grid is coarse (25 rpm and 22 kN apart), so that the roots move far between neighbours. The
// baseline is unstable everywhere (RGD's regenerative mode); with 40 times its axial damping some points are marginal
// (the rightmost root is one of the root chains that hug the imaginary axis).
TEST(StabilityMap2D, ContinuedRootsAgreeWithTheFullSpectrumOnTheCoupledModel) {
  for (const double axial_damping : {50.0, 2000.0}) {
    nlohmann::json doc = LoadCase("baseline-coupled-stability");
    doc["model"]["string"]["axial_damping_Ns_per_m2"] = axial_damping;
    StabilityMapSpec spec{ParseMapAxis("/model/top/speed_rad_s=4.18879:16.75516:6", doc),
                          ParseMapAxis("/model/hoist/weight_on_bit_N=50000:160000:6", doc), 2, false, true};
    const StabilityMapResult full = StabilityMap2D(doc, spec);
    spec.full_spectrum = false;
    const StabilityMapResult continued = StabilityMap2D(doc, spec);
    ASSERT_EQ(full.cells.size(), 36u);
    ASSERT_EQ(continued.cells.size(), 36u);
    EXPECT_EQ(full.full_spectra, 36);
    EXPECT_LT(continued.full_spectra, 18);  // the point of the fast path: most points need no full spectrum
    int verdicts[3] = {0, 0, 0};
    for (std::size_t k = 0; k < full.cells.size(); ++k) {
      const StabilityMapCell &a = full.cells[k], &b = continued.cells[k];
      ASSERT_EQ(a.steady_states, 1) << "at " << a.x << " rad/s, " << a.y << " N";
      ++verdicts[static_cast<int>(a.verdict)];
      EXPECT_EQ(b.steady_states, a.steady_states);
      EXPECT_EQ(b.verdict, a.verdict) << "at " << a.x << " rad/s, " << a.y << " N";
      EXPECT_NEAR(b.spectral_abscissa, a.spectral_abscissa, 1e-6 * std::abs(a.spectral_abscissa))
          << "at " << a.x << " rad/s, " << a.y << " N";
      EXPECT_NEAR(b.frequency_rad_s, a.frequency_rad_s, 1e-6 * (1 + std::abs(a.frequency_rad_s)))
          << "at " << a.x << " rad/s, " << a.y << " N";
      EXPECT_EQ(b.essential_abscissa, a.essential_abscissa);
    }
    std::printf("[ measured ] 6 x 6 coupled map, axial damping %g N s/m^2: %d stable, %d marginal, %d unstable; full "
                "%.2f s, continued %.2f s (%d full spectra)\n", axial_damping, verdicts[0], verdicts[1], verdicts[2],
                full.linear_wall_time_s, continued.linear_wall_time_s, continued.full_spectra);
    if (axial_damping > 50) {
      EXPECT_GT(verdicts[1], 0);  // the map covers marginal points too
    }
  }
}

// The wave network of pipe and collars: a map over the top speed and the bit inertia leaves the difference operator
// (the sections' reflections) alone, so neighbours share its essential abscissa; a map over the collars' polar moment
// changes it at every point. Both give the full spectrum's cells exactly.
TEST(StabilityMap2D, ContinuedRootsAgreeWithTheFullSpectrumOnPipeAndCollars) {
  const nlohmann::json doc = LoadCase("saldivar-collars");
  for (const char* second : {"/model/bit/inertia_kgm2=50:150:6", "/model/string/sections/1/polar_moment_m4=3e-5:7e-5:6"}) {
    StabilityMapSpec spec{ParseMapAxis("/model/top/speed_rad_s/knots/1/1=6:16:6", doc), ParseMapAxis(second, doc), 2,
                          false, true};
    const StabilityMapResult full = StabilityMap2D(doc, spec);
    spec.full_spectrum = false;
    const StabilityMapResult continued = StabilityMap2D(doc, spec);
    ASSERT_EQ(continued.cells.size(), full.cells.size());
    int stable = 0;
    for (std::size_t k = 0; k < full.cells.size(); ++k) {
      const StabilityMapCell &a = full.cells[k], &b = continued.cells[k];
      ASSERT_GE(a.steady_states, 1) << second << " at " << a.x << ", " << a.y;
      EXPECT_EQ(b.steady_states, a.steady_states);
      stable += a.verdict == analysis::Spectrum::Verdict::kStable;
      EXPECT_EQ(b.verdict, a.verdict) << second << " at " << a.x << ", " << a.y;
      EXPECT_NEAR(b.spectral_abscissa, a.spectral_abscissa, 1e-9 * (1 + std::abs(a.spectral_abscissa)));
      EXPECT_EQ(b.essential_abscissa, a.essential_abscissa) << second << " at " << a.x << ", " << a.y;
    }
    std::printf("[ measured ] 6 x 6 pipe-and-collars map over %s: %d stable; full %.3f s, continued %.3f s (%d full "
                "spectra)\n", second, stable, full.linear_wall_time_s, continued.linear_wall_time_s,
                continued.full_spectra);
    EXPECT_GT(stable, 0);
    EXPECT_LT(stable, 36);
  }
}

// A kind without linearization maps the simulated regimes alone (with simulate), and refuses a linear map.
TEST(StabilityMap2D, KindWithoutLinearizationMapsTheSimulatedRegimeOnly) {
  nlohmann::json doc = LoadCase("jeffcott-unbalance");
  doc["simulation"]["duration_s"] = 2;
  doc["statistics"]["window_s"] = {1, 2};
  StabilityMapSpec spec{ParseMapAxis("/model/rotor_mass_kg=10,12", doc),
                        ParseMapAxis("/model/eccentricity_m=0.1", doc), 2, true};
  const StabilityMapResult r = StabilityMap2D(doc, spec);
  ASSERT_EQ(r.cells.size(), 2u);
  for (const StabilityMapCell& c : r.cells) {
    EXPECT_FALSE(c.analysed);
    EXPECT_NE(c.regime, Regime::kNotSimulated);
  }
  spec.simulate = false;
  try {
    StabilityMap2D(doc, spec);
    ADD_FAILURE() << "jeffcott has no linearization";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/model/kind");
  }
}

TEST(StabilityMap2D, BadAxesNameTheOption) {
  const nlohmann::json doc = LoadCase("saldivar-stickslip");
  for (const char* text : {"/model/bit/inertia_kgm2", "/model/bit/inertia_kgm2=1:2", "model/bit=1:2:3",
                           "/model/no/such/0=1:2:3", "/model/bit/inertia_kgm2=1:nan:3", "/model/bit/inertia_kgm2=-5:1:3"}) {
    try {
      ParseMapAxis(text, doc);
      ADD_FAILURE() << text;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.json_path()).rfind("map", 0), 0u) << text << ": " << e.json_path();
    }
  }
  // A value the field refuses: the message names both pointers and values of the point.
  const StabilityMapSpec spec{ParseMapAxis("/model/bit/inertia_kgm2=1,-1", doc),
                              ParseMapAxis("/model/top/beta_Nms_per_rad=1,2", doc), 1, false};
  try {
    StabilityMap2D(doc, spec);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("inertia_kgm2 = -1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace drillwave::cases
