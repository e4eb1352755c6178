// diagnosis/loop_report: the report's plot says where the fit window and the held-out window lie, and its axes name
// the quantity and unit of each channel.
#include "drillwave/diagnosis/loop_report.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace drillwave::diagnosis {
namespace {

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

Recording Sine(const std::string& source) {
  Recording r;
  r.source = source;
  r.names = {"bit_rpm", "tob_Nm"};
  r.channels.resize(2);
  for (int i = 0; i <= 300; ++i) {
    r.time_s.push_back(0.1 * i);
    r.channels[0].push_back(60 + 20 * std::sin(0.1 * i));
    r.channels[1].push_back(1 + 0.2 * std::cos(0.1 * i));
  }
  r.sample_interval_s = 0.1;
  return r;
}

TEST(LoopReport, ThePlotMarksTheFitAndHeldOutWindowsAndNamesItsUnits) {
  const Recording recording = Sine("rig.csv");
  DiagnosisLoop loop;
  loop.baseline_model = Sine("model");
  loop.recording_fit.begin_s = 2, loop.recording_fit.end_s = 20;
  loop.recording_held_out.begin_s = 20, loop.recording_held_out.end_s = 30;
  std::ostringstream html;
  WriteLoopHtml(loop, recording, html);
  const std::string page = html.str();
  EXPECT_EQ(Count(page, "<rect class=\"span\""), 4u);  // two windows in each of the two channels' panels
  EXPECT_EQ(Count(page, ">fit window<"), 1u);
  EXPECT_EQ(Count(page, ">held out<"), 1u);
  EXPECT_NE(page.find(">bit speed [rpm]<"), std::string::npos);
  EXPECT_NE(page.find(">torque on bit [N m]<"), std::string::npos);
}

// Akaike weights: the baseline and each set once (by its lowest AIC), failed fits left out, summing to one.
TEST(LoopReport, ModelProbabilitiesAreTheAkaikeWeightsOfEachSetOnce) {
  DiagnosisLoop loop;
  loop.baseline_aic = 10;
  auto candidate = [](std::vector<std::string> effects, double aic, std::string failure = "") {
    Candidate c;
    c.effects = std::move(effects), c.aic = aic, c.failure = std::move(failure);
    return c;
  };
  loop.candidates = {candidate({"a"}, 6), candidate({"b"}, 12), candidate({"a"}, 5), candidate({"c"}, -50, "failed"),
                     candidate({"b", "a"}, 7)};
  const std::vector<ModelProbability> m = AkaikeWeights(loop);
  ASSERT_EQ(m.size(), 4u);  // baseline, a, b, a + b
  const double total = std::exp(-2.5) + 1 + std::exp(-3.5) + std::exp(-1.0);
  EXPECT_EQ(m[0].effects, std::vector<std::string>{"a"});
  EXPECT_DOUBLE_EQ(m[0].aic, 5);
  EXPECT_NEAR(m[0].weight, 1 / total, 1e-12);
  EXPECT_EQ(m[1].effects, (std::vector<std::string>{"a", "b"}));
  EXPECT_NEAR(m[1].weight, std::exp(-1.0) / total, 1e-12);
  EXPECT_TRUE(m[2].effects.empty());  // the baseline
  EXPECT_NEAR(m[2].weight, std::exp(-2.5) / total, 1e-12);
  EXPECT_NEAR(m[3].weight, std::exp(-3.5) / total, 1e-12);
}

}  // namespace
}  // namespace drillwave::diagnosis
