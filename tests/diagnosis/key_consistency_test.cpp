// drillwave's components against the independent simulator (issue 12 item 3): for each synthetic recording, the
// baseline case at the sidecar's operating point with the concealed effects switched on at the KEY's own parameter
// values — read here, by the test, never by the tool — is compared with the recording feature by feature, as the
// diagnosis loop compares (noise carried into the measured channels, each difference in the feature's own spread,
// on the held-out half of the usable recording, as `diagnose` takes it). With the true effects on, the model must come closer to the recording than the
// baseline does, and within a few spreads of it; where it cannot, the reason is physics the test names, and
// KeyConsistencyAtTheKeysRock shows it: the recording's own rock (the KEY's nuisance eps and sigma l) brings the
// model to it. The sidecar's case starts as the simulator did, from steady drilling over a tiny bottom roughness.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

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
const fs::path kSyntheticTrain = fs::path(DRILLWAVE_SHARED_DIR) / "recordings" / "synthetic-train";
constexpr double kInch = 0.0254;

// The KEY's effect, in the simulator's names, switched on as drillwave's component.
void SwitchOn(const std::string& effect, const nlohmann::json& p, nlohmann::json& doc) {
  nlohmann::json& m = doc["model"];
  if (effect == "side_friction") {
    m["string"]["side_friction"] = {
        {"from_m", p.at("s1_m")}, {"to_m", p.at("s2_m")}, {"torque_per_m_Nm", p.at("torque_per_m_Nm")}};
  } else if (effect == "soft_topdrive") {
    m["top"]["kp_Nms_per_rad"] = p.at("kp_Nms_rad");
    m["top"]["ki_Nm_per_rad"] = p.at("ki_Nm_rad");
  } else if (effect == "unbalance") {
    m["bit"]["unbalance"] = {{"lateral_mass_kg", p.at("M_lat_kg")},
                             {"lateral_stiffness_N_per_m", p.at("k_lat_N_m")},
                             {"lateral_damping_Ns_per_m", p.at("c_lat_Ns_m")},
                             {"unbalance_mass_kg", p.at("m_unb_kg")},
                             {"eccentricity_m", p.at("e_m")}};
  } else if (effect == "sensor_delay") {
    for (const char* channel : {"bit_rpm", "wob_N"}) doc["sensors"]["channels"][channel]["delay_s"] = p.at("tau_s");
  } else if (effect == "axial_coupling_off") {
    m["axial_coupling"] = false;
  } else if (effect == "stribeck") {
    m["rock"]["mu"] = p.at("mu_d");
    m["rock"]["stribeck"] = {{"static_mu", p.at("mu_s")}, {"velocity_rad_s", p.at("omega_s_rad_s")}};
  } else if (effect == "kelvin_voigt") {
    m["string"]["kelvin_voigt_s"] = p.at("eta_s");
  } else if (effect == "bha") {
    m["string"]["bha"] = {{"length_m", p.at("Lb_m")},
                          {"outer_diameter_m", p.at("od_in").get<double>() * kInch},
                          {"inner_diameter_m", p.at("id_in").get<double>() * kInch}};
    m["bit"]["inertia_kgm2"] = p.at("J_bit_kgm2");
    m["bit"]["mass_kg"] = p.at("M_bit_kg");
  } else if (effect == "dc_motor") {
    m["top"]["motor"] = {
        {"motor_constant_Nm_per_A", p.at("K_Nm_A")}, {"resistance_ohm", p.at("R_ohm")}, {"inductance_H", p.at("La_H")}};
  } else {
    FAIL() << "no component for the KEY's effect " << effect;
  }
}

