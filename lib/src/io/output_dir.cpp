#include "drillwave/io/output_dir.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <mutex>
#include <set>
#include <stdexcept>
#include <system_error>
#include <thread>

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include "drillwave/core/error.hpp"

namespace drillwave::io {

namespace fs = std::filesystem;

namespace {

// Distinguishes staging folders of several OutputDirectory objects alive in one process.
std::atomic<int> staging_counter{0};

// The staging folders of this process that are not committed yet: what the termination handler removes. The mutex
// also keeps the handler from removing a folder while a file is being created in it or while it is swapped in.
std::mutex registry_mutex;
std::set<fs::path>& Registry() {
  static std::set<fs::path> registry;
  return registry;
}

const char kMarker[] = ".drillwave-output";

// Names drillwave's commands write, so that a folder written before the marker existed can still be replaced.
bool IsOutputName(const std::string& name) {
  static const std::set<std::string> names = {
      kMarker,         "trajectory.csv",  "summary.json",  "plot.svg",         "report.md",        "case.json",
      "sweep.csv",     "bifurcation.svg", "stability.json", "roots.csv",       "stability_map.csv", "stability_map.svg",
      "findings.json", "comparison.json", "fit.json",       "fitted-case.json", "diagnosis.json", "report.html",
      "orbits.csv",    "orbits.svg",      "edge.json",     "edge_run.csv",     "edge.svg"};
  return names.count(name) > 0;
}

// A relative path that stays inside the folder, in one spelling (so "a/./b.csv" and "a/b.csv" are the same file).
std::string CheckedFileName(const std::string& file_name) {
  const fs::path path(file_name);
  bool escapes = path.empty() || path.has_root_path() || !path.has_filename();
  for (const auto& part : path) escapes |= part == "..";
  if (escapes) throw std::invalid_argument("output file name must be a relative path inside the folder: " + file_name);
  return path.lexically_normal().generic_string();
}

fs::path NormalisedFolder(const std::string& dir) {
  if (dir.empty()) throw InputError("--out", "empty folder name; expected the path of an output folder");
  fs::path path = fs::absolute(dir).lexically_normal();
  if (!path.has_filename()) path = path.parent_path();
  if (!path.has_filename() || path == path.root_path())
    throw InputError("--out", "not a usable output folder: " + ReadableText(dir));
  return path;
}

// The pid in ".<name>.staging-<pid>-<n>", or 0 if `name` is not a staging folder's name.
pid_t StagingPid(const std::string& name) {
  const std::size_t mark = name.rfind(".staging-");
  if (name.empty() || name[0] != '.' || mark == std::string::npos || mark == 0) return 0;
  unsigned long pid = 0;
  int n = 0, used = 0;
  if (std::sscanf(name.c_str() + mark, ".staging-%lu-%d%n", &pid, &n, &used) != 2) return 0;
  if (name.c_str()[mark + static_cast<std::size_t>(used)] != '\0') return 0;
  return static_cast<pid_t>(pid);
}

// Removes the staging folders in `parent` whose process is gone (killed before it could clean up), and this
// process's own that no live OutputDirectory owns (left by an earlier process with the same pid).
void RemoveStaleStaging(const fs::path& parent) {
  std::error_code error;
  std::vector<fs::path> stale;
  for (fs::directory_iterator it(parent, error), end; !error && it != end; it.increment(error)) {
    const pid_t pid = StagingPid(it->path().filename().string());
    if (pid <= 0) continue;
    bool dead;
    if (pid == ::getpid()) {
      std::lock_guard<std::mutex> lock(registry_mutex);
      dead = Registry().count(it->path()) == 0;
    } else {
      dead = ::kill(pid, 0) != 0 && errno == ESRCH;
    }
    if (dead) stale.push_back(it->path());
  }
  for (const fs::path& p : stale) fs::remove_all(p, error);
}

// Swaps two existing paths in one step. False (errno set) where the file system cannot (then nothing changed).
bool ExchangePaths(const fs::path& a, const fs::path& b) {
#if defined(__linux__) && defined(RENAME_EXCHANGE)
  return ::renameat2(AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), RENAME_EXCHANGE) == 0;
#else
  errno = EINVAL;
  return false;
#endif
}

}  // namespace

void OutputDirectory::CheckReplaceable(const std::string& dir) {
  const fs::path path = NormalisedFolder(dir);
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) return;
  if (!fs::is_directory(status))
    throw InputError("--out", path.string() + " exists and is not a folder");
  for (fs::directory_iterator it(path, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (!IsOutputName(name))
      throw InputError("--out", path.string() + " holds \"" + ReadableText(name) +
                                    "\", which drillwave did not write; outputs replace the whole folder, so "
                                    "choose a new or empty folder (or one drillwave wrote)");
  }
  if (error) throw InputError("--out", "cannot read the folder " + path.string() + ": " + error.message());
}

