// The hoist of the axial_torsional kind under a hook force schedule H(t) (chapter eq. 2.23): the steady weight on bit
// of the axial balance, and the d'Alembert travel time of a hook-force step to the bit.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "refused_path.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

nlohmann::json HoistStep() {
  nlohmann::json doc = testing::LoadCase("hoist-step");
  doc.erase("expect");
  return doc;
}
const std::vector<double>& Values(const CaseRun& run, const std::string& name) { return run.result.channel(name).values; }

// Steady drilling at top speed Omega under hook force H, from the case's parameters: W_b - H = W + c_a L V with
// V = (W - a sigma l) Omega / (2 pi a zeta eps), solved for the weight on bit W.
struct AxialBalance {
  double buoyant_weight, drag_per_speed, contact_force, cut_weight_per_depth;
  explicit AxialBalance(const nlohmann::json& md) {
    const auto& s = md["string"];
    const double rho = s["density_kg_m3"], rho_mud = s["mud_density_kg_m3"], g = 9.81;
    const double od = s["outer_diameter_m"], id = s["inner_diameter_m"], length = s["length_m"];
    buoyant_weight = (rho - rho_mud) * g * kPi / 4 * (od * od - id * id) * length +
                     md["bit"]["mass_kg"].get<double>() * g * (1 - rho_mud / rho);
    drag_per_speed = s["axial_damping_Ns_per_m2"].get<double>() * length;
    const double a = md["bit"]["radius_m"];
    contact_force = a * md["rock"]["sigma_l_N_per_m"].get<double>();
    cut_weight_per_depth = a * md["rock"]["zeta"].get<double>() * md["rock"]["intrinsic_specific_energy_Pa"].get<double>();
  }
  double Rop(double wob, double omega) const { return (wob - contact_force) / cut_weight_per_depth * omega / (2 * kPi); }
  double WeightOnBit(double hook, double omega) const {  // linear in W: bisection would do, the closed form is exact
    const double kappa = drag_per_speed * omega / (2 * kPi) / cut_weight_per_depth;
    return (buoyant_weight - hook + kappa * contact_force) / (1 + kappa);
  }
};

// A constant hook force equal to the one the kind sets for a target weight on bit is the same run.
TEST(AxialTorsionalHoist, ConstantHookForceIsTheTargetWeightOnBitRun) {
  nlohmann::json by_weight = HoistStep();
  by_weight["model"]["hoist"] = {{"mass_kg", 30000}, {"weight_on_bit_N", 90000}};
  by_weight["simulation"]["duration_s"] = 2;
  by_weight["statistics"]["window_s"] = {0, 2};
  const CaseRun a = RunCase(ParseCase(by_weight));
  const double hook = a.summary.at("hook_force_N").get<double>();
  nlohmann::json by_hook = by_weight;
  by_hook["model"]["hoist"] = {{"mass_kg", 30000}, {"hook_force_N", hook}};
  const CaseRun b = RunCase(ParseCase(by_hook));
  const double omega = by_weight["model"]["top"]["speed_rad_s"];
  EXPECT_NEAR(AxialBalance(by_weight["model"]).WeightOnBit(hook, omega), 90000, 1e-9 * 90000);
  for (const char* name : {"wob_N", "bit_rpm", "hookload_N"}) {
    ASSERT_EQ(Values(a, name).size(), Values(b, name).size());
    for (std::size_t k = 0; k < Values(a, name).size(); ++k)
      EXPECT_NEAR(Values(a, name)[k], Values(b, name)[k], 1e-6 * std::abs(Values(a, name)[k]) + 1e-9) << name;
  }
}

// H rises by 5 kN at 5 s: after two minutes the weight on bit and the rate of penetration are those of the axial
// balance at the new hook force.
TEST(AxialTorsionalHoist, HookForceStepGivesTheClosedFormSteadyWeightOnBit) {
  const nlohmann::json doc = HoistStep();
  const CaseRun run = RunCase(ParseCase(doc));
  const AxialBalance balance(doc["model"]);
  const double omega = doc["model"]["top"]["speed_rad_s"];
  const double hook = doc["model"]["hoist"]["hook_force_N"]["knots"].back()[1];
  const double wob = balance.WeightOnBit(hook, omega), rop = 3600 * balance.Rop(wob, omega);
  const double wob_mean = run.summary.at("wob_mean_N"), rop_mean = run.summary.at("rop_mean_m_h");
  std::printf("[ measured ] weight on bit %.4f N, rate of penetration %.5f m/h over the last 20 s (axial balance: "
              "%.4f N, %.5f m/h)\n", wob_mean, rop_mean, wob, rop);
  EXPECT_NEAR(wob_mean, wob, 1e-5 * wob);
  EXPECT_NEAR(rop_mean, rop, 1e-4 * rop);
  EXPECT_EQ(run.summary.at("stick_onsets").get<int>(), 0);
}