// The loop's error of a case against the recording on its held-out window (the later half of the usable
// recording, as `diagnose` takes it), nothing fitted.
DiagnosisLoop CaseAgainst(const nlohmann::json& doc, const Recording& recording) {
  const cases::Case c = cases::ParseCase(doc);
  LoopOptions o = DefaultLoopOptions(c, recording, kSidecarWarmupS);
  o.max_singles = 0;  // the case's errors only
  o.measure_regime_margin = false;
  o.maps = ResolveChannelMaps({}, recording, ProbeChannels(c));
  return RunDiagnosisLoop(doc, recording, o);
}
double HeldOutError(const nlohmann::json& doc, const Recording& recording) {
  return CaseAgainst(doc, recording).baseline_held_out_error;
}

// The smallest of that error over three draws of the model: the same case at tolerances 1e-4, 1e-5 and 1e-6. Where
// the model has several attractors at the operating point, one run lands on either by rounding, and its error is
// that draw's: on rec12 (with four surface passes and the former 5 % start bump) the baseline measured 1.25 / 1.21 /
// 164 / 85.6 / 1.12 and the KEY's DC motor 0.896 / 0.528 / 297 / 0.929 / 261 at tolerances 1e-4 / 3e-5 / 1e-5 /
// 3e-6 / 1e-6. The recording shows one regime; the question is
// whether the model reaches it, so the closest draw counts, for the baseline and the KEY's model alike.
double ClosestDrawError(const nlohmann::json& doc, const Recording& recording) {
  double closest = INFINITY;
  for (double tol : {1e-4, 1e-5, 1e-6}) {
    nlohmann::json draw = doc;
    draw["simulation"]["abs_tol"] = draw["simulation"]["rel_tol"] = tol;
    closest = std::min(closest, HeldOutError(draw, recording));
  }
  return closest;
}

// The KEY's entry of a recording (effects, nuisance, config, stats).
nlohmann::json KeyRecord(const std::string& name, const fs::path& set = kSynthetic) {
  const nlohmann::json key = nlohmann::json::parse(std::ifstream(set / "KEY.json"));
  for (const auto& r : key.at("recordings"))
    if (r.at("file") == name + ".csv") return r;
  ADD_FAILURE() << name << " is not in the KEY";
  return {{"effects", nlohmann::json::object()}};
}

// The baseline case at the recording's operating point, as `diagnose` builds it from the sidecar.
nlohmann::json SidecarCase(const std::string& name, const fs::path& set = kSynthetic) {
  return CaseFromSidecar(io::LoadJsonFile((set / (name + ".json")).string()),
                         testing::LoadCase("baseline-60rpm"),
                         kSidecarWarmupS);
}

// Where the components at the KEY's values do not come within the spreads, and why (the README says so too). rec04
// left this list at stop 26: with its bounce's weight on bit left whole and the envelopes' correlogram among the
// features, the KEY's 2.1-s delay takes the held-out error from 3.31 to 0.825 (closest of three draws).
const std::map<std::string, std::string> kExplained = {
    {"rec11", "the BHA string sits at a stability boundary, which the rock moves: at the nominal rock drillwave's "
              "model oscillates with the KEY's collars where the recording is smooth (376); at the KEY's rock (eps "
              "1.126 of nominal) it is smooth and agrees (0.019, KeyConsistencyAtTheKeysRock)"},
};

// Where the components at the KEY's values do not come within the spreads and the reason is not known yet: the test
// prints the errors and skips, saying so. None since the sidecar's case starts as the simulator does (steady drilling
// plus a tiny bottom-hole roughness instead of a 5 % set-point bump): rec01's transient (6.7 -> 2.5) and rec12 (642
// -> 0.305, no longer bouncing) came within the spreads.
const std::map<std::string, std::string> kNotYetExplained = {};

// Where the effect at the KEY's values moves the held-out error by less than chance (sqrt(2 / K) for K held-out
// features, the loop's error_chance): which of the two errors is lower then depends on the draw, so the test asks only
// that the KEY's model stays within chance of the baseline and within the spreads. rec12 left this list at stop 37:
// with the surface torque's fast content read in two halves its DC motor takes the closest draw from 0.995 to 0.702
// (it had moved the error by less than chance: 0.723 and 0.713 against 0.655 and 0.765 on stop 29's and 30's code).
const std::map<std::string, std::string> kBelowTheNoise = {};
constexpr double kChance = 0.283;  // sqrt(2 / 25) for 25 held-out features

