#include "drillwave/io/output_dir.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <set>
#include <stdexcept>
#include <system_error>
#include <thread>

#include <fcntl.h>
#include <pthread.h>
#include <sys/stat.h>
#include <signal.h>
#include <unistd.h>

#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"

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
const char kMarkerText[] = "written by drillwave; the whole folder is replaced by the next run into it\n";
const char kMarkerListing[] = "files:";

// Names drillwave's commands write, so that a folder written before the marker listed its files can still be
// replaced (plain files at its top level only).
bool IsOutputName(const std::string& name) {
  static const std::set<std::string> names = {
      kMarker,         "trajectory.csv",  "summary.json",  "plot.svg",         "report.md",        "case.json",
      "sweep.csv",     "bifurcation.svg", "stability.json", "roots.csv",       "stability_map.csv", "stability_map.svg",
      "findings.json", "comparison.json", "fit.json",       "fitted-case.json", "diagnosis.json", "report.html",
      "orbits.csv",    "orbits.svg",      "edge.json",     "edge_run.csv",     "edge.svg",          "prediction.csv",
      "estimate.csv",  "estimate.json"};
  return names.count(name) > 0;
}

// What the marker of `folder` lists: the files written into it and the sub-folders that hold them ("a/b.svg" adds
// "a/b.svg" and the folder "a"). Empty for a folder without a marker or with one written before the marker listed
// files.
struct Listing {
  std::set<std::string> files, folders;
};
Listing ReadListing(const fs::path& folder) {
  Listing listing;
  std::error_code error;
  if (!fs::is_regular_file(fs::symlink_status(folder / kMarker, error))) return listing;
  std::ifstream in(folder / kMarker, std::ios::binary);
  std::string line;
  bool listed = false;
  for (int lines = 0; std::getline(in, line) && lines < 100000; ++lines) {
    if (!listed) {
      listed = line == kMarkerListing;
      continue;
    }
    if (line.empty()) continue;
    listing.files.insert(line);
    for (fs::path p = fs::path(line).parent_path(); !p.empty(); p = p.parent_path())
      listing.folders.insert(p.generic_string());
  }
  return listing;
}

// The entries of `folder` in name order (so that the first foreign one named is always the same).
std::vector<fs::directory_entry> SortedEntries(const fs::path& folder, std::error_code& error) {
  std::vector<fs::directory_entry> entries;
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) entries.push_back(*it);
  std::sort(entries.begin(), entries.end(),
            [](const auto& a, const auto& b) { return a.path().filename() < b.path().filename(); });
  return entries;
}

// The first entry under `folder` (relative to the output folder: `prefix` + name) that drillwave did not write, with
// what it is ("the sub-folder ...", "the symbolic link ...", "..."); empty if there is none. `error` is set if a
// folder cannot be read.
std::string FirstForeignEntry(const fs::path& folder, const std::string& prefix, const Listing& listing,
                              std::error_code& error) {
  for (const fs::directory_entry& entry : SortedEntries(folder, error)) {
    const std::string name = entry.path().filename().string();
    const std::string relative = prefix + name;
    std::error_code status_error;
    const fs::file_status status = fs::symlink_status(entry.path(), status_error);
    const std::string shown = "\"" + ReadableText(relative) + "\"";
    if (fs::is_symlink(status)) return "the symbolic link " + shown;
    if (fs::is_directory(status)) {
      if (!listing.folders.count(relative)) return "the sub-folder \"" + ReadableText(relative) + "/\"";
      const std::string inside = FirstForeignEntry(entry.path(), relative + "/", listing, error);
      if (!inside.empty() || error) return inside;
      continue;
    }
    if (!fs::is_regular_file(status)) return shown + " (neither a plain file nor a folder)";
    if (listing.files.count(relative) || (prefix.empty() && IsOutputName(name))) continue;
    return shown;
  }
  return "";
}

