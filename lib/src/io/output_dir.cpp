#include "drillwave/io/output_dir.hpp"

#include <filesystem>
#include <stdexcept>
#include <unistd.h>

namespace drillwave::io {

namespace fs = std::filesystem;

OutputDirectory::OutputDirectory(std::string dir) : dir_(std::move(dir)) {
  // Staged beside the destination (same file system, so the final moves are renames).
  const fs::path target = fs::absolute(dir_);
  staging_ = (target.parent_path() / ("." + target.filename().string() + ".staging-" + std::to_string(::getpid()))).string();
  fs::remove_all(staging_);
  fs::create_directories(staging_);
}

OutputDirectory::~OutputDirectory() {
  files_.clear();
  std::error_code ignored;
  if (!committed_) fs::remove_all(staging_, ignored);
}

std::ostream& OutputDirectory::Open(const std::string& file_name) {
  auto& f = files_[file_name];
  f = std::make_unique<std::ofstream>(staging_ + "/" + file_name);
  if (!*f) throw std::runtime_error("cannot write " + staging_ + "/" + file_name);
  return *f;
}

void OutputDirectory::Commit() {
  for (auto& [name, f] : files_) {
    f->flush();
    if (!*f) throw std::runtime_error("writing " + name + " failed");
    f->close();
  }
  fs::create_directories(dir_);
  for (const auto& [name, f] : files_) fs::rename(staging_ + "/" + name, dir_ + "/" + name);
  fs::remove_all(staging_);
  committed_ = true;
}

}  // namespace drillwave::io