// A recording's held-out error (closest of three draws) for the baseline at its operating point and with the KEY's
// effects switched on.
struct KeyErrors {
  nlohmann::json effects;
  std::string list;  // the effects' names
  double before = 0, after = 0;
};
KeyErrors KeyErrorsOf(const std::string& name, const fs::path& set) {
  KeyErrors e;
  e.effects = KeyRecord(name, set).at("effects");
  const Recording recording = LoadRecording((set / (name + ".csv")).string());
  const nlohmann::json baseline = SidecarCase(name, set);
  nlohmann::json with_key = baseline;
  for (const auto& [effect, parameters] : e.effects.items()) SwitchOn(effect, parameters, with_key), e.list += effect + " ";
  e.before = ClosestDrawError(baseline, recording);
  e.after = e.effects.empty() ? e.before : ClosestDrawError(with_key, recording);
  return e;
}

class KeyConsistency : public ::testing::TestWithParam<std::string> {};

TEST_P(KeyConsistency, TheConcealedEffectsAtTheirKeyValuesBringTheModelToTheRecording) {
  const std::string name = GetParam();
  if (!fs::exists(kSynthetic / "KEY.json")) GTEST_SKIP() << "the synthetic recordings are not at " << kSynthetic;
  const KeyErrors e = KeyErrorsOf(name, kSynthetic);
  const double before = e.before, after = e.after;
  const nlohmann::json& effects = e.effects;
  std::printf("[ measured ] %s { %s}: held-out error, baseline %.3g, with the KEY's effects %.3g\n",
              name.c_str(), e.list.c_str(), before, after);
  if (kExplained.count(name)) GTEST_SKIP() << name << ": " << kExplained.at(name);
  if (kBelowTheNoise.count(name)) {
    EXPECT_LT(std::abs(after - before), kChance) << name << ": " << kBelowTheNoise.at(name);
    EXPECT_LT(after, 5.0) << name << ": more than about two spreads off with the true effects on";
    return;
  }
  if (!effects.empty()) {
    EXPECT_LT(after, before) << name << ": the true effects do not bring the model closer";
  }
  if (kNotYetExplained.count(name)) GTEST_SKIP() << name << ": error " << after << ": " << kNotYetExplained.at(name);
  EXPECT_LT(after, 5.0) << name << ": more than about two spreads off with the true effects on";
}

// Recordings as the simulator made them: the KEY's effects on the recording's own rock (its nuisance
// eps and sigma l, drawn per recording: BASELINE.md), from the sidecar's start (steady drilling plus a tiny
// bottom-hole roughness, as the simulator starts) with a roughness of `roughness_m` rms. The tool never knows the
// rock's draw; this shows that the components, not the physics between them, agree.
struct QuietStart {
  std::string recording;
  double roughness_m;
};

class KeyConsistencyAtTheKeysRock : public ::testing::TestWithParam<QuietStart> {};

// The recording's case with the KEY's effects on the KEY's rock, started over a bottom roughness of `roughness_m`.
nlohmann::json AtTheKeysRock(const std::string& name, const nlohmann::json& entry, double roughness_m) {
  nlohmann::json doc = SidecarCase(name);
  for (const auto& [effect, parameters] : entry.at("effects").items()) SwitchOn(effect, parameters, doc);
  nlohmann::json& rock = doc["model"]["rock"];
  rock["intrinsic_specific_energy_Pa"] = entry.at("nuisance").at("eps_Pa");
  rock["sigma_l_N_per_m"] = entry.at("nuisance").at("sigma_l_N_m");
  EXPECT_TRUE(rock.contains("bottom_roughness")) << "CaseFromSidecar no longer starts from a rough bottom";
  rock["bottom_roughness"]["rms_m"] = roughness_m;
  return doc;
}

