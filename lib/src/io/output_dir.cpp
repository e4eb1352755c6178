#include "drillwave/io/output_dir.hpp"

#include <atomic>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

namespace drillwave::io {

namespace fs = std::filesystem;

namespace {

// Distinguishes staging folders of several OutputDirectory objects alive in one process.
std::atomic<int> staging_counter{0};

// A relative path that stays inside the folder, in one spelling (so "a/./b.csv" and "a/b.csv" are the same file).
std::string CheckedFileName(const std::string& file_name) {
  const fs::path path(file_name);
  bool escapes = path.empty() || path.has_root_path() || !path.has_filename();
  for (const auto& part : path) escapes |= part == "..";
  if (escapes) throw std::invalid_argument("output file name must be a relative path inside the folder: " + file_name);
  return path.lexically_normal().generic_string();
}

}  // namespace

OutputDirectory::OutputDirectory(std::string dir) {
  // "out/", "./out" and "out" name the same folder; its staging folder must be a sibling, never inside it.
  dir_ = fs::absolute(dir).lexically_normal();
  if (!dir_.has_filename()) dir_ = dir_.parent_path();
  if (!dir_.has_filename() || dir_ == dir_.root_path())
    throw std::invalid_argument("not a usable output folder: " + dir);
  std::error_code error;
  if (fs::exists(dir_, error) && !fs::is_directory(dir_, error))
    throw std::runtime_error("output folder " + dir_.string() + " exists and is not a folder");

  const fs::path parent = dir_.parent_path();
  for (fs::path p = parent; !p.empty() && !fs::exists(p, error) && p != p.root_path(); p = p.parent_path())
    created_parents_.push_back(p);
  staging_ = parent / ("." + dir_.filename().string() + ".staging-" + std::to_string(::getpid()) + "-" +
                       std::to_string(staging_counter++));
  fs::create_directories(parent, error);
  if (!error) fs::remove_all(staging_, error);  // left over by a killed process that had the same pid
  if (!error) fs::create_directory(staging_, error);
  if (error) {
    for (const fs::path& p : created_parents_) fs::remove(p, error);
    throw std::runtime_error("cannot create the staging folder " + staging_.string() + ": " + error.message());
  }
}

OutputDirectory::~OutputDirectory() {
  files_.clear();  // closes the streams before their files are removed
  if (committed_) return;
  std::error_code ignored;  // a destructor must not throw; there is nothing better to do than try
  fs::remove_all(staging_, ignored);
  for (const fs::path& p : created_parents_) fs::remove(p, ignored);  // only removes them if still empty
}

std::ostream& OutputDirectory::Open(const std::string& file_name) {
  if (committed_) throw std::logic_error("OutputDirectory::Open(" + file_name + ") after Commit()");
  const std::string name = CheckedFileName(file_name);
  if (files_.count(name)) throw std::invalid_argument("output file " + name + " opened twice");
  const fs::path path = staging_ / name;
  std::error_code error;
  fs::create_directories(path.parent_path(), error);
  auto file = std::make_unique<std::ofstream>(path, std::ios::binary);
  if (error || !*file) throw std::runtime_error("cannot create " + path.string());
  return *(files_[name] = std::move(file));
}

void OutputDirectory::Commit() {
  if (committed_) throw std::logic_error("OutputDirectory::Commit() called twice");
  for (auto& [name, file] : files_) {
    file->close();  // flushes
    if (!*file) throw std::runtime_error("writing " + PathOf(name) + " failed (disk full?)");
  }
  std::error_code error;
  if (!fs::exists(dir_, error)) {
    fs::rename(staging_, dir_, error);  // the whole folder appears at once
    if (!error) {
      committed_ = true;
      return;
    }
    // Someone created dir_ meanwhile: fall back to moving the files one by one.
  }
  fs::create_directories(dir_);
  for (const auto& entry : files_) {
    const fs::path target = dir_ / entry.first;
    fs::create_directories(target.parent_path());
    fs::rename(staging_ / entry.first, target);  // replaces a file of the same name
  }
  committed_ = true;
  fs::remove_all(staging_, error);
}

std::string OutputDirectory::PathOf(const std::string& file_name) const { return (dir_ / file_name).string(); }

}  // namespace drillwave::io
