// The effect catalogue: the pairs the loop screens together (one component) are effects the coupled kind offers, and
// both switched on at their first values make a case that parses.
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/diagnosis/effects.hpp"
#include "drillwave/io/json_reader.hpp"

namespace drillwave::diagnosis {
namespace {

TEST(Effects, EachOneComponentPairIsOfferedTogetherByTheCoupledKind) {
  const nlohmann::json doc = io::LoadJsonFile(std::string(DRILLWAVE_SOURCE_DIR) + "/json-cases/baseline-60rpm.json");
  const std::vector<Effect> offered = ProposeEffects(doc, FeatureSet{}, FeatureSet{});
  auto find = [&](const std::string& name) {
    return std::find_if(offered.begin(), offered.end(), [&](const Effect& e) { return e.name == name; });
  };
  ASSERT_FALSE(OneComponentPairs().empty());
  for (const auto& [first, second] : OneComponentPairs()) {
    const auto& vocabulary = EffectVocabulary();
    EXPECT_NE(std::find(vocabulary.begin(), vocabulary.end(), first), vocabulary.end()) << first;
    EXPECT_NE(std::find(vocabulary.begin(), vocabulary.end(), second), vocabulary.end()) << second;
    const auto a = find(first), b = find(second);
    ASSERT_NE(a, offered.end()) << first;
    ASSERT_NE(b, offered.end()) << second;
    nlohmann::json both = doc;
    for (const Effect* e : {&*a, &*b}) {
      std::vector<double> start;
      for (const EffectParameter& p : e->parameters) start.push_back(p.start);
      e->apply(both, start);
    }
    EXPECT_NO_THROW(cases::ParseCase(both)) << first << " + " << second;
    EXPECT_NE(both, doc);
  }
}

}  // namespace
}  // namespace drillwave::diagnosis
