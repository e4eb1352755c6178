// diagnosis/loop_report: the report's plot says where the fit window and the held-out window lie, and its axes name
// the quantity and unit of each channel; it draws masked samples apart from the recording's line and zooms on the
// held-out window's last stick-slip cycles.
#include "drillwave/diagnosis/loop_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "svg_points.hpp"

namespace drillwave::diagnosis {
namespace {

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

using drillwave::testing::PolylinePoints;

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

// The loop masks a spike of the recorded bit speed as an artefact: the figure draws it as a dot of its own, not as a
// point of the recording's line.
TEST(LoopReport, AMaskedSpikeIsADotApartFromTheRecordingsLine) {
  Recording recording = Sine("rig.csv");
  recording.channels[0][100] = 400;  // at 10 s, the bit speed otherwise within 40 .. 80 rpm
  DiagnosisLoop loop;
  loop.baseline_model = Sine("model");
  loop.recording_fit.begin_s = 2, loop.recording_fit.end_s = 20;
  loop.recording_held_out.begin_s = 20, loop.recording_held_out.end_s = 30;
  const io::Figure figure = DiagnosisFigure(loop, recording);
  ASSERT_FALSE(figure.panels.empty());
  const std::vector<io::Series>& bit = figure.panels[0].series;
  ASSERT_EQ(bit[0].label, "recording");
  EXPECT_EQ(std::count(bit[0].y.begin(), bit[0].y.end(), 400.0), 0);
  EXPECT_TRUE(std::isnan(bit[0].y[100]));  // the line breaks there
  const auto dots = std::find_if(bit.begin(), bit.end(), [](const io::Series& s) { return s.mark == io::Mark::kDots; });
  ASSERT_NE(dots, bit.end());
  EXPECT_EQ(dots->label.rfind("masked (artefact)", 0), 0u) << dots->label;
  EXPECT_EQ(dots->x, std::vector<double>{recording.time_s[100]});
  EXPECT_EQ(dots->y, std::vector<double>{400});
  ASSERT_GE(figure.panels.size(), 2u);
  EXPECT_EQ(figure.panels[1].series.size(), 2u);  // the torque on bit: recording and baseline, nothing masked

  // In the picture, no point of a line is where the spike's dot is.
  std::ostringstream html;
  WriteLoopHtml(loop, recording, html);
  const std::string page = html.str();
  const std::size_t dot = page.find("<circle", page.find("<g class=\"dots\""));
  ASSERT_NE(dot, std::string::npos);
  const double spike_y = std::strtod(page.c_str() + page.find("cy=\"", dot) + 4, nullptr);
  for (const auto& [x, y] : PolylinePoints(page)) EXPECT_GT(std::abs(y - spike_y), 1.0) << x;
}

// Below the channels, the bit speed's last few stick-slip cycles of the held-out window, on a time axis of their own.
TEST(LoopReport, TheHeldOutWindowsLastStickSlipCyclesAreZoomed) {
  const Recording recording = Sine("rig.csv");
  DiagnosisLoop loop;
  loop.baseline_model = Sine("model");
  loop.recording_fit.begin_s = 2, loop.recording_fit.end_s = 20;
  loop.recording_held_out.begin_s = 20, loop.recording_held_out.end_s = 30;
  loop.recording_held_out.features = {{"period_s", 2.0, 0.1}};
  const io::Figure figure = DiagnosisFigure(loop, recording);
  ASSERT_EQ(figure.panels.size(), 3u);  // bit speed, torque on bit, the zoom
  const io::Panel& zoom = figure.panels.back();
  EXPECT_EQ(zoom.y_label, "bit speed [rpm]");
  EXPECT_EQ(zoom.x_label.rfind("recording time [s]", 0), 0u) << zoom.x_label;
  ASSERT_GE(zoom.series.size(), 2u);  // the recording and the baseline
  for (const io::Series& s : zoom.series) {
    ASSERT_FALSE(s.x.empty()) << s.label;
    EXPECT_NEAR(s.x.front(), 30 - 4 * 2.0, 0.11) << s.label;  // four periods ...
    EXPECT_NEAR(s.x.back(), 30, 0.11) << s.label;             // ... ending with the held-out window
  }
  EXPECT_TRUE(figure.panels[0].x_label.empty());  // the channels keep the shared axis

  // Without a period: a typical one's (5 s) cycles, within the held-out window.
  loop.recording_held_out.features.clear();
  EXPECT_NEAR(DiagnosisFigure(loop, recording).panels.back().series[0].x.front(), 20, 0.11);
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
