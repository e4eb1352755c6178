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

}  // namespace
}  // namespace drillwave::diagnosis
