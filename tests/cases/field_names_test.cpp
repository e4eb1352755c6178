// One name for one quantity in every kind, and every field `drillwave kinds` documents is one a case may set:
// the documentation (ModelKind::FieldSchema) is held against the readers and against each other.
#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/kinds.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "json_case.hpp"

namespace drillwave::cases {
namespace {

// The documented fields of a kind as paths below /model ("top/inertia_kgm2"), array elements as "*"; the friction
// laws' own fields are documented once, under "friction laws", and left out here.
std::set<std::string> DocumentedFields(const ModelKind& kind) {
  std::set<std::string> fields;
  const nlohmann::json schema = kind.FieldSchema();
  for (const auto& [path, text] : schema.items())
    if (path != "friction laws") fields.insert(path);
  return fields;
}

const ModelKind& Kind(const std::string& name) {
  for (const auto& kind : AllKinds())
    if (kind->name() == name) return *kind;
  throw std::runtime_error("no kind " + name);
}

// Quantities that more than one kind has, with the one path each of them uses.
struct SharedQuantity {
  const char* quantity;
  const char* path;
  std::vector<std::string> kinds;
};

const SharedQuantity kSharedQuantities[] = {
    {"top (drive) inertia", "top/inertia_kgm2", {"torsional_wave", "two_mass", "axial_torsional"}},
    {"top speed set-point", "top/speed_rad_s", {"torsional_wave", "two_mass", "axial_torsional"}},
    {"top kind of drive", "top/type", {"torsional_wave", "two_mass", "axial_torsional"}},
    {"PI proportional gain", "top/kp_Nms_per_rad", {"torsional_wave", "two_mass", "axial_torsional"}},
    {"PI integral gain", "top/ki_Nm_per_rad", {"torsional_wave", "two_mass", "axial_torsional"}},
    {"damper of the top to ground", "top/damping_Nms_per_rad", {"torsional_wave", "two_mass"}},
    {"DC motor constant", "top/motor/motor_constant_Nm_per_A", {"torsional_wave", "axial_torsional"}},
    {"DC motor armature resistance", "top/motor/resistance_ohm", {"torsional_wave", "axial_torsional"}},
    {"DC motor armature inductance", "top/motor/inductance_H", {"torsional_wave", "axial_torsional"}},
    {"bit (BHA) inertia", "bit/inertia_kgm2", {"torsional_wave", "two_mass", "axial_torsional"}},
    {"damper of the bit to ground", "bit/damping_Nms_per_rad", {"torsional_wave", "two_mass"}},
    {"bit friction law", "bit/friction", {"torsional_wave", "two_mass"}},
    {"distributed torsional damping", "string/torsional_damping_Nms_per_rad_m", {"torsional_wave", "axial_torsional"}},
    {"lumped shaft stiffness", "string/stiffness_Nm_per_rad", {"two_mass", "two_disc"}},
    {"lumped shaft damping", "string/damping_Nms_per_rad", {"two_mass", "two_disc"}},
    {"smoothing of set-valued friction", "friction_smoothing_rad_s", {"two_mass", "two_disc"}},
};

TEST(FieldNames, EachSharedQuantityHasOnePathInEveryKindThatHasIt) {
  for (const SharedQuantity& q : kSharedQuantities)
    for (const std::string& kind : q.kinds)
      EXPECT_TRUE(DocumentedFields(Kind(kind)).count(q.path)) << q.quantity << ": kind " << kind << " does not "
                                                              << "document /model/" << q.path;
}

TEST(FieldNames, NoKindDocumentsAFormerName) {
  // Former names of the shared quantities above (before the kinds were made to agree).
  const std::set<std::string> former = {"top_inertia_kgm2", "bit_inertia_kgm2", "top_damping_Nms_per_rad",
                                        "bit_damping_Nms_per_rad", "stiffness_Nm_per_rad", "shaft_damping_Nms_per_rad",
                                        "string/viscous_damping_Nms_per_rad_m", "top/motor_constant_Nm_per_A",
                                        "top/resistance_ohm", "top/inductance_H"};
  for (const auto& kind : AllKinds())
    for (const std::string& field : DocumentedFields(*kind)) {
      EXPECT_FALSE(former.count(field)) << kind->name() << " documents the former name " << field;
      EXPECT_NE(field.rfind("top_drive/", 0), 0u) << kind->name() << " documents " << field << " (now top/...)";
    }
}

TEST(FieldNames, AFormerNameIsRefusedWithItsNewPath) {
  nlohmann::json doc = testing::LoadCase("two-mass-stickslip");
  doc["model"]["bit_inertia_kgm2"] = 400.0;
  try {
    ParseCase(doc);
    FAIL() << "the former name was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "/model/bit_inertia_kgm2");
    EXPECT_NE(std::string(e.what()).find("/model/bit/inertia_kgm2"), std::string::npos) << e.what();
  }
}

// The values a documented "<parent>/type" field lists ("prescribed_speed | top_drive (PI) | torque").
std::vector<std::string> DocumentedTypes(const ModelKind& kind, const std::string& parent) {
  const nlohmann::json schema = kind.FieldSchema();
  const auto it = schema.find(parent + "/type");
  if (it == schema.end()) return {};
  std::vector<std::string> types;
  const std::string text = it->get<std::string>();
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t bar = std::min(text.find('|', start), text.size());
    std::string alternative = text.substr(start, bar - start);
    alternative.erase(0, alternative.find_first_not_of(' '));
    types.push_back(alternative.substr(0, alternative.find(' ')));
    start = bar + 1;
  }
  return types;
}

// Every documented field is known to its kind's reader: set in a case of that kind (to the case's own value, or to a
// probe value where the case leaves it out), it may be refused for its value or for a combination, but never as an
// unknown field. A field that only some variant reads (a DC motor's gains, a dissipative top's beta) must be known
// in at least one case of the kind in json-cases/, or in one with the variant's documented type switched on.
TEST(FieldNames, EveryDocumentedFieldIsReadByItsKind) {
  std::map<std::string, std::vector<nlohmann::json>> cases_by_kind;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(DRILLWAVE_SOURCE_DIR) + "/json-cases")) {
    if (entry.path().extension() != ".json") continue;
    nlohmann::json doc = io::LoadJsonFile(entry.path().string());
    cases_by_kind[doc["model"]["kind"].get<std::string>()].push_back(std::move(doc));
  }
  for (const auto& kind : AllKinds()) {
    const auto& docs = cases_by_kind[kind->name()];
    ASSERT_FALSE(docs.empty()) << "no case of kind " << kind->name() << " in json-cases/";
    for (std::string field : DocumentedFields(*kind)) {
      std::replace(field.begin(), field.end(), '*', '0');
      const std::string pointer = "/model/" + field;
      bool known = false;
      std::string last_error;
      std::vector<nlohmann::json> variants = docs;
      const std::string parent = field.substr(0, field.rfind('/'));
      for (const std::string& type : DocumentedTypes(*kind, parent))
        for (nlohmann::json doc : docs) {
          io::SetByPointer(doc, "/model/" + parent + "/type", type);
          variants.push_back(std::move(doc));
        }
      for (nlohmann::json doc : variants) {
        const nlohmann::json::json_pointer p(pointer);
        const bool present = [&] {
          try {
            return doc.contains(p);
          } catch (const nlohmann::json::exception&) {
            return false;  // a path through a number or an array the case does not have
          }
        }();
        try {
          if (!present) io::SetByPointer(doc, pointer, 1.0);
          ParseCase(doc);
          known = true;
        } catch (const InputError& e) {
          last_error = e.what();
          known = last_error.find("unknown field") == std::string::npos || e.json_path() != pointer.substr(0, e.json_path().size());
        }
        if (known) break;
      }
      EXPECT_TRUE(known) << kind->name() << " documents " << pointer << " but no case of the kind reads it: "
                         << last_error;
    }
  }
}

}  // namespace
}  // namespace drillwave::cases