// Whether this process may create and remove entries in `folder`; the cause otherwise.
bool MayWriteIn(const fs::path& folder, std::string& cause) {
  if (::faccessat(AT_FDCWD, folder.c_str(), W_OK | X_OK, AT_EACCESS) == 0) return true;
  cause = std::strerror(errno);
  return false;
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
  if (dir.empty()) throw ParameterError("out", "empty folder name; expected the path of an output folder");
  fs::path path = fs::absolute(dir).lexically_normal();
  if (!path.has_filename()) path = path.parent_path();
  if (!path.has_filename() || path == path.root_path())
    throw ParameterError("out", "not a usable output folder: " + ReadableText(dir));
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

// An output file that remembers why its writing failed (errno of the first failed write), which std::ofstream
// forgets: a full disk is then reported as "No space left on device" on the file that hit it.
class OutputFile : public std::ostream {
 public:
  OutputFile(const fs::path& path, std::atomic<int>* failures) : std::ostream(nullptr), buffer_(failures) {
    buffer_.fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (buffer_.fd < 0) buffer_.Fail(errno);
    rdbuf(&buffer_);
    if (buffer_.fd < 0) setstate(std::ios::badbit);
  }
  ~OutputFile() override { Close(); }

  // Flushes and closes; false if anything failed since the file was opened.
  bool Close() {
    if (buffer_.fd >= 0) {
      buffer_.Drain();
      if (::close(buffer_.fd) != 0) buffer_.Fail(errno);
      buffer_.fd = -1;
    }
    if (buffer_.error != 0) setstate(std::ios::badbit);
    return buffer_.error == 0;
  }
  int error() const { return buffer_.error; }  // errno of the first failure, 0 if none
  int order() const { return buffer_.order; }  // when it failed among the folder's files (smaller: earlier)

 private:
  struct Buffer : std::streambuf {
    explicit Buffer(std::atomic<int>* failures) : failures(failures) { setp(data, data + sizeof data); }
    int fd = -1, error = 0, order = 0;
    std::atomic<int>* failures;
    char data[1 << 16];

    void Fail(int code) {
      if (error != 0) return;
      error = code != 0 ? code : EIO;
      order = (*failures)++;
    }
    // Writes what is buffered; false (and nothing more is written) once a write failed.
    bool Drain() {
      const char* p = pbase();
      while (error == 0 && p < pptr()) {
        const ssize_t n = ::write(fd, p, static_cast<std::size_t>(pptr() - p));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) Fail(n < 0 ? errno : EIO);
        else p += n;
      }
      setp(data, data + sizeof data);
      return error == 0;
    }
    int_type overflow(int_type c) override {
      if (fd < 0 || !Drain()) return traits_type::eof();
      if (!traits_type::eq_int_type(c, traits_type::eof())) {
        *pptr() = traits_type::to_char_type(c);
        pbump(1);
      }
      return traits_type::not_eof(c);
    }
    int sync() override { return fd >= 0 && Drain() ? 0 : -1; }
  };
  Buffer buffer_;
};

namespace {

// "No space left on device" and the like, for a message.
std::string Cause(int error) { return std::strerror(error); }

// Folders that passed CheckReplaceable (before the work), until an OutputDirectory for them is made (after it): if
// the folder fails the check then, it changed while we worked.
std::set<fs::path>& CheckedBeforeTheWork() {
  static std::set<fs::path> checked;
  return checked;
}

// OutputDirectory::CheckReplaceable's checks of the normalised folder `path`.
void CheckFolder(const fs::path& path) {
  std::error_code error;
  const fs::file_status link_status = fs::symlink_status(path, error);
  if (fs::is_symlink(link_status)) {
    const fs::path target = fs::read_symlink(path, error);
    throw ParameterError("out", path.string() + " is a symbolic link (to " + ReadableText(target.string(), 200) +
                                  "); drillwave replaces its output folder as a whole and neither replaces a link "
                                  "nor writes through one: give the folder itself or a new name");
  }
  std::string cause;
  if (!fs::exists(link_status)) {
    // Where the folder will be created: the nearest existing folder above it must be a folder we may write in.
    fs::path above = path.parent_path();
    while (above.has_relative_path() && !fs::exists(fs::status(above, error))) above = above.parent_path();
    if (!fs::is_directory(fs::status(above, error)))
      throw ParameterError("out", "cannot create " + path.string() + ": " + above.string() + " is not a folder");
    if (!MayWriteIn(above, cause))
      throw ParameterError("out", "cannot create " + path.string() + ": the folder " + above.string() +
                                    " is not writable (" + cause + ")");
    return;
  }
  if (!fs::is_directory(link_status))
    throw ParameterError("out", path.string() + " exists and is not a folder");
  const std::string foreign = FirstForeignEntry(path, "", ReadListing(path), error);
  if (error) throw ParameterError("out", "cannot read the folder " + path.string() + ": " + error.message());
  if (!foreign.empty())
    throw ParameterError("out", path.string() + " holds " + foreign +
                                  ", which drillwave did not write; outputs replace the whole folder, so choose a "
                                  "new or empty folder (or one drillwave wrote)");
  // The new folder is staged beside the old one and swapped in by a rename in the parent; the old one's files are
  // removed after.
  if (!MayWriteIn(path.parent_path(), cause))
    throw ParameterError("out", "cannot replace " + path.string() + ": its parent folder " +
                                  path.parent_path().string() + " is not writable (" + cause + ")");
  if (!MayWriteIn(path, cause))
    throw ParameterError("out", "cannot replace " + path.string() + ": the folder is not writable (" + cause +
                                  "), so its old files could not be removed");
}

}  // namespace

