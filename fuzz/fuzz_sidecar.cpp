// libFuzzer target: bytes as a synthetic recording's operator sidecar (recNN.json), read onto the baseline case of the
// synthetic recordings as diagnose, compare, fit and calibrate --sidecar do (diagnosis::CaseFromSidecar), the case
// prepared (cases::ParseCase) and, once accepted, run briefly (short_run.hpp). Bad input must end in InputError, a run
// in success or a NumericalError; anything else is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/diagnosis/sidecar.hpp"
#include "drillwave/io/json_reader.hpp"
#include "short_run.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const nlohmann::json baseline =
      drillwave::io::LoadJsonFile(std::string(DRILLWAVE_JSON_CASES) + "/baseline-60rpm.json");
  try {
    const nlohmann::json sidecar =
        drillwave::io::ParseJsonText(std::string(reinterpret_cast<const char*>(data), size), "fuzz input");
    const drillwave::cases::Case c = drillwave::cases::ParseCase(
        drillwave::diagnosis::CaseFromSidecar(sidecar, baseline, drillwave::diagnosis::kSidecarWarmupS, "fuzz input"));
    drillwave::fuzz::RunBriefly(c.document);
  } catch (const drillwave::InputError&) {
  }
  return 0;
}
