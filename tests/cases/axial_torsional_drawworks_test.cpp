// The drawworks of the hoisting rig (chapter eq. 2.37, model::Drawworks): an induction motor through a gear on the
// drum pays out the line. At its steady supply it pays out at the steady rate of penetration and the string drills as
// without it; a step in its supply makes it pay out faster, and the weight on bit rises until the bit drills as fast
// as the line is paid out — the steady state of that balance, solved here from the string's steady relations and
// the motor's equations, is where the run settles.
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/model/drawworks.hpp"
#include "json_case.hpp"
#include "refused_path.hpp"

namespace drillwave::cases {
namespace {

using testing::RefusedPath;

double Summary(const CaseRun& run, const std::string& key) { return run.summary[key].get<double>(); }

double Bisect(double lo, double hi, const std::function<double(double)>& f) {
  double flo = f(lo);
  for (int k = 0; k < 200 && hi - lo > 1e-13 * std::abs(hi); ++k) {
    const double mid = 0.5 * (lo + hi), fm = f(mid);
    if ((fm > 0) == (flo > 0)) lo = mid, flo = fm;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

double MeanOver(const CaseRun& run, const std::string& channel, double begin, double end) {
  const auto& t = run.result.time_s;
  const auto& v = run.result.channel(channel).values;
  double sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= begin && t[i] <= end) sum += v[i], ++n;
  return sum / n;
}

// Without a supply change the drawworks pays out at the steady rate of penetration: the run is steady drilling, as
// with the constant pay-out it replaces.
TEST(AxialTorsionalDrawworks, AtItsSteadySupplyTheStringDrillsAsWithAConstantPayOut) {
  nlohmann::json with = testing::LoadCase("hoist-drawworks");
  with["model"]["hoist"]["rig"]["drawworks"].erase("supply_change_Hz");
  with["simulation"]["duration_s"] = 20;
  with["statistics"]["window_s"] = {10, 20};
  nlohmann::json without = with;
  without["model"]["hoist"]["rig"].erase("drawworks");
  const CaseRun a = RunCase(ParseCase(with)), b = RunCase(ParseCase(without));
  const auto &wob_a = a.result.channel("wob_N").values, &wob_b = b.result.channel("wob_N").values;
  double largest = 0;
  for (std::size_t i = 0; i < wob_a.size(); ++i) largest = std::max(largest, std::abs(wob_a[i] - wob_b[i]));
  const double steady_rop = Summary(a, "steady_rop_m_h");
  double pay_out_off = 0;
  for (double p : a.result.channel("pay_out_m_h").values) pay_out_off = std::max(pay_out_off, std::abs(p - steady_rop));
  std::printf("[ measured ] drawworks at its steady supply %.6f Hz: weight on bit within %.3g N of the constant "
              "pay-out's, pay-out within %.3g m/h of %.4f\n",
              Summary(a, "drawworks_steady_supply_frequency_Hz"), largest, pay_out_off, steady_rop);
  EXPECT_LT(largest, 1e-6 * 90000);
  EXPECT_LT(pay_out_off, 1e-8 * steady_rop);
}

// The supply raised by 0.5 Hz at 10 s: the new steady weight on bit W solves rop(W) = r w_d(W), where the bit's rate
// of penetration is linear in its weight (the rock's cut: rop = (W - a sigma l) w / (2 pi K), read from the kind's
// steady state at two weights), the drum turns where the motor's steady torque holds the line's pull P(W) = B - W -
// D rop(W) (the buoyant weight less the weight on bit and the string's axial damping, read from the kind's hook force
// at two weights), n T_em(f0 + 0.5 Hz, n w_d) = -r P.
TEST(AxialTorsionalDrawworks, AFasterSupplyLoadsTheBitUntilItDrillsAsFastAsTheLineIsPaidOut) {
  const nlohmann::json doc = testing::LoadCase("hoist-drawworks");
  // The string's steady relations, without the drawworks, at two weights on bit.
  auto steady = [&](double wob) {
    nlohmann::json d = doc;
    d["model"]["hoist"]["rig"].erase("drawworks");
    d["model"]["hoist"]["weight_on_bit_N"] = wob;
    d["simulation"]["duration_s"] = 0.1;
    d["statistics"]["window_s"] = {0, 0.1};
    const CaseRun run = RunCase(ParseCase(d));
    return std::pair<double, double>{Summary(run, "steady_rop_m_h") / 3600, Summary(run, "hook_force_N")};
  };
  const double w1 = 90000, w2 = 95000;
  const auto [rop1, hook1] = steady(w1);
  const auto [rop2, hook2] = steady(w2);
  const double rop_per_wob = (rop2 - rop1) / (w2 - w1);
  // C++17 lambdas cannot capture a structured binding (clang refuses it): rop1 by an init-capture.
  auto rop = [&, rop_at_w1 = rop1](double wob) { return rop_at_w1 + rop_per_wob * (wob - w1); };
  // hook = B - W - D rop: two equations for B and D.
  const double damping = -((hook2 - hook1) + (w2 - w1)) / (rop2 - rop1), buoyant = hook1 + w1 + damping * rop1;
  const CaseRun run = RunCase(ParseCase(doc));
  const double f = Summary(run, "drawworks_steady_supply_frequency_Hz") + 0.5;
  const nlohmann::json& dw = doc["model"]["hoist"]["rig"]["drawworks"];
  const double r = dw["line_radius_m"], n = dw["gear_ratio"];
  model::InductionMotor motor;
  const nlohmann::json& m = dw["induction_motor"];
  motor.pole_pairs = m["pole_pairs"];
  motor.stator_resistance = m["stator_resistance_ohm"], motor.rotor_resistance = m["rotor_resistance_ohm"];
  motor.stator_leakage_inductance = m["stator_leakage_inductance_H"];
  motor.rotor_leakage_inductance = m["rotor_leakage_inductance_H"];
  motor.magnetizing_inductance = m["magnetizing_inductance_H"], motor.volts_per_hertz = m["volts_per_hertz_V_per_Hz"];
  // The pay-out where the motor holds the pull of weight W: the shaft speed between synchronous and pull-out.
  auto pay_out = [&](double wob) {
    const double pull = buoyant - wob - damping * rop(wob);
    const double synchronous = 2 * kPi * f / motor.pole_pairs;
    const double shaft = Bisect(synchronous, synchronous + motor.PullOutSlipFrequency() / motor.pole_pairs,
                                [&](double s) { return n * motor.Torque(motor.SteadyFluxes(f, s)) + r * pull; });
    return r * shaft / n;
  };
  const double wob = Bisect(w1, w2, [&](double w) { return pay_out(w) - rop(w); });
  const double simulated = MeanOver(run, "wob_N", 60, 80), simulated_rop = Summary(run, "rop_mean_m_h") / 3600;
  std::printf("[ measured ] supply +0.5 Hz: weight on bit %.3f N over 60-80 s against %.3f N solved (%.2g); rate of "
              "penetration %.4f m/h against %.4f; pay-out %.4f m/h\n",
              simulated, wob, (simulated - wob) / (wob - w1), 3600 * simulated_rop, 3600 * rop(wob),
              MeanOver(run, "pay_out_m_h", 60, 80));
  EXPECT_GT(wob - w1, 1000);                               // the bit is loaded by more than a kilonewton
  EXPECT_NEAR(simulated, wob, 1e-4 * (wob - w1));          // to 0.01 % of the rise
  EXPECT_NEAR(MeanOver(run, "pay_out_m_h", 60, 80) / 3600, pay_out(wob), 1e-3 * pay_out(wob));
}

TEST(AxialTorsionalDrawworks, BadInputIsRefusedByPath) {
  nlohmann::json doc = testing::LoadCase("hoist-drawworks");
  nlohmann::json no_radius = doc;
  no_radius["model"]["hoist"]["rig"]["drawworks"].erase("line_radius_m");
  EXPECT_EQ(RefusedPath(no_radius), "/model/hoist/rig/drawworks/line_radius_m");
  nlohmann::json weak = doc;  // a motor far too small to hold 517 kN on the line
  weak["model"]["hoist"]["rig"]["drawworks"]["induction_motor"]["volts_per_hertz_V_per_Hz"] = 0.5;
  EXPECT_EQ(RefusedPath(weak), "/model/hoist/rig/drawworks/induction_motor");
  nlohmann::json stray = doc;  // no field of a code it does not have
  stray["model"]["hoist"]["rig"]["drawworks"]["line_radius"] = 0.04;
  EXPECT_EQ(RefusedPath(stray), "/model/hoist/rig/drawworks/line_radius");
  EXPECT_EQ(RefusedPath(doc, true), "");  // linearized with its drum and motor (AxialTorsionalStability)
}

}  // namespace
}  // namespace drillwave::cases