void OutputDirectory::CheckFreeSpace(const std::string& dir, double estimated_bytes) {
  std::error_code ec;
  fs::path existing = fs::absolute(dir, ec);
  while (!existing.empty() && !fs::exists(existing, ec) && existing.has_parent_path() && existing != existing.parent_path())
    existing = existing.parent_path();
  const fs::space_info space = fs::space(existing, ec);
  if (ec || space.available == static_cast<std::uintmax_t>(-1)) return;
  const auto available = static_cast<double>(space.available);
  if (available >= estimated_bytes) return;
  auto megabytes = [](double bytes) { return Significant(bytes / 1e6, 3) + " MB"; };
  throw OutputError("about " + megabytes(estimated_bytes) + " of outputs for " + dir + ", but only " +
                    megabytes(available) + " free on the file system of " + existing.string() +
                    ": free some space, write elsewhere (-o), or ask for fewer samples (a longer output interval)");
}

void OutputDirectory::CheckReplaceable(const std::string& dir) {
  const fs::path path = NormalisedFolder(dir);
  CheckFolder(path);
  std::lock_guard<std::mutex> lock(registry_mutex);
  CheckedBeforeTheWork().insert(path);
}

OutputDirectory::OutputDirectory(std::string dir) {
  // "out/", "./out" and "out" name the same folder; its staging folder must be a sibling, never inside it.
  dir_ = NormalisedFolder(dir);
  bool checked_before_the_work;
  {
    std::lock_guard<std::mutex> lock(registry_mutex);
    checked_before_the_work = CheckedBeforeTheWork().erase(dir_) > 0;
  }
  CheckAgain(checked_before_the_work);

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
    throw OutputError("cannot create the staging folder " + staging_.string() + " for " + dir_.string() + ": " +
                      error.message());
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
  if (error) throw OutputError("cannot create the folder for " + PathOf(name) + " (in " + staging_.string() + "): " +
                               error.message());
  auto file = std::make_unique<OutputFile>(path, &failures_);
  if (file->error() != 0)
    throw OutputError("cannot create " + PathOf(name) + " (in " + staging_.string() + "): " + Cause(file->error()));
  return *(files_[name] = std::move(file));
}

void OutputDirectory::Commit() {
  if (committed_) throw std::logic_error("OutputDirectory::Commit() called twice");
  {
    std::ostream& marker = Open(kMarker);
    marker << kMarkerText << kMarkerListing << "\n";
    for (const auto& item : files_)
      if (item.first != kMarker && item.first.find('\n') == std::string::npos) marker << item.first << "\n";
  }
  // Every file is closed; the one that failed first is named (a full disk fails every file written after it).
  const std::string* failed = nullptr;
  const OutputFile* failed_file = nullptr;
  for (auto& [name, file] : files_) {
    if (file->Close() || (failed_file && failed_file->order() <= file->order())) continue;
    failed = &name;
    failed_file = file.get();
  }
  if (failed_file)
    throw OutputError("cannot write " + PathOf(*failed) + ": " + Cause(failed_file->error()) +
                      "; nothing was changed in " + dir_.string());
  CheckAgain(true);  // someone may have put a file there, or made the parent read-only, since the constructor
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
      fs::rename(dir_, old, error);
      if (error) throw OutputError("cannot move " + dir_.string() + " aside to replace it: " + error.message());
      fs::rename(staging_, dir_, error);
      if (error) {
        std::error_code ignored;  // the first error is the one to report
        fs::rename(old, dir_, ignored);
        throw OutputError("cannot move " + staging_.string() + " to " + dir_.string() + ": " + error.message());
      }
      fs::rename(old, staging_, error);  // removed below as the staging folder, or here if it cannot be moved
      if (error) fs::remove_all(old, error);
    } else {
      throw OutputError("cannot replace " + dir_.string() + " by " + staging_.string() + ": " +
                        std::error_code(errno, std::generic_category()).message());
    }
  }
  committed_ = true;
  lock.unlock();
  fs::remove_all(staging_, error);  // the old folder, if there was one
  std::lock_guard<std::mutex> relock(registry_mutex);
  Registry().erase(staging_);
}

void OutputDirectory::CheckAgain(bool passed_before) const {
  try {
    CheckFolder(dir_);
  } catch (const InputError& e) {
    // A folder that passed the check and fails it now was changed meanwhile (a file put there, the parent made
    // read-only): the environment kept the outputs from being written (exit 5), not bad input.
    if (!passed_before) throw;
    throw OutputError(std::string(e.what()) + " (found after the work: the folder or its parent changed meanwhile); "
                      "nothing was changed in " + dir_.string());
  }
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
