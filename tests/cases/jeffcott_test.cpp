// The Jeffcott rotor (kind jeffcott, failure seed eqs. 1-23) against closed forms: the steady synchronous whirl
// at constant drive speed is exact (x = r cos(beta - phi), y = r sin(beta - phi), constant twist), with the
// shaft's bending and shear stress of that deflection and twist and no fatigue cycles, the undamped
// rotor at its critical speed grows linearly, and a constant reverse torque twists the shaft by T / k_tor.
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/sweep.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

nlohmann::json Rotor() {
  return testing::LoadCase("jeffcott-unbalance");
}

struct Constants {
  double m, a, k_b, c_b, k_tor;
};
Constants Of(const nlohmann::json& doc, const nlohmann::json& summary) {
  const auto& md = doc["model"];
  const double m = md["rotor_mass_kg"].get<double>() + md["unbalance_mass_kg"].get<double>();
  const double w_b = summary["bending_natural_frequency_rad_s"].get<double>();
  const double inertia = md["rotor_inertia_kgm2"].get<double>() +
                         md["unbalance_mass_kg"].get<double>() * std::pow(md["eccentricity_m"].get<double>(), 2);
  const double w_tor = summary["torsional_natural_frequency_rad_s"].get<double>();
  return {m, md["unbalance_mass_kg"].get<double>() * md["eccentricity_m"].get<double>(), m * w_b * w_b,
          summary["bending_damping_Ns_per_m"].get<double>(), inertia * w_tor * w_tor};
}

// Steady whirl at constant Omega: r = a Omega^2 / sqrt((k - m Omega^2)^2 + (c Omega)^2), tan phi = c Omega / (k -
// m Omega^2), and the twist balances the unbalance's drag and the external torque: k_tor gamma = T - a Omega^2 r sin phi.
TEST(Jeffcott, SteadyWhirlAndTwistMatchTheClosedForm) {
  for (double torque : {0.0, -120.0}) {
    for (double ratio : {0.5, 0.9, 1.3}) {
      nlohmann::json doc = Rotor();
      const double w_b = RunCase(ParseCase(doc)).summary["bending_natural_frequency_rad_s"].get<double>();
      const double omega = ratio * w_b;
      doc["model"]["drive_speed_rad_s"] = {{"knots", {{0, 0}, {3, omega}}}};
      doc["model"]["torque_Nm"] = torque;
      doc["simulation"]["duration_s"] = 15;
      doc["simulation"]["abs_tol"] = doc["simulation"]["rel_tol"] = 1e-11;
      doc["statistics"]["window_s"] = {13, 15};
      doc["model"]["fatigue"] = {{"endurance_limit_Pa", 0.0}};  // so that any stress cycle would do damage
      const auto s = RunCase(ParseCase(doc)).summary;
      const Constants k = Of(doc, s);
      const double det = std::hypot(k.k_b - k.m * omega * omega, k.c_b * omega);
      const double r = k.a * omega * omega / det, sin_phi = k.c_b * omega / det;
      const double gamma = (torque - k.a * omega * omega * r * sin_phi) / k.k_tor;
      std::printf("[ measured ] Omega/w_b = %.1f, T = %g N m: whirl %.9f m (closed form %.9f), twist %.9e rad (%.9e)\n",
                  ratio, torque, s["deflection_mean_m"].get<double>(), r, s["twist_mean_rad"].get<double>(), gamma);
      EXPECT_NEAR(s["deflection_max_m"].get<double>(), r, 1e-7 * r);
      EXPECT_NEAR(s["deflection_min_m"].get<double>(), r, 1e-7 * r);
      EXPECT_NEAR(s["twist_max_rad"].get<double>(), gamma, 1e-7 * std::abs(gamma));
      EXPECT_NEAR(s["twist_min_rad"].get<double>(), gamma, 1e-7 * std::abs(gamma));
      EXPECT_NEAR(s["rotor_speed_mean_rad_s"].get<double>(), omega, 1e-9 * omega);
      // Fixed-fixed shaft, central load: sigma_b = (k_b r L / 8) c / I = 12 E d_o r / L^2; tau = G d_o |gamma| / 2L.
      const auto& shaft = doc["model"]["shaft"];
      const double e_mod = shaft["youngs_modulus_Pa"], g_mod = shaft["shear_modulus_Pa"];
      const double d_o = shaft["outer_diameter_m"], length = shaft["length_m"];
      const double sigma = 12 * e_mod * d_o * r / (length * length), tau = g_mod * d_o * std::abs(gamma) / (2 * length);
      std::printf("[ measured ] bending stress %.6e Pa (closed form %.6e), shear %.6e Pa (%.6e), damage %.3e\n",
                  s["max_bending_stress_Pa"].get<double>(), sigma, s["max_shear_stress_Pa"].get<double>(), tau,
                  s["fatigue_damage_miner"].get<double>());
      EXPECT_NEAR(s["max_bending_stress_Pa"].get<double>(), sigma, 1e-7 * sigma);
      EXPECT_NEAR(s["max_shear_stress_Pa"].get<double>(), tau, 1e-7 * tau);
      EXPECT_NEAR(s["max_von_mises_stress_Pa"].get<double>(), std::sqrt(sigma * sigma + 3 * tau * tau), 1e-7 * sigma);
      // Synchronous whirl bends every fibre of the rotor steadily: no stress cycles, although each revolution
      // would be a fully reversed cycle of sigma_b for a shaft turning in a bend fixed in space.
      EXPECT_LT(s["fatigue_damage_bending_miner"].get<double>(), 1e-30);
      EXPECT_LT(s["fatigue_damage_torsion_miner"].get<double>(), 1e-30);
    }
  }
}

