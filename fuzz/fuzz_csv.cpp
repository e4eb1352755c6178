// libFuzzer target: bytes as a CSV file, read as a table (io::ReadCsv, NaN allowed) and as a recording
// (diagnosis::LoadRecording: finite cells, increasing time_s). Bad input must end in InputError; anything else is a
// bug. The readers take a file name, so the bytes go to an in-memory file opened through /proc/self/fd.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "drillwave/core/error.hpp"
#include "drillwave/diagnosis/recording.hpp"
#include "drillwave/io/csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const int fd = memfd_create("drillwave-fuzz.csv", 0);
  static const std::string file = "/proc/self/fd/" + std::to_string(fd);
  if (fd < 0 || ftruncate(fd, 0) != 0 || pwrite(fd, data, size, 0) != static_cast<ssize_t>(size)) std::abort();
  try {
    drillwave::io::ReadCsv(file);
  } catch (const drillwave::InputError&) {
  }
  try {
    drillwave::diagnosis::LoadRecording(file);
  } catch (const drillwave::InputError&) {
  }
  return 0;
}
