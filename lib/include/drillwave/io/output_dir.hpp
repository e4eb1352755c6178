#pragma once
// Results are written all or nothing: files go to a staging folder and are moved into place by Commit(). If Commit()
// is never reached (an exception), the staging folder is removed and the output folder is left as it was.
#include <fstream>
#include <map>
#include <memory>
#include <string>

namespace drillwave::io {

class OutputDirectory {
 public:
  explicit OutputDirectory(std::string dir);
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  std::ostream& Open(const std::string& file_name);  // a new file in the staging folder
  void Commit();
  std::string PathOf(const std::string& file_name) const { return dir_ + "/" + file_name; }

 private:
  std::string dir_, staging_;
  std::map<std::string, std::unique_ptr<std::ofstream>> files_;
  bool committed_ = false;
};

}  // namespace drillwave::io
