#pragma once
// Results are written all or nothing, so a failed or interrupted run never leaves a half-written folder that looks
// like a finished one, nor a folder that mixes old and new files.
#include <atomic>
#include <filesystem>
#include <fstream>  // not needed here; kept for files that relied on it
#include <map>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace drillwave::io {

// The outputs could not be written after the work was done (disk full, quota, file-size limit, a folder made
// read-only meanwhile): the environment, not the input and not a bug. The message names the file and the cause; the
// output folder is left as it was. The command-line tool exits with 5.
class OutputError : public std::runtime_error {
 public:
  explicit OutputError(const std::string& message) : std::runtime_error(message) {}
};

class OutputFile;

// Files opened here are written into a hidden staging folder beside `dir` (".<name>.staging-<pid>-<n>", on the same
// file system, so moving it is a rename). Commit() makes the staging folder the new `dir` as a whole: if `dir` did
// not exist the staging folder is renamed into place; if it did, the two are swapped in one atomic rename
// (renameat2 RENAME_EXCHANGE) and the old folder, now under the staging name, is removed. At every instant `dir` is
// the complete old folder or the complete new one. If Commit() is never reached, e.g. because an exception unwinds
// past this object, the destructor removes the staging folder and any parent folders it had to create, leaving
// `dir` as it was; if `dir` did not exist, it still does not.
//
// Because the whole folder is replaced, an existing `dir` must hold nothing but drillwave's outputs (CheckReplaceable):
// nothing a user owns is ever deleted. The marker file every committed folder gets lists the files written into it.
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
  // Creates the staging folder. Throws InputError where CheckReplaceable does, but OutputError (with the same
  // message) for a folder that passed CheckReplaceable since the last OutputDirectory for it (the tool's check before
  // the work), and so changed while drillwave worked; OutputError if the staging folder cannot be created.
  explicit OutputDirectory(std::string dir);
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  // A new file in the staging folder, valid until Commit() or destruction. `file_name` is relative and may contain
  // subfolders ("figures/a.svg"). Throws std::invalid_argument for absolute names, "..", or a name opened twice;
  // std::logic_error after Commit(); OutputError (naming the file and the cause) if the file cannot be created.
  std::ostream& Open(const std::string& file_name);

  // Flushes and closes every file (OutputError naming the first file whose writing failed and why, e.g. "No space
  // left on device", leaving `dir` untouched), checks `dir` again as CheckReplaceable does (OutputError with its
  // message if it changed since the constructor), then replaces `dir` by the staging folder as a whole (see above).
  void Commit();

  // Where `file_name` ends up after Commit().
  std::string PathOf(const std::string& file_name) const;

  // Throws InputError (exit 2 in the tool), naming the folder and the first foreign entry in name order, unless `dir`
  // may be replaced by a new run:
  //  - `dir` is not a symbolic link (a link is refused, never replaced nor written through: the link is the user's,
  //    and the folder behind it may be shared);
  //  - `dir` does not exist yet, and the nearest folder above it that does exist is a folder this process may
  //    write in; or
  //  - `dir` is a folder that this process may write in, in a parent it may write in, and every entry in it is
  //    one drillwave wrote: a file or sub-folder its marker (".drillwave-output") lists, or a plain file at the top
  //    level with the name of a drillwave output (trajectory.csv, summary.json, ...: folders written before the
  //    marker listed its files). Anything else is foreign: a sub-folder the marker does not list (even one named
  //    like an output, "summary.json/"), a symbolic link, a file the marker does not list inside a sub-folder, a
  //    file with another name.
  // The command-line tool calls it before any work starts, so that no run is wasted on a folder it may not replace
  // or cannot write; a folder that passes is remembered until an OutputDirectory for it is made, so that failing
  // the check after the work is told apart (see the constructor).
  static void CheckReplaceable(const std::string& dir);

  // Before the work: OutputError when the file system `dir` would be written on (that of its nearest existing folder)
  // has less free space than `estimated_bytes` and the staging copy need, naming both sizes and the folder. Does
  // nothing where the free space cannot be read.
  static void CheckFreeSpace(const std::string& dir, double estimated_bytes);

 private:
  // CheckReplaceable's checks once more; an InputError becomes an OutputError if `dir` passed them before.
  void CheckAgain(bool passed_before) const;

  std::filesystem::path dir_;      // absolute, normalised
  std::filesystem::path staging_;  // sibling of dir_
  std::vector<std::filesystem::path> created_parents_;  // parents of dir_ we created, deepest first
  std::map<std::string, std::unique_ptr<OutputFile>> files_;
  std::atomic<int> failures_{0};  // numbers the files' first write failures in the order they happened
  bool committed_ = false;
};

// For programs (not libraries): blocks SIGTERM, SIGINT and SIGHUP in the calling thread and the threads it starts
// later, and handles them on a thread of its own that removes every staging folder of this process and exits with
// 128 + the signal's number. Call it at the start of main, before any other thread exists.
void InstallTerminationCleanup();

}  // namespace drillwave::io