TEST_P(KeyConsistencyAtTheKeysRock, TheExplainedRecordingsAgreeOnTheirOwnRock) {
  const auto& [name, roughness] = GetParam();
  if (!fs::exists(kSynthetic / "KEY.json")) GTEST_SKIP() << "the synthetic recordings are not at " << kSynthetic;
  const nlohmann::json doc = AtTheKeysRock(name, KeyRecord(name), roughness);
  const double error = HeldOutError(doc, LoadRecording((kSynthetic / (name + ".csv")).string()));
  std::printf("[ measured ] %s at the KEY's rock, start roughness %g um: held-out error %.3g\n", name.c_str(),
              roughness * 1e6, error);
  EXPECT_LT(error, 1.0) << name << ": not within the spreads even on the recording's own rock";
}

INSTANTIATE_TEST_SUITE_P(Recordings, KeyConsistencyAtTheKeysRock,
                         ::testing::Values(QuietStart{"rec01", 1e-6}, QuietStart{"rec01", kSidecarStartRoughnessM},
                                           QuietStart{"rec01", 1e-4}, QuietStart{"rec11", kSidecarStartRoughnessM}),
                         [](const ::testing::TestParamInfo<QuietStart>& info) {
                           return info.param.recording + "_roughness" +
                                  std::to_string(static_cast<int>(std::lround(info.param.roughness_m * 1e6))) + "um";
                         });

// rec12's operating point holds two regimes in drillwave's model, a bouncing bit and stick-slip on the bottom, and
// the start decides between them (the independent simulator's twin without the DC motor bounced as well). The
// recording stays on the bottom; the loop draws starts until five do too and judges the baseline on those, so that
// the model is compared with the recording in the regime the recording shows, not by the share of starts that bounce.
TEST(BistableRecording, Rec12sBaselineIsJudgedOnItsDrawsThatStayOnTheBottom) {
  if (!fs::exists(kSynthetic / "rec12.csv")) GTEST_SKIP() << "the synthetic recordings are not at " << kSynthetic;
  const DiagnosisLoop loop = CaseAgainst(SidecarCase("rec12"), LoadRecording((kSynthetic / "rec12.csv").string()));
  const std::vector<char>& in_regime = loop.baseline_draw_in_regime;
  const auto on_bottom = std::count(in_regime.begin(), in_regime.end(), 1);
  std::printf("[ measured ] rec12's baseline: %ld of %zu draws on the bottom, held-out error %.3g; recording off the "
              "bottom %.4f of the time\n", static_cast<long>(on_bottom), in_regime.size(), loop.baseline_held_out_error,
              loop.recorded_off_bottom_share);
  EXPECT_FALSE(loop.recording_bounces);
  EXPECT_EQ(loop.recorded_off_bottom_share, 0.0);
  ASSERT_EQ(in_regime.size(), loop.baseline_held_out_draw_errors.size());
  EXPECT_LT(on_bottom, static_cast<long>(in_regime.size())) << "no draw bounced: the test no longer shows both regimes";
  EXPECT_EQ(on_bottom, 5) << "five draws on the bottom were expected within fifteen";
  EXPECT_TRUE(in_regime.at(static_cast<std::size_t>(loop.fit_draw)));
  // The judged error is a draw on the bottom's, far below any bouncing draw's.
  for (std::size_t d = 0; d < in_regime.size(); ++d)
    if (!in_regime[d]) {
      EXPECT_GT(loop.baseline_held_out_draw_errors[d], 20 * loop.baseline_held_out_error);
    }
  EXPECT_LT(loop.baseline_held_out_error, 5.0);
}

