#include "drillwave/core/memory.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "drillwave/core/format.hpp"

namespace drillwave {
namespace {

// A "Name:   123 kB" line of a /proc file, in bytes; infinity where it is missing.
double ProcKilobytes(const char* file, const std::string& name) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    if (line.compare(0, name.size() + 1, name + ":") != 0) continue;
    std::istringstream fields(line.substr(name.size() + 1));
    double kilobytes = 0;
    if (fields >> kilobytes) return kilobytes * 1024;
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace

double AvailableMemoryBytes() {
  double available = ProcKilobytes("/proc/meminfo", "MemAvailable");
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    const double mapped = ProcKilobytes("/proc/self/status", "VmSize");
    if (std::isfinite(mapped)) available = std::min(available, static_cast<double>(limit.rlim_cur) - mapped);
  }
  return std::max(available, 0.0);
}

void CheckMemory(double estimated_bytes, const std::string& what, const std::string& remedy) {
  const double available = AvailableMemoryBytes();
  if (!(estimated_bytes > available)) return;
  auto megabytes = [](double bytes) { return Significant(bytes / 1e6, 3) + " MB"; };
  throw MemoryError("about " + megabytes(estimated_bytes) + " of memory for " + what + ", but only " +
                    megabytes(available) + " available (the machine's MemAvailable, or this process's address-space " +
                    "limit, ulimit -v): " + remedy);
}

}  // namespace drillwave
