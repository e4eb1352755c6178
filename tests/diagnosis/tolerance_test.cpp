// The diagnosis compares statistics of the motion (features.hpp), so its objective must not move with the
// integrator's tolerance even where the trajectory does (stick-slip is chaotic: runs at two tolerances part within a
// few periods). This is what lets the fits run at a looser tolerance than the case's (LoopOptions::fit_tolerance):
// the baseline's held-out errors at tolerances 1e-6, 1e-5 and 1e-4 (the default fit tolerance) scatter by less than
// chance moves that error (sqrt(2 / K) over K features): a change of tolerance acts as another draw of the same
// physics. Measured on rec03 (no effect) with the former 5 % start bump: 0.2535 / 0.2537 / 0.2516, and within 0.004
// over eight tolerances from 1e-6 to 1e-4; from the sidecar's steady start over a 10 um bottom roughness 0.3798 /
// 0.3841 / 0.2321 (standard deviation 0.087, chance 0.289).
// Where the physics draws from two patterns the claim does not hold, and the recording is not tested here: rec10
// (Kelvin-Voigt concealed) is bimodal, held-out error about 0.65 or about 2.0 whatever the tolerance. With the engine
// of f3fb4fb: 0.72, 0.65, 2.21, 0.70, 0.61, 0.56, 2.37, 0.67 at 1e-6, 2e-6, 5e-6, 1e-5, 2e-5, 5e-5, 7e-5, 1e-4 (this
// test passed on the three it sampled); since kinks are followed through the sub-sections: 0.68, 0.73, 2.05, 1.12,
// 2.14, 2.04, 0.63, 1.98. rec12 (DC motor) scatters from 0.9 to 66. Since stop 25 the loop judges the median of
// three draws (LoopOptions::draws): rec03 reads 0.3791 / 0.3786 / 0.3562 at 1e-6 / 1e-5 / 1e-4 (standard deviation
// 0.013, against 0.087 from one draw).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/diagnosis/comparison.hpp"
#include "drillwave/diagnosis/loop.hpp"
#include "drillwave/diagnosis/recording.hpp"
#include "drillwave/diagnosis/sidecar.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::diagnosis {
namespace {

namespace fs = std::filesystem;
const fs::path kSynthetic = fs::path(DRILLWAVE_SHARED_DIR) / "recordings" / "synthetic";

class ToleranceIndependence : public ::testing::TestWithParam<std::string> {};

TEST_P(ToleranceIndependence, TheHeldOutErrorDoesNotMoveWithTheTolerance) {
  const std::string name = GetParam();
  if (!fs::exists(kSynthetic / (name + ".csv")))
    GTEST_SKIP() << "the synthetic recordings are not at " << kSynthetic;
  const Recording recording = LoadRecording((kSynthetic / (name + ".csv")).string());
  const nlohmann::json baseline =
      CaseFromSidecar(io::LoadJsonFile((kSynthetic / (name + ".json")).string()),
                      testing::LoadCase("baseline-60rpm"),
                      kSidecarWarmupS);
  std::vector<double> errors;
  double chance = 0;
  for (const double tolerance : {1e-6, 1e-5, 1e-4}) {
    nlohmann::json doc = baseline;
    doc["simulation"]["rel_tol"] = doc["simulation"]["abs_tol"] = tolerance;
    const cases::Case c = cases::ParseCase(doc);
    LoopOptions o = DefaultLoopOptions(c, recording, kSidecarWarmupS);
    o.max_singles = 0;  // the baseline's errors only
    o.measure_regime_margin = false;
    o.maps = ResolveChannelMaps({}, recording, ProbeChannels(c));
    const DiagnosisLoop loop = RunDiagnosisLoop(doc, recording, o);
    errors.push_back(loop.baseline_held_out_error);
    chance = loop.error_chance;
    std::printf("[ measured ] %s at tolerance %g: held-out error %.4f (fit window %.4f)\n", name.c_str(), tolerance,
                loop.baseline_held_out_error, loop.baseline_fit_error);
  }
  double mean = 0, variance = 0;
  for (double e : errors) mean += e / errors.size();
  for (double e : errors) variance += (e - mean) * (e - mean) / (errors.size() - 1);
  std::printf("[ measured ] %s: held-out errors scatter by %.4f (standard deviation), chance %.4f\n", name.c_str(),
              std::sqrt(variance), chance);
  EXPECT_LT(std::sqrt(variance), chance);
}

// rec03 has no concealed effect (as the KEY says; only the test's choice of recordings knows it).
INSTANTIATE_TEST_SUITE_P(Recordings, ToleranceIndependence, ::testing::Values("rec03"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace drillwave::diagnosis
