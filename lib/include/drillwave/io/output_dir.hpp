#pragma once
// Results are written all or nothing, so a failed or interrupted run never leaves a half-written folder that looks
// like a finished one.
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace drillwave::io {

// Files opened here are written into a hidden staging folder beside `dir` (".<name>.staging-<pid>-<n>", on the same
// file system, so moving them is a rename) and moved into `dir` by Commit(). If Commit() is never reached, e.g.
// because an exception unwinds past this object, the destructor removes the staging folder and any parent folders
// it had to create, leaving `dir` as it was; if `dir` did not exist, it still does not.
//
//   OutputDirectory out("results/run1");
//   WriteCsv(out.Open("trajectory.csv"), header, columns);
//   out.Open("summary.json") << summary.dump(2);
//   out.Commit();
class OutputDirectory {
 public:
  // Creates the staging folder. Throws std::runtime_error if `dir` exists but is not a folder, or the staging
  // folder cannot be created.
  explicit OutputDirectory(std::string dir);
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  // A new file in the staging folder, valid until Commit() or destruction. `file_name` is relative and may contain
  // subfolders ("figures/a.svg"). Throws std::invalid_argument for absolute names, "..", or a name opened twice;
  // std::logic_error after Commit(); std::runtime_error if the file cannot be created.
  std::ostream& Open(const std::string& file_name);

  // Flushes and closes every file (std::runtime_error if any write failed, leaving `dir` untouched), then moves
  // them into `dir`, creating it and replacing files of the same name. If `dir` did not exist the whole staging
  // folder is renamed into place in one step; otherwise files are moved one by one, each move atomic.
  void Commit();

  // Where `file_name` ends up after Commit().
  std::string PathOf(const std::string& file_name) const;

 private:
  std::filesystem::path dir_;      // absolute, normalised
  std::filesystem::path staging_;  // sibling of dir_
  std::vector<std::filesystem::path> created_parents_;  // parents of dir_ we created, deepest first
  std::map<std::string, std::unique_ptr<std::ofstream>> files_;
  bool committed_ = false;
};

}  // namespace drillwave::io
