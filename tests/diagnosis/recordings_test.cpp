// The inspection on the recordings in ../shared (skipped, saying why, where they are absent): what the README of
// the real laboratory recording says a careful tool must notice by itself, and, on the synthetic set, whether the
// soft-drive finding matches the concealed effects (KEY.json is read here to score, never by the tool).
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "drillwave/diagnosis/inspection.hpp"
#include "drillwave/io/json_reader.hpp"

namespace drillwave::diagnosis {
namespace {

const std::string kShared = DRILLWAVE_SHARED_DIR;

TEST(RigRecording, TheInspectionFindsWhatACarefulReaderShould) {
  const std::string file = kShared + "/recordings/ufrj-rig/rig-0-30s.csv";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "the laboratory recording is not at " << file;
  const Recording rec = LoadRecording(file);
  const Inspection ins = InspectRecording(rec);
  for (const std::string& f : ins.findings) std::printf("[ measured ] %s\n", f.c_str());
  // Encoder artefacts in the top speed: spikes to about -260 rpm, masked; the bit channel is clean.
  const ChannelArtefacts& top = ins.artefacts[0];
  ASSERT_EQ(top.channel, "top_rpm");
  EXPECT_LT(top.raw_min, -200);
  EXPECT_GT(top.clean_min, -50);
  EXPECT_GE(top.bursts.size(), 10u);
  EXPECT_GT(top.bursts_while_stuck, 0);
  EXPECT_EQ(ins.artefacts[1].samples_flagged, 0) << "bit_rpm has no artefacts";
  // The top speed is far from constant: the drive is not stiff.
  EXPECT_TRUE(ins.top_drive_soft);
  // Whole stuck episodes, the longest near 28-30 s; a stretch without full sticking around 7-12 s.
  double longest = 0, longest_begin = 0;
  for (const Interval& s : ins.stuck)
    if (s.duration() > longest) longest = s.duration(), longest_begin = s.begin_s;
  EXPECT_GT(longest, 1.0);
  EXPECT_GT(longest_begin, 27.5);
  EXPECT_LT(longest_begin, 29.0);
  bool stretch = false;
  for (const Interval& s : ins.slip_without_stick) stretch |= s.begin_s < 8.0 && s.end_s > 11.5;
  EXPECT_TRUE(stretch) << "no stretch without sticking found around 7-12 s";
  // Torque on bit and weight on bit oscillate together.
  bool tob_wob = false;
  for (const ChannelPair& p : ins.correlations)
    if ((p.a == "tob_Nm" && p.b == "wob_N") || (p.a == "wob_N" && p.b == "tob_Nm")) tob_wob = p.correlation > 0.5;
  EXPECT_TRUE(tob_wob);
  // The stick-slip oscillation of the bit: about 0.37 s.
  EXPECT_NEAR(ins.bit_oscillation_period_s, 0.37, 0.03);
}

TEST(SyntheticRecordings, SoftDriveFindingMatchesTheConcealedEffect) {
  const std::string dir = kShared + "/recordings/synthetic";
  if (!std::filesystem::exists(dir + "/KEY.json")) GTEST_SKIP() << "the synthetic recordings are not at " << dir;
  const nlohmann::json key = io::LoadJsonFile(dir + "/KEY.json");
  int checked = 0;
  for (const auto& entry : key.at("recordings")) {
    const std::string file = dir + "/" + entry.at("file").get<std::string>();
    const Inspection ins = InspectRecording(LoadRecording(file));
    const bool soft = entry.at("effects").contains("soft_topdrive");
    std::printf("[ measured ] %s: top-speed fluctuation ratio %.1f, soft drive %s (concealed: %s)\n",
                entry.at("file").get<std::string>().c_str(), ins.top_speed_fluctuation_ratio,
                ins.top_drive_soft ? "yes" : "no", soft ? "yes" : "no");
    EXPECT_EQ(ins.top_drive_soft, soft) << file;
    ++checked;
  }
  EXPECT_EQ(checked, 12);
}

TEST(SyntheticRecordings, OnlyTheBouncingBitsWeightOnBitIsLeftWhole) {
  // rec04's bit bounces: its weight-on-bit impacts are as short as glitches and recur at every bounce, so more than
  // kMaxArtefactShare of the samples are flagged and the inspection leaves the channel whole, as diagnose does.
  const std::string dir = kShared + "/recordings/synthetic";
  if (!std::filesystem::exists(dir + "/rec12.csv")) GTEST_SKIP() << "the synthetic recordings are not at " << dir;
  for (int k = 1; k <= 12; ++k) {
    const std::string name = (k < 10 ? "rec0" : "rec") + std::to_string(k);
    const Inspection ins = InspectRecording(LoadRecording(dir + "/" + name + ".csv"));
    for (const ChannelArtefacts& a : ins.artefacts) {
      const bool bounce = name == "rec04" && a.channel == "wob_kN";
      EXPECT_EQ(a.left_whole, bounce) << name << " " << a.channel << ": " << a.samples_flagged << " flagged";
      if (a.left_whole) {
        std::printf("[ measured ] %s %s: %d samples flagged, left whole\n", name.c_str(), a.channel.c_str(),
                    a.samples_flagged);
        EXPECT_TRUE(a.bursts.empty());
        EXPECT_EQ(a.clean_max, a.raw_max);
      }
    }
  }
}

}  // namespace
}  // namespace drillwave::diagnosis