// Undamped, driven at its critical speed from the start: x'' + w^2 x = (a w^2 / m) cos(w t) grows like
// (a w / 2m) t; the rotor's twist couples in only at order a^2 / (m I).
TEST(Jeffcott, UndampedRotorAtItsCriticalSpeedGrowsLinearly) {
  nlohmann::json doc = Rotor();
  doc["model"]["bending_damping_ratio"] = 0;
  doc["model"]["unbalance_mass_kg"] = 0.01;
  doc["model"]["rotor_inertia_kgm2"] = 10.0;  // a torsionally heavy rotor: the drive speed is the rotor's speed
  const double w_b = RunCase(ParseCase(doc)).summary["bending_natural_frequency_rad_s"].get<double>();
  doc["model"]["drive_speed_rad_s"] = w_b;
  doc["simulation"]["duration_s"] = 4;
  doc["simulation"]["abs_tol"] = doc["simulation"]["rel_tol"] = 1e-10;
  double previous = 0;
  for (double t_end : {2.0, 4.0}) {
    doc["statistics"]["window_s"] = {t_end - 0.05, t_end};
    doc["simulation"]["duration_s"] = t_end;
    const auto s = RunCase(ParseCase(doc)).summary;
    const Constants k = Of(doc, s);
    const double predicted = k.a * w_b / (2 * k.m) * t_end;
    std::printf("[ measured ] undamped at w_b: deflection %.6e m at t = %g s, linear growth predicts %.6e m\n",
                s["deflection_max_m"].get<double>(), t_end, predicted);
    EXPECT_NEAR(s["deflection_max_m"].get<double>(), predicted, 0.01 * predicted);
    EXPECT_GT(s["deflection_max_m"].get<double>(), 1.9 * previous);
    previous = s["deflection_max_m"].get<double>();
  }
}

// The seed's unbalance study (Figs. 11-13): with e fitted to 35 mm at 1 kg, 3 and 5 kg are predictions; the seed
// states 0.09 m and "about 0.13 m", so each must round to the seed's figure.
TEST(Jeffcott, UnbalanceStudyPredictsTheSeedsWhirlFor3And5Kg) {
  const nlohmann::json doc =
      testing::LoadCase("jeffcott-unbalance-study");
  const SweepResult sweep = RunSweep(doc, {"/model/unbalance_mass_kg", {1, 3, 5}, 2}, nullptr);
  const double seed[] = {0.035, 0.09, 0.13}, rounding[] = {0.0005, 0.005, 0.005};
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(sweep.points[i].ok) << sweep.points[i].error;
    const double whirl = sweep.points[i].summary["deflection_mean_m"].get<double>();
    std::printf("[ measured ] m_b = %g kg: whirl %.4f m, the seed %.3f m\n", sweep.points[i].value, whirl, seed[i]);
    EXPECT_NEAR(whirl, seed[i], rounding[i]);
  }
}

// Parsing the document fails with an InputError naming `json_path`.
void ExpectRefusedAt(const nlohmann::json& doc, const std::string& json_path) {
  try {
    ParseCase(doc);
    ADD_FAILURE() << "accepted; expected bad input at " << json_path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), json_path);
  }
}

