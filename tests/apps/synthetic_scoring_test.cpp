// Issue 13's proof, scored as a user would meet it: `drillwave diagnose` on each synthetic recording (an independent
// simulator's, with concealed effects) from the baseline case and the operator's sidecar, then scored against the
// recordings' KEY — which only this test reads, never the tool. A recording passes when every concealed effect is
// named, nothing is named on a base recording, and the held-out error is lower after than before wherever there is
// an effect. The test is labelled `scoring` in tests/CMakeLists.txt (1-8 minutes a recording, and not every recording
// passes yet) and kept out of the default test run; scripts/score-synthetic.sh runs it.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace {

namespace fs = std::filesystem;
using drillwave::test_support::Outcome;
using drillwave::test_support::RunTool;

const fs::path kSynthetic = fs::path(DRILLWAVE_SHARED_DIR) / "recordings" / "synthetic";

class SyntheticScoring : public ::testing::TestWithParam<std::string> {};

// Recordings whose concealed effect the held-out check cannot confirm with this model, as measured: the tool must then
// propose that effect first, name nothing else, and leave the held-out error no higher than it was.
//   rec12 (dc_motor): with the KEY's own DC motor the held-out error falls only from 0.723 to 0.655 (docs/results.md,
//   KEY consistency), while the loop asks for more than chance, sqrt(2 / 25) = 0.28 for its 25 held-out features; a
//   fitted DC motor reaches 0.803 against the baseline's 0.79 (fit window 1.37 -> 0.633). Until stop 29 the tool named it (1.2 -> 0.573) because
//   6 of the baseline's 10 draws bounced where the recording does not, which inflated the baseline's error; since the
//   coupled kind follows the kink its start puts into the waves, 3 of 8 do (and none at tol 3e-6).
bool BelowTheHeldOutNoise(const std::string& name) { return name == "rec12"; }

TEST_P(SyntheticScoring, NamesTheConcealedEffectsAndImprovesTheHeldOutError) {
  const std::string name = GetParam();
  if (!fs::exists(kSynthetic / "KEY.json")) GTEST_SKIP() << "the synthetic recordings are not at " << kSynthetic;
  const nlohmann::json key = nlohmann::json::parse(std::ifstream(kSynthetic / "KEY.json"));
  nlohmann::json entry;
  for (const auto& r : key.at("recordings"))
    if (r.at("file") == name + ".csv") entry = r;
  ASSERT_FALSE(entry.is_null()) << name << " is not in the KEY";

  const fs::path out = drillwave::test_support::ScratchFolder("score-" + name);
  fs::remove_all(out);
  const Outcome o = RunTool("diagnose " + std::string(DRILLWAVE_TEST_SOURCE_DIR) + "/json-cases/baseline-60rpm.json " +
                            (kSynthetic / (name + ".csv")).string() + " --sidecar " +
                            (kSynthetic / (name + ".json")).string() + " -j 2 -o " + out.string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const nlohmann::json d = nlohmann::json::parse(std::ifstream(out / "diagnosis.json"));
  std::set<std::string> named, concealed;
  for (const auto& h : d.at("hypotheses")) named.insert(h.at("effect").get<std::string>());
  for (const auto& [effect, parameters] : entry.at("effects").items()) concealed.insert(effect);
  const double before = d.at("held_out").at("error_before"), after = d.at("held_out").at("error_after");
  std::string named_list, concealed_list;
  for (const auto& n : named) named_list += n + " ";
  for (const auto& c : concealed) concealed_list += c + " ";
  std::printf("[ measured ] %s: concealed { %s} named { %s} held-out error %.3g -> %.3g, %d model runs\n",
              name.c_str(), concealed_list.c_str(), named_list.c_str(), before, after, d.at("model_runs").get<int>());
  if (BelowTheHeldOutNoise(name)) {
    for (const std::string& effect : named) EXPECT_TRUE(concealed.count(effect)) << name << ": " << effect << " named";
    ASSERT_FALSE(d.at("proposals").empty()) << name << ": nothing proposed";
    EXPECT_TRUE(concealed.count(d.at("proposals").at(0).at("effect").get<std::string>()))
        << name << ": the first proposal is " << d.at("proposals").at(0).at("effect");
    EXPECT_LE(after, before) << name << ": the held-out error grew";
    fs::remove_all(out);
    return;
  }
  for (const std::string& effect : concealed) EXPECT_TRUE(named.count(effect)) << name << ": " << effect << " not named";
  if (concealed.empty()) {
    EXPECT_TRUE(named.empty()) << name << " is a base recording; named " << named_list;
  } else {
    EXPECT_LT(after, before) << name << ": the held-out error did not fall";
  }
  fs::remove_all(out);
}

INSTANTIATE_TEST_SUITE_P(Recordings, SyntheticScoring,
                         ::testing::Values("rec01", "rec02", "rec03", "rec04", "rec05", "rec06", "rec07", "rec08",
                                           "rec09", "rec10", "rec11", "rec12"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
