// libFuzzer target: the input's first byte picks a case (the embedded default case or one of json-cases/), each
// following line is a command line's --set "/json/pointer=value", applied in turn (io::ApplySetOption), and the case
// is then prepared (cases::ParseCase) and, once accepted, run briefly (short_run.hpp). Bad input must end in
// InputError, a run in success or a NumericalError; anything else is a bug (a case accepted must also be writable as
// case.json).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "short_run.hpp"

namespace {

// Every kind's fields are reachable: the default case and every case file, read once.
std::vector<nlohmann::json> BaseCases() {
  std::vector<nlohmann::json> cases{
      drillwave::io::ParseJsonText(drillwave::cases::DefaultCaseText(), "the default case")};
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(DRILLWAVE_JSON_CASES))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());  // the same byte picks the same case on every run
  for (const auto& file : files) cases.push_back(drillwave::io::LoadJsonFile(file.string()));
  return cases;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::vector<nlohmann::json> bases = BaseCases();
  if (size == 0) return 0;
  nlohmann::json doc = bases[data[0] % bases.size()];
  std::istringstream lines(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  try {
    for (std::string line; std::getline(lines, line);) drillwave::io::ApplySetOption(doc, line);
    drillwave::cases::ParseCase(doc);
    (void)doc.dump();  // what writing case.json does after a run
    drillwave::fuzz::RunBriefly(doc);
  } catch (const drillwave::InputError&) {
  }
  return 0;
}
