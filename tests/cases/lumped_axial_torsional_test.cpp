// The lumped axial-torsional kind (Richard, Germay & Detournay, chapter eq. 2.11): steady drilling against the closed
// form of the RGD law, its input errors, and its agreement with the wave kind axial_torsional on a short stiff string.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/analysis/spectrum.hpp"
#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

nlohmann::json Lumped() {
  return testing::LoadCase("rgd-lumped");
}

// Without a disturbance the run stays in steady drilling, which the RGD law gives in closed form:
//   d0 = (W0 - a sigma l) / (a zeta eps),  V0 = d0 Omega / 2 pi,  T0 = a^2 eps d0 / 2 + a gamma mu a sigma l / 2,
//   t_n0 = 2 pi / (n Omega),  top torque T0 (the spring's twist T0 / C, plus c times a zero speed difference).
// (Steady drilling is unstable: rounding-sized perturbations grow, to 1e-9 of V0 after 1.1 s at 9 rad/s; the run
// stops at 1 s.)
TEST(LumpedAxialTorsional, SteadyDrillingIsTheClosedFormOfTheRgdLaw) {
  for (double damping : {0.0, 50.0}) {
    nlohmann::json doc = Lumped();
    auto& m = doc["model"];
    const double omega = 9.0;
    m["top"]["speed_rad_s"] = omega;
    m["string"]["damping_Nms_per_rad"] = damping;
    doc["simulation"] = {{"duration_s", 1}, {"output_interval_s", 0.01}, {"abs_tol", 1e-10}, {"rel_tol", 1e-10}};
    doc["statistics"]["window_s"] = {0, 1};
    const double a = m["bit"]["radius_m"], eps = m["rock"]["intrinsic_specific_energy_Pa"], zeta = m["rock"]["zeta"];
    const double sigma_l = m["rock"]["sigma_l_N_per_m"], mu = m["rock"]["mu"], gamma = m["rock"]["gamma"];
    const double w0 = m["hoist"]["weight_on_bit_N"], n = m["bit"]["blades"];
    const double depth = (w0 - a * sigma_l) / (a * zeta * eps);
    const double rop = depth * omega / (2 * kPi);
    const double torque = 0.5 * a * a * eps * depth + 0.5 * a * gamma * mu * a * sigma_l;
    const CaseRun run = RunCase(ParseCase(doc));
    const RunResult& r = run.result;
    for (std::size_t i = 0; i < r.time_s.size(); ++i) {
      ASSERT_NEAR(r.channel("bit_rpm").values[i], omega * 30 / kPi, 1e-7) << "t = " << r.time_s[i];
      ASSERT_NEAR(r.channel("bit_axial_speed_m_s").values[i], rop, 1e-9 * rop) << "t = " << r.time_s[i];
      ASSERT_NEAR(r.channel("depth_of_cut_m").values[i], depth, 1e-8 * depth) << "t = " << r.time_s[i];
      ASSERT_NEAR(r.channel("bit_torque_Nm").values[i], torque, 1e-8 * torque) << "t = " << r.time_s[i];
      ASSERT_NEAR(r.channel("top_torque_Nm").values[i], torque, 1e-8 * torque) << "t = " << r.time_s[i];
      ASSERT_NEAR(r.channel("wob_N").values[i], w0, 1e-8 * w0) << "t = " << r.time_s[i];
      ASSERT_NEAR(r.channel("cut_delay_s").values[i], 2 * kPi / (n * omega), 1e-9) << "t = " << r.time_s[i];
    }
    EXPECT_NEAR(run.summary.at("steady_rop_m_h").get<double>(), 3600 * rop, 1e-9 * 3600 * rop);
    EXPECT_NEAR(run.summary.at("steady_bit_torque_Nm").get<double>(), torque, 1e-9 * torque);
    EXPECT_EQ(run.summary.at("stick_onsets").get<int>(), 0);
  }
}

TEST(LumpedAxialTorsional, BadInputIsRefusedByItsField) {
  auto refused_at = [](nlohmann::json doc) -> std::string {
    try {
      ParseCase(doc);
    } catch (const InputError& e) {
      return e.json_path();
    }
    return "accepted";
  };
  nlohmann::json both = Lumped();
  both["model"]["string"]["stiffness_Nm_per_rad"] = 480;
  EXPECT_EQ(refused_at(both), "/model/string");
  nlohmann::json light = Lumped();
  light["model"]["hoist"]["weight_on_bit_N"] = 40000;  // below a sigma l = 48.6 kN
  EXPECT_EQ(refused_at(light), "/model/hoist/weight_on_bit_N");
  nlohmann::json stopped = Lumped();
  stopped["model"]["top"]["speed_rad_s"] = 0;
  EXPECT_EQ(refused_at(stopped), "/model/top/speed_rad_s");
  nlohmann::json hollow = Lumped();
  hollow["model"]["string"]["inner_diameter_m"] = 0.2;
  EXPECT_EQ(refused_at(hollow), "/model/string/inner_diameter_m");
  nlohmann::json blades = Lumped();
  blades["model"]["bit"]["blades"] = 0;
  EXPECT_EQ(refused_at(blades), "/model/bit/blades");
}


