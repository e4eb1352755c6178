// io/output_dir: results appear all at once on Commit(), and nothing is left behind without it.
#include "drillwave/io/output_dir.hpp"

#include <filesystem>
#include <algorithm>
#include <fstream>
#include <functional>
#include <memory>
#include <iterator>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include "drillwave/core/error.hpp"

namespace drillwave::io {
namespace {

namespace fs = std::filesystem;

std::string Contents(const fs::path& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Each test works in its own empty scratch folder.
class OutputDirectoryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scratch_ = fs::temp_directory_path() /
               ("drillwave-outdir-" + std::to_string(::getpid()) + "-" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(scratch_);
    fs::create_directories(scratch_);
  }
  void TearDown() override { fs::remove_all(scratch_); }

  // Names in the scratch folder, to see that no staging folder is left over.
  std::vector<std::string> Entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(scratch_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path scratch_;
};

TEST_F(OutputDirectoryTest, CommitMovesEveryFileIntoPlace) {
  const fs::path dir = scratch_ / "run";
  {
    OutputDirectory out(dir.string());
    out.Open("trajectory.csv") << "t\n0\n";
    out.Open("summary.json") << "{}";
    out.Open("figures/plot.svg") << "<svg/>";
    EXPECT_FALSE(fs::exists(dir)) << "nothing visible before Commit()";
    out.Commit();
    EXPECT_EQ(out.PathOf("summary.json"), (dir / "summary.json").string());
  }
  EXPECT_EQ(Contents(dir / "trajectory.csv"), "t\n0\n");
  EXPECT_EQ(Contents(dir / "summary.json"), "{}");
  EXPECT_EQ(Contents(dir / "figures/plot.svg"), "<svg/>");
  EXPECT_EQ(Entries(), std::vector<std::string>{"run"});
}

TEST_F(OutputDirectoryTest, WithoutCommitNothingIsLeftBehind) {
  const fs::path dir = scratch_ / "not" / "yet" / "there";
  try {
    OutputDirectory out(dir.string());
    out.Open("trajectory.csv") << "half a file";
    throw std::runtime_error("the integration failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(fs::exists(dir));
  EXPECT_FALSE(fs::exists(scratch_ / "not")) << "parent folders created for the staging folder are removed too";
  EXPECT_TRUE(Entries().empty());
}

TEST_F(OutputDirectoryTest, AnExistingFolderIsUntouchedWithoutCommitAndReplacedAsAWholeWithIt) {
  const fs::path dir = scratch_ / "run";
  fs::create_directories(dir);  // (a sub-folder summary.json/ is refused since issue 41: see below)
  std::ofstream(dir / "trajectory.csv") << "old";
  std::ofstream(dir / "report.md") << "old";
  {
    OutputDirectory out(dir.string());
    out.Open("trajectory.csv") << "new";
  }
  EXPECT_EQ(Contents(dir / "trajectory.csv"), "old");
  EXPECT_EQ(Entries(), std::vector<std::string>{"run"});
  {
    OutputDirectory out(dir.string());
    out.Open("trajectory.csv") << "new";
    out.Open("summary.json") << "{}";
    out.Commit();
  }
  EXPECT_EQ(Contents(dir / "trajectory.csv"), "new");
  EXPECT_EQ(Contents(dir / "summary.json"), "{}");
  EXPECT_FALSE(fs::exists(dir / "report.md")) << "an old file the new run did not write must not stay: no mix";
  EXPECT_EQ(Entries(), std::vector<std::string>{"run"});
}

TEST_F(OutputDirectoryTest, AFolderWithFilesDrillwaveDidNotWriteIsRefusedAndKept) {
  // Replacing the whole folder would delete them, so it is bad input, found before anything is staged.
  const fs::path dir = scratch_ / "run";
  fs::create_directories(dir);
  std::ofstream(dir / "summary.json") << "old";
  std::ofstream(dir / "notes.txt") << "mine";
  try {
    OutputDirectory out(dir.string());
    ADD_FAILURE() << "accepted a folder holding notes.txt";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("notes.txt"), std::string::npos) << e.what();
  }
  EXPECT_THROW(OutputDirectory::CheckReplaceable(dir.string()), InputError);
  EXPECT_EQ(Contents(dir / "notes.txt"), "mine");
  EXPECT_EQ(Contents(dir / "summary.json"), "old");
  EXPECT_EQ(Entries(), std::vector<std::string>{"run"});
  EXPECT_THROW(OutputDirectory(""), InputError);
}

TEST_F(OutputDirectoryTest, ASubFolderIsRefusedEvenWhenNamedLikeAnOutput) {
  // Issue 41: the name check looked at top-level names only, so summary.json/ with the user's files in it was
  // replaced, and the files were gone (exit 0).
  const fs::path dir = scratch_ / "run";
  fs::create_directories(dir / "summary.json");
  std::ofstream(dir / "summary.json" / "mine.txt") << "mine";
  std::ofstream(dir / "trajectory.csv") << "old";
  std::ofstream(dir / "report.md") << "old";
  for (int attempt = 0; attempt < 2; ++attempt) {
    try {
      if (attempt == 0) {
        OutputDirectory::CheckReplaceable(dir.string());
      } else {
        OutputDirectory out(dir.string());
      }
      ADD_FAILURE() << "accepted a folder holding the sub-folder summary.json/";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("the sub-folder \"summary.json/\""), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(Contents(dir / "summary.json" / "mine.txt"), "mine");
  EXPECT_EQ(Contents(dir / "trajectory.csv"), "old");
  fs::remove(dir / "summary.json" / "mine.txt");  // empty, it is still not drillwave's
  EXPECT_THROW(OutputDirectory::CheckReplaceable(dir.string()), InputError);
  EXPECT_EQ(Entries(), std::vector<std::string>{"run"});
}

TEST_F(OutputDirectoryTest, OnlyWhatTheMarkerListsMayBeInSubFoldersAndNoLinkAnywhere) {
  const fs::path dir = scratch_ / "run";
  auto write = [&](const std::string& text) {
    OutputDirectory out(dir.string());
    out.Open("figures/plot.svg") << text;
    out.Open("prediction.csv") << text;
    out.Open("summary.json") << text;
    out.Commit();
  };
  write("first");
  write("second");  // a folder drillwave wrote, sub-folder included, is replaced
  EXPECT_EQ(Contents(dir / "figures" / "plot.svg"), "second");
  std::ofstream(dir / "figures" / "notes.txt") << "mine";  // the user added a file where drillwave writes
  try {
    OutputDirectory::CheckReplaceable(dir.string());
    ADD_FAILURE() << "accepted figures/notes.txt";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("\"figures/notes.txt\""), std::string::npos) << e.what();
  }
  fs::remove(dir / "figures" / "notes.txt");
  std::ofstream(scratch_ / "data.csv") << "the user's data";
  fs::remove(dir / "summary.json");
  fs::create_symlink(scratch_ / "data.csv", dir / "summary.json");  // a link with an output's name
  try {
    OutputDirectory out(dir.string());
    ADD_FAILURE() << "accepted a symbolic link named summary.json";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the symbolic link \"summary.json\""), std::string::npos) << e.what();
  }
  EXPECT_EQ(Contents(scratch_ / "data.csv"), "the user's data");
}

TEST_F(OutputDirectoryTest, ASymbolicLinkAsTheFolderIsRefusedAndLeftAsItIs) {
  // Documented choice (README, Exit codes): a link is neither replaced by a real folder (what it did, undocumented)
  // nor written through (what the first version did).
  const fs::path target = scratch_ / "target", link = scratch_ / "link";
  {
    OutputDirectory out(target.string());
    out.Open("summary.json") << "old";
    out.Commit();
  }
  fs::create_directory_symlink(target, link);
  for (const fs::path& dir : {link, fs::path(link.string() + "/")}) {
    try {
      OutputDirectory out(dir.string());
      ADD_FAILURE() << "accepted the symbolic link " << dir;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("is a symbolic link (to " + target.string() + ")"), std::string::npos)
          << e.what();
    }
  }
  fs::create_symlink(scratch_ / "nowhere", scratch_ / "dangling");
  EXPECT_THROW(OutputDirectory::CheckReplaceable((scratch_ / "dangling").string()), InputError);
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(Contents(target / "summary.json"), "old");
  EXPECT_EQ(Entries(), (std::vector<std::string>{"dangling", "link", "target"}));
}

TEST_F(OutputDirectoryTest, AFolderThatCannotBeCreatedIsFoundBeforeAnyWork) {
  std::ofstream(scratch_ / "a-file") << "x";
  try {
    OutputDirectory::CheckReplaceable((scratch_ / "a-file" / "deeper" / "run").string());
    ADD_FAILURE() << "accepted a folder under a file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find((scratch_ / "a-file").string() + " is not a folder"), std::string::npos)
        << e.what();
  }
}

TEST_F(OutputDirectoryTest, AFailedWriteNamesTheFileThatFailedAndWhy) {
  // Issue 41: a full disk named .drillwave-output, and said "disk full?" whatever the cause. A file-size limit in a
  // child process makes the writes fail like a full disk (EFBIG instead of ENOSPC).
  const fs::path dir = scratch_ / "run";
  {
    OutputDirectory out(dir.string());
    out.Open("summary.json") << "old";
    out.Commit();
  }
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  const pid_t child = ::fork();
  if (child == 0) {
    ::close(pipe_fds[0]);
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{16384, 16384};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::string message = "no OutputError";
    try {
      OutputDirectory out(dir.string());
      out.Open("a-small.json") << "{}";
      out.Open("b-large.csv") << std::string(200000, 'x');
      out.Open("c-large.csv") << std::string(200000, 'y');
      out.Commit();
    } catch (const OutputError& e) {
      message = e.what();
    } catch (const std::exception& e) {
      message = std::string("another exception: ") + e.what();
    }
    (void)!::write(pipe_fds[1], message.data(), message.size());
    ::_exit(0);
  }
  ASSERT_GT(child, 0);
  ::close(pipe_fds[1]);
  std::string message;
  char buffer[512];
  for (ssize_t n; (n = ::read(pipe_fds[0], buffer, sizeof buffer)) > 0;) message.append(buffer, n);
  ::close(pipe_fds[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_NE(message.find("cannot write " + (dir / "b-large.csv").string() + ": File too large"), std::string::npos)
      << message;
  EXPECT_EQ(message.find(".drillwave-output"), std::string::npos) << message;
  EXPECT_EQ(Contents(dir / "summary.json"), "old") << "the old folder is kept whole";
  EXPECT_EQ(Entries(), std::vector<std::string>{"run"}) << "no staging folder left";
}

// The message of the OutputError `work` throws; a failure if it throws none.
std::string OutputErrorOf(const std::function<void()>& work) {
  try {
    work();
  } catch (const OutputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no OutputError";
  return "";
}

TEST_F(OutputDirectoryTest, AFolderChangedDuringTheWorkIsAnOutputFailureNotBadInput) {
  // Issue 41: the tool checks the folder before the work (CheckReplaceable), the constructor again after it, and
  // Commit() once more after writing. Failing then is the environment changed meanwhile (OutputError, exit 5), not
  // bad input (exit 2, "checked before any work starts"); the folder is left as it is.
  const fs::path after_the_work = scratch_ / "checked", while_writing = scratch_ / "written";
  OutputDirectory::CheckReplaceable(after_the_work.string());
  for (const fs::path& dir : {after_the_work, while_writing}) {
    const std::string message = OutputErrorOf([&] {
      std::unique_ptr<OutputDirectory> out;
      if (dir == while_writing) out = std::make_unique<OutputDirectory>(dir.string());
      fs::create_directories(dir);
      std::ofstream(dir / "notes.txt") << "mine";
      if (!out) out = std::make_unique<OutputDirectory>(dir.string());
      out->Open("summary.json") << "{}";
      out->Commit();
    });
    EXPECT_NE(message.find(dir.string() + " holds \"notes.txt\""), std::string::npos) << message;
    EXPECT_NE(message.find("found after the work"), std::string::npos) << message;
    EXPECT_EQ(Contents(dir / "notes.txt"), "mine");
  }
  EXPECT_EQ(Entries(), (std::vector<std::string>{"checked", "written"})) << "no staging folder left";
}

TEST_F(OutputDirectoryTest, StagingFoldersOfDeadProcessesAreRemoved) {
  // A child process that exits at once leaves a pid that is no longer alive.
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  int status = 0;
  ::waitpid(child, &status, 0);
  const fs::path stale = scratch_ / (".run.staging-" + std::to_string(child) + "-0");
  const fs::path other = scratch_ / (".other.staging-" + std::to_string(child) + "-3");
  const fs::path alive = scratch_ / (".run.staging-" + std::to_string(::getppid()) + "-0");  // our parent lives
  for (const fs::path& p : {stale, other, alive}) {
    fs::create_directories(p);
    std::ofstream(p / "trajectory.csv") << "half a file";
  }
  {
    OutputDirectory out((scratch_ / "run").string());
    out.Open("a.txt") << "a";
    out.Commit();
  }
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_FALSE(fs::exists(other));
  EXPECT_TRUE(fs::exists(alive)) << "a live process's staging folder is not ours to remove";
  EXPECT_FALSE(fs::exists(scratch_ / "run" / "trajectory.csv"));
}

TEST_F(OutputDirectoryTest, TrailingSlashStagesBesideNotInside) {
  const std::string dir = (scratch_ / "run").string() + "/";
  {
    OutputDirectory out(dir);
    out.Open("a.txt") << "a";
    EXPECT_FALSE(fs::exists(scratch_ / "run"));
  }
  EXPECT_TRUE(Entries().empty());
}

TEST_F(OutputDirectoryTest, TwoWritersToTheSameFolderDoNotClobberEachOther) {
  const fs::path dir = scratch_ / "run";
  OutputDirectory first(dir.string());
  first.Open("a.txt") << "first";
  {
    OutputDirectory second(dir.string());
    second.Open("b.txt") << "second";
  }  // abandoned: must not remove the first writer's staging folder
  first.Commit();
  EXPECT_EQ(Contents(dir / "a.txt"), "first");
  EXPECT_FALSE(fs::exists(dir / "b.txt"));
}

TEST_F(OutputDirectoryTest, RejectsMisuse) {
  std::ofstream(scratch_ / "a-file") << "x";
  EXPECT_THROW(OutputDirectory((scratch_ / "a-file").string()), std::runtime_error);

  OutputDirectory out((scratch_ / "run").string());
  EXPECT_THROW(out.Open("../escape.txt"), std::invalid_argument);
  EXPECT_THROW(out.Open("/tmp/absolute.txt"), std::invalid_argument);
  EXPECT_THROW(out.Open(""), std::invalid_argument);
  out.Open("a.txt") << "a";
  EXPECT_THROW(out.Open("./a.txt"), std::invalid_argument);
  out.Commit();
  EXPECT_THROW(out.Open("b.txt"), std::logic_error);
  EXPECT_THROW(out.Commit(), std::logic_error);
}

// Free space against the outputs' estimate, before any work: more than the file system holds is refused naming both
// sizes and the nearest existing folder (a folder not yet made is judged by its parent's file system); what fits
// passes and nothing is created.
TEST_F(OutputDirectoryTest, OutputsLargerThanTheFreeSpaceAreRefusedBeforeAnyWork) {
  const std::string dir = (scratch_ / "not" / "yet").string();
  const double free_bytes = static_cast<double>(fs::space(scratch_).available);
  EXPECT_NO_THROW(OutputDirectory::CheckFreeSpace(dir, 1e3));
  try {
    OutputDirectory::CheckFreeSpace(dir, 10 * free_bytes + 1e12);
    FAIL() << "not refused";
  } catch (const OutputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("free on the file system of " + scratch_.string()), std::string::npos) << what;
    EXPECT_NE(what.find(" MB of outputs for " + dir), std::string::npos) << what;
  }
  EXPECT_TRUE(Entries().empty());
}

}  // namespace
}  // namespace drillwave::io