// Why rec01's pair is no harder than its parts: while every node of the string turns forward, Coulomb side friction
// is a constant torque, so the pair is the soft drive alone (rec01's transient) with the top torque raised by the
// friction's total f (s2 - s1) (`drillwave stability` gives the same roots with and without it). Held at its full
// level throughout, the friction shows that no node stopped.
TEST(KeyConsistencyRec01, SideFrictionOnTurningNodesOnlyRaisesTheTopTorqueByItsTotal) {
  if (!fs::exists(kSynthetic / "KEY.json")) GTEST_SKIP() << "the synthetic recordings are not at " << kSynthetic;
  const nlohmann::json entry = KeyRecord("rec01");
  const nlohmann::json& side = entry.at("effects").at("side_friction");
  const double total_kNm = side.at("torque_per_m_Nm").get<double>() *
                           (side.at("s2_m").get<double>() - side.at("s1_m").get<double>()) / 1000;
  const nlohmann::json pair = AtTheKeysRock("rec01", entry, kSidecarStartRoughnessM);
  nlohmann::json soft_drive_alone = pair;
  soft_drive_alone["model"]["string"].erase("side_friction");
  const Recording recording = LoadRecording((kSynthetic / "rec01.csv").string());
  const FeatureSet with = CaseAgainst(pair, recording).baseline_held_out;
  const FeatureSet without = CaseAgainst(soft_drive_alone, recording).baseline_held_out;
  const double raised = with.Value("top_torque_kNm mean") - without.Value("top_torque_kNm mean");
  std::printf("[ measured ] rec01: side friction raises the top torque by %.4f kNm (f (s2 - s1) = %.4f kNm); bit rpm "
              "std %.3f / %.3f, top rpm std %.3f / %.3f with / without\n",
              raised, total_kNm, with.Value("bit_rpm std"), without.Value("bit_rpm std"), with.Value("top_rpm std"),
              without.Value("top_rpm std"));
  EXPECT_NEAR(raised, total_kNm, 0.01 * total_kNm);
  for (const char* feature : {"bit_rpm std", "top_rpm std", "top_torque_kNm std", "wob_kN std", "period_s"})
    EXPECT_NEAR(with.Value(feature), without.Value(feature), 0.02 * std::abs(without.Value(feature))) << feature;
  EXPECT_EQ(with.Value("stick_fraction"), 0.0);  // nor the bit
}

INSTANTIATE_TEST_SUITE_P(Recordings, KeyConsistency,
                         ::testing::Values("rec01", "rec02", "rec03", "rec04", "rec05", "rec06", "rec07", "rec08",
                                           "rec09", "rec10", "rec11", "rec12"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// The same on the 36 training recordings (other operating points and draws, 0-2 effects each): which concealed
// effects drillwave's components reproduce at the KEY's values, and by how much, in one table. An acceptance score,
// not a gate (labelled `scoring`, outside scripts/test.sh): where the components at the KEY's values do not bring the
// model closer, the diagnosis cannot name the effect, and the failure says which component to look at.
class KeyConsistencyTrain : public ::testing::TestWithParam<int> {};

std::string TrainName(int number) {
  char name[8];
  std::snprintf(name, sizeof name, "rec%02d", number);
  return name;
}

TEST_P(KeyConsistencyTrain, TheConcealedEffectsAtTheirKeyValuesBringTheModelToTheRecording) {
  const std::string name = TrainName(GetParam());
  if (!fs::exists(kSyntheticTrain / "KEY.json"))
    GTEST_SKIP() << "the training recordings are not at " << kSyntheticTrain;
  const KeyErrors e = KeyErrorsOf(name, kSyntheticTrain);
  const double before = e.before, after = e.after;
  std::printf("[ measured ] train %s { %s}: held-out error, baseline %.3g, with the KEY's effects %.3g (chance %.3g)\n",
              name.c_str(), e.list.c_str(), before, after, kChance);
  if (!e.effects.empty()) {
    EXPECT_LT(after, before - kChance) << name << ": the true effects do not bring the model closer beyond chance";
  }
  EXPECT_LT(after, 5.0) << name << ": more than about two spreads off with the true effects on";
}

INSTANTIATE_TEST_SUITE_P(TrainRecordings, KeyConsistencyTrain, ::testing::Range(1, 37),
                         [](const ::testing::TestParamInfo<int>& info) { return TrainName(info.param); });

}  // namespace
}  // namespace drillwave::diagnosis