// The wave kind axial_torsional on a short stiff string (100 m of the baseline pipe, no damping, no mud) under a top
// drive heavy and stiff enough to hold its speed (J_td = 1e6 kg m^2, kp = 1e7 N m s/rad) and a light hoist (10 kg,
// under a constant hook force: the string's top is axially free), against the lumped kind with the string reduced to
// its first modes: C = G J / L, I = J_b + rho J L / 3 (Rayleigh), M = M_b + rho A L + M_h (the string moves axially
// as one body). At low frequency (the torsional mode at 10 rad/s, the regenerative axial pair near 28 rad/s, against
// travel times of 31 and 19 ms) the two linearizations' roots agree.
TEST(LumpedAxialTorsional, ShortStiffStringHasTheRootsOfTheWaveModel) {
  nlohmann::json wave =
      testing::LoadCase("baseline-coupled-stability");
  auto& w = wave["model"];
  const double length = 100, hoist = 10;
  w["string"]["length_m"] = length;
  w["string"]["torsional_damping_Nms_per_rad_m"] = 0;
  w["string"]["axial_damping_Ns_per_m2"] = 0;
  w["string"]["mud_density_kg_m3"] = 0;
  w["top"] = {{"inertia_kgm2", 1e6}, {"kp_Nms_per_rad", 1e7}, {"ki_Nm_per_rad", 0}, {"speed_rad_s", 2 * kPi}};
  w["hoist"]["mass_kg"] = hoist;
  const auto& s = w["string"];
  const double od = s["outer_diameter_m"], id = s["inner_diameter_m"], rho = s["density_kg_m3"];
  const double polar = kPi / 32 * (std::pow(od, 4) - std::pow(id, 4)), area = kPi / 4 * (od * od - id * id);
  nlohmann::json lumped = Lumped();
  auto& l = lumped["model"];
  l["string"] = {{"length_m", length}, {"outer_diameter_m", od}, {"inner_diameter_m", id},
                 {"shear_modulus_Pa", s["shear_modulus_Pa"]}};
  l["bit"]["inertia_kgm2"] = w["bit"]["inertia_kgm2"].get<double>() + rho * polar * length / 3;
  l["bit"]["mass_kg"] = w["bit"]["mass_kg"].get<double>() + rho * area * length + hoist;
  l["top"]["speed_rad_s"] = 2 * kPi;
  l["hoist"]["weight_on_bit_N"] = w["hoist"]["weight_on_bit_N"];
  analysis::SpectrumOptions o;
  o.im_max = 60;
  const auto wave_points = ParseCase(wave).model->Linearize();
  const auto lumped_points = ParseCase(lumped).model->Linearize();
  ASSERT_EQ(wave_points.size(), 1u);
  ASSERT_EQ(lumped_points.size(), 1u);
  const analysis::Spectrum ws = analysis::ComputeSpectrum(wave_points[0].system, o);
  const analysis::Spectrum ls = analysis::ComputeSpectrum(lumped_points[0].system, o);
  int compared = 0;
  for (const auto& r : ls.roots) {
    if (r.s.real() < -2 || r.s.imag() > 40) continue;
    std::complex<double> nearest = 1e300;
    for (const auto& q : ws.roots)
      if (std::abs(q.s - r.s) < std::abs(nearest - r.s)) nearest = q.s;
    const double rel = std::abs(nearest - r.s) / std::abs(r.s);
    std::printf("[ measured ] 100 m string: lumped root %.5f%+.5fi, wave root %.5f%+.5fi (relative difference %.2e)\n",
                r.s.real(), r.s.imag(), nearest.real(), nearest.imag(), rel);
    EXPECT_LT(rel, 0.02) << r.s;
    ++compared;
  }
  EXPECT_GE(compared, 2);
  EXPECT_GT(ls.spectral_abscissa, 0);
  EXPECT_GT(ws.spectral_abscissa, 0);
}

}  // namespace
}  // namespace drillwave::cases
