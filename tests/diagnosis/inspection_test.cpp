// diagnosis/inspection: the inspection's figure draws the samples it masked as artefacts apart from the recorded
// lines, and zooms on the recording's last few stick-slip cycles.
#include "drillwave/diagnosis/inspection.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace drillwave::diagnosis {
namespace {

// 30 s of stick-slip with a 2-s period (stuck for 0.6 s, then a slip hump to 120 rpm) under a steady top speed, at
// 100 Hz, with an encoder spike in each speed.
Recording StickSlip() {
  Recording r;
  r.source = "stick-slip.csv";
  r.names = {"bit_rpm", "top_rpm"};
  r.channels.resize(2);
  const double pi = std::acos(-1.0);
  for (int i = 0; i <= 3000; ++i) {
    const double t = 0.01 * i, phase = std::fmod(t, 2.0);
    r.time_s.push_back(t);
    r.channels[0].push_back(phase < 0.6 ? 0.0 : 120 * std::sin(pi * (phase - 0.6) / 1.4));
    r.channels[1].push_back(60 + 0.5 * std::sin(7 * t));
  }
  r.channels[0][2530] = 900;  // at 25.3 s, while the bit slips
  r.channels[1][1000] = 300;  // at 10 s
  r.sample_interval_s = 0.01;
  return r;
}

const io::Series* Dots(const io::Panel& panel) {
  for (const io::Series& s : panel.series)
    if (s.mark == io::Mark::kDots) return &s;
  return nullptr;
}

TEST(InspectionFigure, MaskedSpikesAreDotsApartFromTheRecordedLines) {
  const Recording rec = StickSlip();
  const Inspection ins = InspectRecording(rec);
  const io::Figure figure = InspectionFigure(rec, ins);
  ASSERT_GE(figure.panels.size(), 2u);
  for (std::size_t j = 0; j < 2; ++j) {  // the bit speed, then the top speed
    const io::Panel& panel = figure.panels[j];
    const double spike = j == 0 ? 900 : 300;
    for (const io::Series& s : panel.series) {
      if (s.mark != io::Mark::kLine) continue;
      EXPECT_EQ(std::count(s.y.begin(), s.y.end(), spike), 0) << s.label;
    }
    const io::Series* dots = Dots(panel);
    ASSERT_NE(dots, nullptr) << panel.y_label;
    EXPECT_EQ(dots->label.rfind("masked (artefact)", 0), 0u) << dots->label;
    EXPECT_EQ(std::count(dots->y.begin(), dots->y.end(), spike), 1) << panel.y_label;
    EXPECT_EQ(dots->x.size(), static_cast<std::size_t>(ins.artefacts[j].samples_flagged));
  }
}

TEST(InspectionFigure, TheRecordingsLastStickSlipCyclesAreZoomed) {
  const Recording rec = StickSlip();
  const Inspection ins = InspectRecording(rec);
  ASSERT_NEAR(ins.stick_slip_period_s, 2.0, 0.02);
  const io::Figure figure = InspectionFigure(rec, ins);
  const io::Panel& zoom = figure.panels.back();
  EXPECT_EQ(zoom.y_label, "bit speed [rpm]");
  EXPECT_EQ(zoom.x_label.rfind("time [s]", 0), 0u) << zoom.x_label;
  ASSERT_FALSE(zoom.series.empty());
  const std::vector<double>& t = zoom.series[0].x;
  ASSERT_FALSE(t.empty());
  EXPECT_NEAR(t.back(), 30, 1e-9);
  const double periods = (t.back() - t.front()) / ins.stick_slip_period_s;
  EXPECT_GE(periods, 3);
  EXPECT_LE(periods, 4.05);
  const io::Series* dots = Dots(zoom);  // the spike at 25.3 s lies within the zoom
  ASSERT_NE(dots, nullptr);
  EXPECT_EQ(std::count(dots->x.begin(), dots->x.end(), rec.time_s[2530]), 1);
}

}  // namespace
}  // namespace drillwave::diagnosis
