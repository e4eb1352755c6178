#pragma once
// Results are written all or nothing, so a failed or interrupted run never leaves a half-written folder that looks
// like a finished one, nor a folder that mixes old and new files.
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace drillwave::io {

// Files opened here are written into a hidden staging folder beside `dir` (".<name>.staging-<pid>-<n>", on the same
// file system, so moving it is a rename). Commit() makes the staging folder the new `dir` as a whole: if `dir` did
// not exist the staging folder is renamed into place; if it did, the two are swapped in one atomic rename
// (renameat2 RENAME_EXCHANGE) and the old folder, now under the staging name, is removed. At every instant `dir` is
// the complete old folder or the complete new one. If Commit() is never reached, e.g. because an exception unwinds
// past this object, the destructor removes the staging folder and any parent folders it had to create, leaving
// `dir` as it was; if `dir` did not exist, it still does not.
//
// Because the whole folder is replaced, an existing `dir` must hold nothing but drillwave's outputs (CheckReplaceable).
// Staging folders left by processes that no longer exist (killed with SIGKILL) are removed by the next
// OutputDirectory in the same parent folder; InstallTerminationCleanup() removes this process's own on SIGTERM,
// SIGINT and SIGHUP.
//
//   OutputDirectory out("results/run1");
//   WriteCsv(out.Open("trajectory.csv"), header, columns);
//   out.Open("summary.json") << summary.dump(2);
//   out.Commit();
class OutputDirectory {
 public:
  // Creates the staging folder. Throws InputError if `dir` is empty, exists but is not a folder, or holds files
  // drillwave did not write; std::runtime_error if the staging folder cannot be created.
  explicit OutputDirectory(std::string dir);
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  // A new file in the staging folder, valid until Commit() or destruction. `file_name` is relative and may contain
  // subfolders ("figures/a.svg"). Throws std::invalid_argument for absolute names, "..", or a name opened twice;
  // std::logic_error after Commit(); std::runtime_error if the file cannot be created.
  std::ostream& Open(const std::string& file_name);

  // Flushes and closes every file (std::runtime_error if any write failed, leaving `dir` untouched), then replaces
  // `dir` by the staging folder as a whole (see above).
  void Commit();

  // Where `file_name` ends up after Commit().
  std::string PathOf(const std::string& file_name) const;

  // Throws InputError (naming the folder and the first foreign entry) unless `dir` does not exist yet, or is a folder
  // that is empty or holds only drillwave's outputs (a ".drillwave-output" marker, which every committed folder
  // gets, or names drillwave writes such as trajectory.csv and summary.json). The command-line tool calls it before
  // any work starts, so that a run is not wasted on a folder it may not replace.
  static void CheckReplaceable(const std::string& dir);

 private:
  std::filesystem::path dir_;      // absolute, normalised
  std::filesystem::path staging_;  // sibling of dir_
  std::vector<std::filesystem::path> created_parents_;  // parents of dir_ we created, deepest first
  std::map<std::string, std::unique_ptr<std::ofstream>> files_;
  bool committed_ = false;
};

// For programs (not libraries): blocks SIGTERM, SIGINT and SIGHUP in the calling thread and the threads it starts
// later, and handles them on a thread of its own that removes every staging folder of this process and exits with
// 128 + the signal's number. Call it at the start of main, before any other thread exists.
void InstallTerminationCleanup();

}  // namespace drillwave::io
