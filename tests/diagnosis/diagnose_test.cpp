// Diagnosis on the twelve synthetic recordings (../shared; skipped where absent): the baseline model at each
// recording's operating point (from its operator sidecar) is compared with it, and the rules name the effects they
// cover. KEY.json, which says what each recording hides, is read here to score and never by the tool.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/diagnosis/diagnose.hpp"
#include "drillwave/io/json_reader.hpp"

namespace drillwave::diagnosis {
namespace {

TEST(Diagnose, NamesTheConcealedEffectsItsRulesCover) {
  const std::string dir = std::string(DRILLWAVE_SHARED_DIR) + "/recordings/synthetic";
  if (!std::filesystem::exists(dir + "/KEY.json")) GTEST_SKIP() << "the synthetic recordings are not at " << dir;
  const std::set<std::string> covered{"soft_topdrive", "side_friction", "stribeck", "axial_coupling_off"};
  nlohmann::json baseline = io::LoadJsonFile(std::string(DRILLWAVE_SOURCE_DIR) + "/json-cases/baseline-60rpm.json");
  baseline["simulation"]["abs_tol"] = baseline["simulation"]["rel_tol"] = 1e-4;
  const nlohmann::json key = io::LoadJsonFile(dir + "/KEY.json");
  int right = 0, total = 0;
  for (const auto& entry : key.at("recordings")) {
    const std::string name = entry.at("file").get<std::string>();
    const std::string stem = name.substr(0, name.size() - 4);
    const nlohmann::json doc = CaseFromSidecar(io::LoadJsonFile(dir + "/" + stem + ".json"), baseline, 30);
    cases::RunResult model = cases::RunCase(cases::ParseCase(doc)).result;
    for (double& t : model.time_s) t -= 30;
    const Recording rec = LoadRecording(dir + "/" + name);
    const Diagnosis d = Diagnose(rec, model,
                                 {{"bit_rpm", "bit_rpm", 1}, {"top_rpm", "top_rpm", 1},
                                  {"top_torque_kNm", "top_torque_Nm", 1e-3}, {"wob_kN", "wob_N", 1e-3}},
                                 5, 1e9);
    std::set<std::string> found, hidden;
    for (const Hypothesis& h : d.hypotheses) found.insert(h.effect);
    for (const auto& e : entry.at("effects").items())
      if (covered.count(e.key())) hidden.insert(e.key());
    std::string f, h;
    for (const auto& s : found) f += s + " ";
    for (const auto& s : hidden) h += s + " ";
    std::printf("[ measured ] %s: found [ %s] concealed (covered) [ %s]\n", name.c_str(), f.c_str(), h.c_str());
    for (const Hypothesis& hy : d.hypotheses)
      if (hy.effect == "side_friction") {
        const double truth = entry.at("effects").at("side_friction").at("total_kNm").get<double>();
        std::printf("[ measured ]   side friction estimate %.2f kN m, concealed %.2f kN m\n", hy.estimate, truth);
        EXPECT_NEAR(hy.estimate, truth, 0.15 * truth) << name;
      }
    EXPECT_EQ(found, hidden) << name;
    right += found == hidden ? 1 : 0;
    ++total;
  }
  std::printf("[ measured ] %d of %d recordings diagnosed right for the covered effects\n", right, total);
  EXPECT_EQ(total, 12);
}

// The named effect, modelled: Coulomb side friction over rec07's concealed stretch makes the baseline explain it.
TEST(Diagnose, SideFrictionModelledExplainsItsRecording) {
  const std::string dir = std::string(DRILLWAVE_SHARED_DIR) + "/recordings/synthetic";
  if (!std::filesystem::exists(dir + "/rec07.csv")) GTEST_SKIP() << "the synthetic recordings are not at " << dir;
  nlohmann::json baseline = io::LoadJsonFile(std::string(DRILLWAVE_SOURCE_DIR) + "/json-cases/baseline-60rpm.json");
  baseline["simulation"]["abs_tol"] = baseline["simulation"]["rel_tol"] = 1e-4;
  const Recording rec = LoadRecording(dir + "/rec07.csv");
  auto diagnose = [&](const nlohmann::json& side_friction) {
    nlohmann::json doc = CaseFromSidecar(io::LoadJsonFile(dir + "/rec07.json"), baseline, 30);
    doc["model"]["string"]["side_friction"] = side_friction;
    cases::RunResult model = cases::RunCase(cases::ParseCase(doc)).result;
    for (double& t : model.time_s) t -= 30;
    return Diagnose(rec, model,
                    {{"bit_rpm", "bit_rpm", 1}, {"top_rpm", "top_rpm", 1}, {"top_torque_kNm", "top_torque_Nm", 1e-3},
                     {"wob_kN", "wob_N", 1e-3}},
                    5, 1e9);
  };
  auto torque_mismatch = [](const Diagnosis& d) {
    for (const auto& f : d.comparison.features)
      if (f.feature == "top_torque_kNm mean") return f.relative;
    return std::nan("");
  };
  const Diagnosis before = diagnose({{"torque_per_m_Nm", 0.0}});
  const Diagnosis after = diagnose({{"torque_per_m_Nm", 3.4602}, {"from_m", 853.7}, {"to_m", 2337.1}});
  std::printf("[ measured ] rec07 mean top torque: baseline %+.1f %%, with the side friction %+.1f %%; rules firing "
              "%zu -> %zu\n", 100 * torque_mismatch(before), 100 * torque_mismatch(after), before.hypotheses.size(),
              after.hypotheses.size());
  EXPECT_LT(torque_mismatch(before), -0.4);
  EXPECT_LT(std::abs(torque_mismatch(after)), 0.05);
  EXPECT_FALSE(before.hypotheses.empty());
  // The side friction is no longer named once it is modelled. (Whether the stribeck rule fires here is not
  // asserted: with side friction the recording sticks rarely, 5.5 % of the time, and the model's stick fraction in
  // that regime changes with the tolerance, 0.0 % at 1e-3 to 0.4 % at 1e-4 and ~1 % at 3e-4 and 1e-5, on both sides
  // of the rule's 1 % threshold.)
  for (const auto& h : after.hypotheses) {
    std::printf("[ measured ] still firing after: %s (%s)\n", h.effect.c_str(), h.evidence.c_str());
    EXPECT_NE(h.effect, "side_friction");
  }
}

}  // namespace
}  // namespace drillwave::diagnosis
