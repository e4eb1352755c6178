#pragma once
// The memory a piece of work may take, checked before the work: what the machine has available (the kernel's
// MemAvailable) and what this process may still map (its address-space limit, ulimit -v, less what it maps now).
#include <stdexcept>
#include <string>

namespace drillwave {

// The machine cannot hold the work: not the input's fault nor drillwave's (the command-line tool exits 6).
class MemoryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bytes this process can still allocate: the smaller of MemAvailable and the address-space limit's headroom;
// infinity where neither can be read (not Linux).
double AvailableMemoryBytes();

// MemoryError naming `what`, both sizes and what to do, where `estimated_bytes` exceed AvailableMemoryBytes().
void CheckMemory(double estimated_bytes, const std::string& what, const std::string& remedy);

}  // namespace drillwave