OutputDirectory::OutputDirectory(std::string dir) {
  // "out/", "./out" and "out" name the same folder; its staging folder must be a sibling, never inside it.
  dir_ = NormalisedFolder(dir);
  CheckReplaceable(dir_.string());

  std::error_code error;
  const fs::path parent = dir_.parent_path();
  for (fs::path p = parent; !p.empty() && !fs::exists(p, error) && p != p.root_path(); p = p.parent_path())
    created_parents_.push_back(p);
  staging_ = parent / ("." + dir_.filename().string() + ".staging-" + std::to_string(::getpid()) + "-" +
                       std::to_string(staging_counter++));
  fs::create_directories(parent, error);
  if (!error) RemoveStaleStaging(parent);
  if (!error) fs::remove_all(staging_, error);  // left over by a killed process that had the same pid
  if (!error) {
    std::lock_guard<std::mutex> lock(registry_mutex);
    fs::create_directory(staging_, error);
    if (!error) Registry().insert(staging_);
  }
  if (error) {
    for (const fs::path& p : created_parents_) fs::remove(p, error);
    throw std::runtime_error("cannot create the staging folder " + staging_.string() + ": " + error.message());
  }
}

OutputDirectory::~OutputDirectory() {
  files_.clear();  // closes the streams before their files are removed
  if (committed_) return;
  std::error_code ignored;  // a destructor must not throw; there is nothing better to do than try
  {
    std::lock_guard<std::mutex> lock(registry_mutex);
    fs::remove_all(staging_, ignored);
    Registry().erase(staging_);
  }
  for (const fs::path& p : created_parents_) fs::remove(p, ignored);  // only removes them if still empty
}

std::ostream& OutputDirectory::Open(const std::string& file_name) {
  if (committed_) throw std::logic_error("OutputDirectory::Open(" + file_name + ") after Commit()");
  const std::string name = CheckedFileName(file_name);
  if (files_.count(name)) throw std::invalid_argument("output file " + name + " opened twice");
  const fs::path path = staging_ / name;
  std::error_code error;
  std::lock_guard<std::mutex> lock(registry_mutex);
  fs::create_directories(path.parent_path(), error);
  auto file = std::make_unique<std::ofstream>(path, std::ios::binary);
  if (error || !*file) throw std::runtime_error("cannot create " + path.string());
  return *(files_[name] = std::move(file));
}

void OutputDirectory::Commit() {
  if (committed_) throw std::logic_error("OutputDirectory::Commit() called twice");
  Open(kMarker) << "written by drillwave; the whole folder is replaced by the next run into it\n";
  for (auto& [name, file] : files_) {
    file->close();  // flushes
    if (!*file) throw std::runtime_error("writing " + PathOf(name) + " failed (disk full?)");
  }
  CheckReplaceable(dir_.string());  // again: someone may have put a file there while we worked
  std::error_code error;
  std::unique_lock<std::mutex> lock(registry_mutex);
  fs::rename(staging_, dir_, error);  // dir_ does not exist (or is an empty folder): the new one appears at once
  if (error) {
    error.clear();
    if (ExchangePaths(staging_, dir_)) {
      // dir_ is the new folder; the old one is under the staging name, still registered, so a termination signal
      // from here on removes it too.
    } else if (errno == EINVAL || errno == ENOSYS || errno == ENOTSUP) {
      // A file system without an atomic exchange: two renames, with the old folder put back if the second fails.
      // Only between the two is dir_ missing (never mixed).
      const fs::path old = staging_.string() + "-old";
      fs::rename(dir_, old);
      fs::rename(staging_, dir_, error);
      if (error) {
        fs::rename(old, dir_);
        throw std::runtime_error("cannot move " + staging_.string() + " to " + dir_.string() + ": " + error.message());
      }
      fs::rename(old, staging_);
    } else {
      throw std::runtime_error("cannot replace " + dir_.string() + " by " + staging_.string() + ": " +
                               std::error_code(errno, std::generic_category()).message());
    }
  }
  committed_ = true;
  lock.unlock();
  fs::remove_all(staging_, error);  // the old folder, if there was one
  std::lock_guard<std::mutex> relock(registry_mutex);
  Registry().erase(staging_);
}

std::string OutputDirectory::PathOf(const std::string& file_name) const { return (dir_ / file_name).string(); }

void InstallTerminationCleanup() {
  static std::once_flag once;
  std::call_once(once, [] {
    sigset_t signals;
    sigemptyset(&signals);
    for (int s : {SIGTERM, SIGINT, SIGHUP}) sigaddset(&signals, s);
    pthread_sigmask(SIG_BLOCK, &signals, nullptr);
    std::thread([signals] {
      int signal = 0;
      if (sigwait(&signals, &signal) != 0) return;
      registry_mutex.lock();  // held until _exit: no file is created and no folder swapped in from here on
      std::error_code ignored;
      for (const fs::path& p : Registry()) fs::remove_all(p, ignored);
      std::fprintf(stderr, "drillwave: terminated by signal %d; unfinished outputs removed\n", signal);
      ::_exit(128 + signal);
    }).detach();
  });
}

}  // namespace drillwave::io
