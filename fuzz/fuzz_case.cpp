// libFuzzer target: bytes as a case file, parsed (io::ParseJsonText), prepared (cases::ParseCase, any kind) and, once
// accepted, run briefly (short_run.hpp). Bad input must end in InputError, a run in success or a NumericalError;
// anything else (a crash, a sanitizer report, another exception, a hang) is a bug, and a case accepted must also be
// writable as case.json.
#include <cstddef>
#include <cstdint>
#include <string>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "short_run.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const drillwave::cases::Case c = drillwave::cases::ParseCase(
        drillwave::io::ParseJsonText(std::string(reinterpret_cast<const char*>(data), size), "fuzz input"));
    (void)c.document.dump();  // what writing case.json does after a run
    drillwave::fuzz::RunBriefly(c.document);
  } catch (const drillwave::InputError&) {
  }
  return 0;
}
