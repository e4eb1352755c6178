// The two-mass hoisting rig of the axial_torsional kind (chapter eq. 2.22, model::HoistRig; its frequencies are
// checked with the string removed in tests/model/hoist_rig_test.cpp): steady drilling is kept as it is without the
// rig, a cable-tension step relieves the bit by the string's stretch and the constant pay-out restores it, and the
// hook load rings at the rig's frequencies.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "refused_path.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

nlohmann::json RigCase() {
  nlohmann::json doc = testing::LoadCase("hoist-rig");
  doc.erase("expect");
  return doc;
}
const std::vector<double>& Values(const CaseRun& run, const std::string& name) { return run.result.channel(name).values; }

using testing::RefusedPath;

// Without a tension change the rig stays at rest in steady drilling: the weight on bit and the hook load are those of
// the run without the rig.
TEST(AxialTorsionalRig, SteadyDrillingIsKept) {
  nlohmann::json with = RigCase();
  with["model"]["hoist"]["rig"].erase("cable_tension_change_N");
  with["simulation"]["duration_s"] = 10;
  with["statistics"]["window_s"] = {5, 10};
  nlohmann::json without = with;
  without["model"]["hoist"].erase("rig");
  const CaseRun a = RunCase(ParseCase(with)), b = RunCase(ParseCase(without));
  const auto &wob_a = Values(a, "wob_N"), &wob_b = Values(b, "wob_N");
  const auto &hook_a = Values(a, "hookload_N"), &hook_b = Values(b, "hookload_N");
  double wob_diff = 0, hook_diff = 0;
  for (std::size_t i = 0; i < wob_a.size(); ++i)
    wob_diff = std::max(wob_diff, std::abs(wob_a[i] - wob_b[i])), hook_diff = std::max(hook_diff, std::abs(hook_a[i] - hook_b[i]));
  std::printf("[ measured ] rig on, no tension change: largest weight-on-bit difference %.3g N, hook load %.3g N\n",
              wob_diff, hook_diff);
  EXPECT_LT(wob_diff, 1e-6 * 90000);
  EXPECT_LT(hook_diff, 1e-6 * a.summary["hook_force_N"].get<double>());
  EXPECT_NEAR(a.summary["wob_mean_N"].get<double>(), 90000, 1e-6 * 90000);
}

// A lasting tension change du lifts the derrick by du / k01 and with it the block and the top of the string: the rig
// rings, and the string's pull at the top (the hook load) swings by its impedance times the top's speed. That wave
// relieves the bit one axial travel time later, by less than twice its size (a wave doubles at a rigid end; the
// cutting holds the bit nearly so); the pay-out at the steady rate then brings the weight on bit back.
TEST(AxialTorsionalRig, TensionStepRelievesTheBitForAWhile) {
  const nlohmann::json doc = RigCase();
  const CaseRun run = RunCase(ParseCase(doc));
  const auto& t = run.result.time_s;
  const auto &wob = Values(run, "wob_N"), &hook = Values(run, "hookload_N");
  const double travel = doc["model"]["string"]["length_m"].get<double>() /
                        std::sqrt(doc["model"]["string"]["youngs_modulus_Pa"].get<double>() /
                                  doc["model"]["string"]["density_kg_m3"].get<double>());
  double lowest = 1e300, swing = 0, before = 0, wob_before = 0, first_change = -1;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] <= 5) before = hook[i], wob_before = wob[i];
    if (t[i] > 5 && t[i] < 5 + travel) swing = std::max(swing, std::abs(hook[i] - before));
    if (t[i] > 5 && t[i] < 20) lowest = std::min(lowest, wob[i]);
    if (t[i] > 5 && first_change < 0 && std::abs(wob[i] - wob_before) > 100) first_change = t[i];
  }
  const double dip = wob_before - lowest;
  std::printf("[ measured ] tension step 1 MN: hook load swings by %.1f N before the wave reaches the bit (%.4f s), the "
              "weight on bit dips by %.1f N from %.3f s on; mean over [30, 60] s %.3f N\n",
              swing, travel, dip, first_change, run.summary["wob_mean_N"].get<double>());
  EXPECT_GT(first_change, 5 + travel);
  EXPECT_GT(dip, 0.5 * swing);
  EXPECT_LT(dip, 2 * swing);
  EXPECT_NEAR(run.summary["wob_mean_N"].get<double>(), 90000, 1e-4 * 90000);
}

TEST(AxialTorsionalRig, BadInputNamesTheField) {
  nlohmann::json doc = RigCase();
  doc["model"]["hoist"]["rig"]["derrick_mass_kg"] = 0;
  EXPECT_EQ(RefusedPath(doc), "/model/hoist/rig/derrick_mass_kg");
  doc = RigCase();
  doc["model"]["hoist"]["rig"]["cable_stifness_N_per_m"] = 1e7;
  EXPECT_EQ(RefusedPath(doc), "/model/hoist/rig/cable_stifness_N_per_m");
  doc = RigCase();
  doc["model"]["hoist"].erase("weight_on_bit_N");
  doc["model"]["hoist"]["hook_force_N"] = 517004.154;
  EXPECT_EQ(RefusedPath(doc), "/model/hoist/rig");
  doc = RigCase();
  doc["model"]["axial_coupling"] = false;
  EXPECT_EQ(RefusedPath(doc), "/model/hoist/rig");
  EXPECT_EQ(RefusedPath(RigCase(), true), "");  // the stability analysis linearizes the rig
}

}  // namespace
}  // namespace drillwave::cases