TEST(Jeffcott, BadInputNamesTheJsonPath) {
  nlohmann::json doc = Rotor();
  doc["model"]["shaft"]["inner_diameter_m"] = 0.08;  // above the outer diameter
  ExpectRefusedAt(doc, "/model/shaft/inner_diameter_m");
  doc = Rotor();
  doc["model"]["unbalance_mass_kg"] = -1;
  ExpectRefusedAt(doc, "/model/unbalance_mass_kg");
  doc = Rotor();
  doc["model"].erase("drive_speed_rad_s");
  EXPECT_THROW(ParseCase(doc), InputError);
  doc = Rotor();
  doc["model"]["drive_speed_ratio"] = 0.9;  // as well as drive_speed_rad_s
  ExpectRefusedAt(doc, "/model/drive_speed_rad_s");
  doc = Rotor();
  doc["model"]["fatigue"] = {{"sn_exponent", 0.5}};  // a rising S-N curve
  ExpectRefusedAt(doc, "/model/fatigue/sn_exponent");
}

// Transients (the run-up, a brake applied and released) load the fibres in cycles, unlike the steady whirl above;
// the total is the sum of the bending and torsion damage; a shaft given by stiffnesses alone has no stresses.
TEST(Jeffcott, TransientsDoFatigueDamage) {
  nlohmann::json doc =
      testing::LoadCase("jeffcott-reverse-torque");
  doc["model"]["fatigue"] = {{"endurance_limit_Pa", 0.0}};
  doc["statistics"]["window_s"] = {0, 15};
  const auto s = RunCase(ParseCase(doc)).summary;
  EXPECT_GT(s["fatigue_damage_bending_miner"].get<double>(), 0);
  EXPECT_GT(s["fatigue_damage_torsion_miner"].get<double>(), 0);
  EXPECT_DOUBLE_EQ(s["fatigue_damage_miner"].get<double>(),
                   s["fatigue_damage_bending_miner"].get<double>() + s["fatigue_damage_torsion_miner"].get<double>());
  doc["model"]["shaft"] = {{"bending_stiffness_N_per_m", 4e5}, {"torsional_stiffness_Nm_per_rad", 3e4}};
  EXPECT_FALSE(RunCase(ParseCase(doc)).summary.contains("max_bending_stress_Pa"));
}

// Issue 41: a drive that comes to rest (its speed knots ending at 0) exited 3, because rotor_speed_norm = beta'/theta'
// divided by the drive's zero speed while the rotor still swung on the shaft. While the drive turns the channel is the
// seed's ratio; at rest it is the rotor's speed over the speed the drive ran at before it stopped.
TEST(Jeffcott, ADriveComingToRestIsAValidRun) {
  nlohmann::json doc = Rotor();
  doc["model"]["drive_speed_rad_s"] = {{"knots", {{0, 0}, {0.2, 100}, {0.3, 100}, {0.35, 0}}}};
  doc["simulation"] = {{"duration_s", 0.6}, {"output_interval_s", 0.001}};
  doc["statistics"]["window_s"] = {0, 0.6};
  doc.erase("expect");
  CaseRun run;
  ASSERT_NO_THROW(run = RunCase(ParseCase(doc)));
  const auto& t = run.result.time_s;
  const auto& norm = run.result.channel("rotor_speed_norm").values;
  const auto& rotor_rpm = run.result.channel("bit_rpm").values;
  const auto& drive_rpm = run.result.channel("top_rpm").values;
  int at_rest_turning = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    ASSERT_TRUE(std::isfinite(norm[i])) << "t = " << t[i];
    if (t[i] > 0.01 && t[i] < 0.34) {
      EXPECT_NEAR(norm[i], rotor_rpm[i] / drive_rpm[i], 1e-12 * std::abs(norm[i])) << "t = " << t[i];
    }
    if (t[i] > 0.36) {
      EXPECT_EQ(drive_rpm[i], 0.0);
      EXPECT_NEAR(norm[i], rotor_rpm[i] * kPi / 30 / 100, 1e-12) << "t = " << t[i];
      at_rest_turning += rotor_rpm[i] != 0;
    }
  }
  EXPECT_GT(at_rest_turning, 100) << "the rotor swings on after the drive stopped";
}

}  // namespace
}  // namespace drillwave::cases
