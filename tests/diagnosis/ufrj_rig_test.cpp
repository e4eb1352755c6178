// The UFRJ laboratory rig (json-cases/ufrj-rig-wob-input.json) against its recording (../shared; skipped where absent): the
// case was fitted on 2-20 s, and is judged here on the held-out 20-30 s by the features of the brief (stick fraction,
// stick-slip period, bit speed mean and max, torque on bit mean and std), against the start values kept in its notes.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/diagnosis/comparison.hpp"
#include "drillwave/diagnosis/loop.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::diagnosis {
namespace {

const char* const kFeatures[] = {"stick_fraction", "stick_slip_period_s", "bit_speed_mean",
                                 "bit_speed_max",  "tob_Nm mean",         "tob_Nm std"};

// The start values of the fitted parameters, as the case's notes list them (estimated from 0-20 s of the recording).
const std::pair<const char*, double> kStartValues[] = {{"/model/bit/inertia_kgm2", 0.0026},
                                                       {"/model/bit/friction/mu_s", 0.509},
                                                       {"/model/bit/friction/nu_f_rad_s", 23.2},
                                                       {"/model/top/kp_Nms_per_rad", 0.22}};

// Root mean square of the relative differences of kFeatures over [begin, end] s (a missing or undefined feature, such
// as a stick-slip period without sticking, counts as 100 %).
double FeatureError(const nlohmann::json& doc, const Recording& rec, double begin, double end, const char* label) {
  const auto model = cases::RunCase(cases::ParseCase(doc)).result;
  const Comparison c = Compare(rec, model, {{"bit_rpm", "bit_rpm", 1}, {"top_rpm", "top_rpm", 1},
                                            {"tob_Nm", "bit_torque_Nm", 1}},
                               begin, end);
  double sum = 0;
  for (const char* name : kFeatures) {
    double rel = 1;
    for (const FeatureDifference& d : c.features)
      if (d.feature == name && std::isfinite(d.relative)) rel = d.relative;
    std::printf("[ measured ] %s [%g, %g] s %s: %+.1f %%\n", label, begin, end, name, 100 * rel);
    sum += rel * rel;
  }
  const double error = std::sqrt(sum / std::size(kFeatures));
  std::printf("[ measured ] %s [%g, %g] s: feature error (rms of the relative differences) %.1f %%\n", label, begin,
              end, 100 * error);
  return error;
}

TEST(UfrjRig, FittedCasePredictsTheHeldOutFeaturesBetterThanItsStart) {
  const std::string file = std::string(DRILLWAVE_SHARED_DIR) + "/recordings/ufrj-rig/rig-0-30s.csv";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "the laboratory recording is not at " << file;
  const Recording rec = LoadRecording(file);
  const nlohmann::json fitted = testing::LoadCase("ufrj-rig-wob-input");
  nlohmann::json start = fitted;
  for (const auto& [pointer, value] : kStartValues) start[nlohmann::json::json_pointer(pointer)] = value;
  ASSERT_NE(start, fitted);
  const double before = FeatureError(start, rec, 20, 30, "start");
  const double after = FeatureError(fitted, rec, 20, 30, "fitted");
  // Measured: start 32.2 %, fitted 24.9 % (gcc, Release; the weight on bit after 20 s held at its fit-window mean);
  // the bound leaves room for another compiler's rounding.
  EXPECT_LT(after, before);
  EXPECT_LT(after, 0.27);
}

// The loop from the user's start (json-cases/ufrj-rig.json: the droop drive and the calibrated period the recording's
// first 20 s show, Coulomb friction): fitted on 2-20 s, held out 20-30 s, it must add the velocity weakening the rig's
// torque on bit shows and predict the held-out part far better. Measured: stribeck + soft_topdrive + bit_inertia kept,
// held-out error 30.9 -> 5.51 (with pairs, f9ff18c); with every effect screened and the soft drive a droop drive on its
// motor's inertia (no integral), the same three, 20.5 -> 3.51; with the friction's slope and the drive's droop among
// the features and the droop as the drive's start, stribeck + soft_topdrive, 38.2 -> 8.31 (the CLI's README command,
// without the torque-to-bit lag: 34 -> 1.1); from the base with the droop drive and the shaft's period calibrated, the
// friction falling linearly with speed (linear_weakening; the CLI's README command: 34 -> 0.446, the torque limit and
// the normal load fitted beside it and refused); the shaft's period then calibrated beside it as a base parameter
// (CalibrateBesideTheKept: fit window 3.34 -> 2.80, held out 0.98 -> 0.806, period 0.351 -> 0.360 s).
LoopOptions RigLoopOptions() {
  LoopOptions o;
  o.maps = {{"top_rpm", "top_rpm", 1}, {"bit_rpm", "bit_rpm", 1}, {"tob_Nm", "bit_torque_Nm", 1}};
  o.fit_begin_s = 2, o.fit_end_s = 20, o.held_out_begin_s = 20, o.held_out_end_s = 30;
  o.features.top_torque = "tob_Nm";
  o.threads = 2;
  return o;
}

std::string KeptNames(const DiagnosisLoop& loop) {
  std::string names;
  if (loop.kept >= 0)
    for (const std::string& e : loop.candidates[loop.kept].effects) names += e + " ";
  return names;
}

TEST(UfrjRig, TheLoopAddsTheLinearVelocityWeakeningAndPredictsTheHeldOutPart) {
  const std::string file = std::string(DRILLWAVE_SHARED_DIR) + "/recordings/ufrj-rig/rig-0-30s.csv";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "the laboratory recording is not at " << file;
  const Recording rec = LoadRecording(file);
  const DiagnosisLoop loop = RunDiagnosisLoop(
      testing::LoadCase("ufrj-rig"), rec, RigLoopOptions());
  ASSERT_GE(loop.kept, 0) << "nothing kept";
  const std::vector<std::string>& kept = loop.candidates[loop.kept].effects;
  const std::string names = KeptNames(loop);
  std::printf("[ measured ] ufrj-rig loop: kept %s; held-out error %.3g -> %.3g; masked top_rpm samples %d\n",
              names.c_str(), loop.baseline_held_out_error, loop.fitted_held_out_error, loop.masked_samples[0].second);
  EXPECT_NE(std::find(kept.begin(), kept.end(), "linear_weakening"), kept.end()) << names;
  EXPECT_LT(loop.fitted_held_out_error, 0.3 * loop.baseline_held_out_error);
  // The fitted model keeps sticking and slipping with the recording's period (0.378 s on 20-30 s) within 5 % (issue
  // 32; the friction alone fitted 0.351 s, -7.1 %).
  const double period = loop.fitted_held_out.Value("period_s");
  std::printf("[ measured ] ufrj-rig loop: held-out period %.3f s, stick fraction %.3f\n", period,
              loop.fitted_held_out.Value("stick_fraction"));
  EXPECT_NEAR(period, 0.378, 0.05 * 0.378);
  EXPECT_GT(loop.fitted_held_out.Value("stick_fraction"), 0.05);
  EXPECT_GT(loop.masked_samples[0].second, 0);  // the encoder's spikes in top_rpm are masked, not modelled
}

}  // namespace
}  // namespace drillwave::diagnosis