// Nothing at the bit moves before the step's axial wave arrives, t_step + L / sqrt(E / rho); the weight on bit then
// departs within 3 ms (the hoist's mass turns the force step into a kink of the top speed, so the bit's response
// starts smoothly).
TEST(AxialTorsionalHoist, HookForceStepReachesTheBitOneAxialTravelTimeLater) {
  nlohmann::json doc = HoistStep();
  doc["simulation"]["duration_s"] = 5.6;
  doc["simulation"]["output_interval_s"] = 1e-4;
  doc["simulation"]["abs_tol"] = doc["simulation"]["rel_tol"] = 1e-9;
  doc["statistics"]["window_s"] = {0, 5.6};
  const CaseRun run = RunCase(ParseCase(doc));
  const auto& s = doc["model"]["string"];
  const double step = doc["model"]["hoist"]["hook_force_N"]["knots"].back()[0];
  const double arrival = step + s["length_m"].get<double>() /
                                    std::sqrt(s["youngs_modulus_Pa"].get<double>() / s["density_kg_m3"].get<double>());
  const std::vector<double>& t = run.result.time_s;
  const std::vector<double>& wob = Values(run, "wob_N");
  double before = 0, departure = NAN;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double change = std::abs(wob[k] - wob.front());
    if (t[k] < arrival - 1e-3) before = std::max(before, change);
    if (std::isnan(departure) && change > 0.01) departure = t[k];
  }
  std::printf("[ measured ] largest weight-on-bit change before the arrival at %.6f s: %.3g N; departs by 0.01 N at "
              "%.4f s\n", arrival, before, departure);
  EXPECT_LT(before, 1e-4);
  EXPECT_GE(departure, arrival);
  EXPECT_LT(departure, arrival + 3e-3);
}

TEST(AxialTorsionalHoist, HookForceAndTargetWeightOnBitExcludeEachOther) {
  nlohmann::json doc = HoistStep();
  doc["model"]["hoist"]["weight_on_bit_N"] = 90000;
  EXPECT_THROW(ParseCase(doc), InputError);
  doc["model"]["hoist"].erase("hook_force_N");
  doc["model"]["hoist"]["weight_on_bit_N"] = 90000;
  EXPECT_NO_THROW(ParseCase(doc));
  doc["model"]["hoist"].erase("weight_on_bit_N");
  EXPECT_THROW(ParseCase(doc), InputError);
  doc["model"]["hoist"]["hook_force_N"] = 600000;  // leaves less than a sigma l on the bit
  EXPECT_EQ(testing::RefusedPath(doc), "/model/hoist/hook_force_N");
}

// The hoist's dashpot pulls against the block paying out at the steady rate of penetration: nothing in steady drilling,
// so a start at the target weight on bit stays there. It is refused with the rig (whose dampers hold the block).
TEST(AxialTorsionalHoist, HoistDashpotIsQuietInSteadyDrilling) {
  nlohmann::json doc = HoistStep();
  auto& hoist = doc["model"]["hoist"];
  hoist.erase("hook_force_N");
  hoist["weight_on_bit_N"] = 90000;
  hoist["damping_Ns_per_m"] = 2e5;
  doc["model"]["top"]["speed_rad_s"] = 2 * kPi;
  doc["simulation"]["duration_s"] = 2;
  doc["statistics"] = {{"window_s", {0, 2}}};
  const CaseRun run = RunCase(ParseCase(doc));
  double drift = 0;
  for (double w : Values(run, "wob_N")) drift = std::max(drift, std::abs(w - 90000));
  std::printf("[ measured ] weight on bit over 2 s of steady drilling with a 2e5 N s/m hoist dashpot: within %.3g N of "
              "90 kN\n", drift);
  EXPECT_LT(drift, 1e-3);

  nlohmann::json rig = doc;
  rig["model"]["hoist"]["rig"] = testing::LoadCase("hoist-rig")
                                     ["model"]["hoist"]["rig"];
  EXPECT_EQ(testing::RefusedPath(rig), "/model/hoist/damping_Ns_per_m");
}

// After a hook-force step the rate of penetration changes and the dashpot carries c_h (V - V0): the run settles at
// the steady state the linearization is taken about (its axial balance counts the dashpot), not at the plain one.
TEST(AxialTorsionalHoist, HoistDashpotShiftsTheSteadyStateAfterAHookForceStep) {
  nlohmann::json doc = HoistStep();
  const double c_h = 2e6;
  doc["model"]["hoist"]["damping_Ns_per_m"] = c_h;
  const Case c = ParseCase(doc);
  const auto points = c.model->Linearize();
  ASSERT_EQ(points.size(), 1u);
  const double linear_wob = points[0].steady_state.at("weight_on_bit_N");
  const AxialBalance plain(doc["model"]);
  const double omega = doc["model"]["top"]["speed_rad_s"];
  const double plain_wob = plain.WeightOnBit(doc["model"]["hoist"]["hook_force_N"]["knots"].back()[1], omega);
  const double wob_mean = RunCase(c).summary.at("wob_mean_N");
  std::printf("[ measured ] hook-force step with a %.0e N s/m hoist dashpot: weight on bit %.4f N over the last 20 s, "
              "the linearization's steady state %.4f N (without the dashpot's share %.4f N)\n", c_h, wob_mean,
              linear_wob, plain_wob);
  EXPECT_NEAR(wob_mean, linear_wob, 1e-5 * linear_wob);
  EXPECT_GT(std::abs(plain_wob - linear_wob), 100 * std::abs(wob_mean - linear_wob));
}

}  // namespace
}  // namespace drillwave::cases
