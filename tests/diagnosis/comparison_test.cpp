// Model against recording: a simulation compared with its own written trajectory agrees exactly; a model with other
// friction shows the difference in the features that friction sets; channel maps parse or say why not.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/diagnosis/comparison.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::diagnosis {
namespace {

namespace fs = std::filesystem;

nlohmann::json Saldivar() {
  nlohmann::json doc = testing::LoadCase("saldivar-stickslip");
  doc["simulation"]["duration_s"] = 40;
  doc["simulation"]["output_interval_s"] = 0.01;
  doc["statistics"]["window_s"] = {20, 40};
  return doc;
}

// The case's trajectory written by the runner and read back as a recording.
Recording AsRecording(const nlohmann::json& doc, const fs::path& dir) {
  const cases::Case c = cases::ParseCase(doc);
  cases::WriteCaseOutputs(c, cases::RunCase(c), dir.string());
  return LoadRecording((dir / "trajectory.csv").string());
}

TEST(Comparison, AModelAgreesWithItsOwnTrajectory) {
  const fs::path dir = fs::temp_directory_path() / ("drillwave-compare-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const nlohmann::json doc = Saldivar();
  const Recording rec = AsRecording(doc, dir);
  const cases::RunResult model = cases::RunCase(cases::ParseCase(doc)).result;
  InspectOptions clean;
  clean.mask_artefacts = false;
  const Comparison c = Compare(rec, model, {{"bit_rpm", "bit_rpm", 1}, {"top_rpm", "top_rpm", 1},
                                            {"bit_torque_Nm", "bit_torque_Nm", 1}}, 20, 40, clean);
  // The CSV holds 10 significant digits.
  for (const ChannelResidual& r : c.residuals) EXPECT_LT(r.rms, 1e-6 * (1 + r.recording_std)) << r.channel;
  for (const FeatureDifference& d : c.features)
    if (std::isfinite(d.relative)) {
      EXPECT_LT(std::abs(d.relative), 1e-6) << d.feature;
    }
  ASSERT_EQ(c.findings.size(), 1u);
  EXPECT_EQ(c.findings[0], "no feature differs by more than 10 %.");
  fs::remove_all(dir);
}

TEST(Comparison, OtherFrictionShowsInTheFeaturesFrictionSets) {
  const fs::path dir = fs::temp_directory_path() / ("drillwave-compare2-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  nlohmann::json truth = Saldivar();
  const Recording rec = AsRecording(truth, dir);
  nlohmann::json wrong = truth;
  wrong["model"]["bit"]["friction"]["mu_s"] = 0.65;  // much less velocity weakening than the "recording"
  const Comparison c = Compare(rec, cases::RunCase(cases::ParseCase(wrong)).result,
                               {{"bit_rpm", "bit_rpm", 1}, {"top_rpm", "top_rpm", 1}}, 20, 40);
  double stick = 0;
  for (const FeatureDifference& d : c.features)
    if (d.feature == "stick_fraction") stick = d.relative;
  std::printf("[ measured ] mu_s 0.8 -> 0.65: stick fraction %+.0f %%; first finding: %s\n", 100 * stick,
              c.findings.front().c_str());
  EXPECT_LT(stick, -0.3);  // the model sticks far less
  bool named = false;
  for (const std::string& f : c.findings) named |= f.find("static and kinetic levels") != std::string::npos;
  EXPECT_TRUE(named);
  fs::remove_all(dir);
}

TEST(Comparison, ChannelMapsParseOrSayWhy) {
  const ChannelMap m = ParseChannelMap("wob_kN=weight_on_bit_N*0.001");
  EXPECT_EQ(m.recording, "wob_kN");
  EXPECT_EQ(m.model, "weight_on_bit_N");
  EXPECT_DOUBLE_EQ(m.scale, 0.001);
  for (const char* bad : {"tob_Nm", "=x", "x=", "a=b*", "a=b*zero", "a=b*0"})
    EXPECT_THROW(ParseChannelMap(bad), InputError) << bad;
}

}  // namespace
}  // namespace drillwave::diagnosis
