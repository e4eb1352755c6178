// io/csv: the exact written format, round trips with NaN, bad rows named by file and line, and reading speed.
#include "drillwave/io/csv.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>
#include <unistd.h>

#include "drillwave/core/error.hpp"

namespace drillwave::io {
namespace {

namespace fs = std::filesystem;

// A temporary file removed at the end of the test.
class TempFile {
 public:
  explicit TempFile(const std::string& name)
      : path_((fs::temp_directory_path() / ("drillwave-csv-" + std::to_string(::getpid()) + "-" + name)).string()) {}
  TempFile(const std::string& name, const std::string& text) : TempFile(name) {
    std::ofstream(path_, std::ios::binary) << text;
  }
  ~TempFile() { fs::remove(path_); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

std::string ReadErrorOf(const std::string& path) {
  try {
    ReadCsv(path);
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "");
    return e.what();
  }
  ADD_FAILURE() << "no InputError for " << path;
  return "";
}

TEST(WriteCsv, WritesHeaderAndTenSignificantDigits) {
  std::ostringstream out;
  WriteCsv(out, {"time_s", "v"},
           {{0.0, 0.5, 1e-12}, {1.234567890123, std::nan(""), -std::numeric_limits<double>::infinity()}});
  EXPECT_EQ(out.str(), "time_s,v\n0,1.23456789\n0.5,nan\n1e-12,-inf\n");
}

TEST(WriteCsv, RejectsMismatchedColumns) {
  std::ostringstream out;
  EXPECT_THROW(WriteCsv(out, {"a", "b"}, {{1, 2}, {3}}), std::invalid_argument);
  EXPECT_THROW(WriteCsv(out, {"a"}, {{1}, {2}}), std::invalid_argument);
  EXPECT_THROW(WriteCsv(out, {"a,b"}, {{1}}), std::invalid_argument);
}

TEST(ReadCsv, RoundTripKeepsValuesAndNaN) {
  const TempFile file("round-trip.csv");
  const std::vector<double> t{0, 0.001, 2.5, 1e6};
  const std::vector<double> v{1.25, std::nan(""), -3e-7, 123456.789};
  {
    std::ofstream out(file.path());
    WriteCsv(out, {"time_s", "bit_speed_rad_s"}, {t, v});
  }
  const CsvTable table = ReadCsv(file.path());
  ASSERT_EQ(table.header, (std::vector<std::string>{"time_s", "bit_speed_rad_s"}));
  EXPECT_EQ(table.Column("time_s"), t);
  const std::vector<double>& read = table.Column("bit_speed_rad_s");
  ASSERT_EQ(read.size(), 4u);
  EXPECT_EQ(read[0], 1.25);
  EXPECT_TRUE(std::isnan(read[1]));
  EXPECT_EQ(read[2], -3e-7);
  EXPECT_EQ(read[3], 123456.789);
  EXPECT_THROW(table.Column("no_such_column"), std::out_of_range);
}

TEST(ReadCsv, EmptyFieldsAndNanAreNaN_CrLfAndBlankLinesAccepted) {
  const TempFile file("lenient.csv", "\xEF\xBB\xBF" "a, b ,c\r\n1,,nan\r\n\r\n 2 , 3.5 ,-4\r\n,,");
  const CsvTable table = ReadCsv(file.path());
  ASSERT_EQ(table.header, (std::vector<std::string>{"a", "b", "c"}));
  ASSERT_EQ(table.Column("a").size(), 3u);
  EXPECT_EQ(table.Column("a")[0], 1);
  EXPECT_TRUE(std::isnan(table.Column("b")[0]));
  EXPECT_TRUE(std::isnan(table.Column("c")[0]));
  EXPECT_EQ(table.Column("a")[1], 2);
  EXPECT_EQ(table.Column("b")[1], 3.5);
  EXPECT_EQ(table.Column("c")[1], -4);
  for (const auto& column : table.columns) EXPECT_TRUE(std::isnan(column[2]));
}

TEST(ReadCsv, RaggedRowsNameFileAndLine) {
  const TempFile short_row("short.csv", "a,b\n1,2\n3\n");
  EXPECT_EQ(ReadErrorOf(short_row.path()), short_row.path() + ":3: 1 fields, but the header has 2");
  const TempFile long_row("long.csv", "a,b\n1,2,3\n");
  EXPECT_EQ(ReadErrorOf(long_row.path()), long_row.path() + ":2: 3 fields, but the header has 2");
}

TEST(ReadCsv, BadNumbersNameTheColumn) {
  const TempFile file("bad-number.csv", "a,b\n1,2\n\n3,4x\n");
  EXPECT_EQ(ReadErrorOf(file.path()), file.path() + ":4: column b (2): \"4x\" is not a number");
}

TEST(ReadCsv, MissingOrEmptyFile) {
  EXPECT_NE(ReadErrorOf("/no/such/file.csv").find("cannot open CSV file /no/such/file.csv"), std::string::npos);
  const TempFile empty("empty.csv", "");
  EXPECT_EQ(ReadErrorOf(empty.path()), empty.path() + ":1: no header line");
  EXPECT_EQ(ReadErrorOf(""), "empty file name; expected the path of a CSV file");
}

// Recordings (issue 16): every cell a finite number, named by file, line and column; headers with unique UTF-8 names.
TEST(ReadCsv, FiniteOnlyRejectsBlankAndNonFiniteCellsAndEmptyTables) {
  const CsvOptions strict{true};
  auto error = [&](const std::string& name, const std::string& text) {
    const TempFile file(name, text);
    try {
      ReadCsv(file.path(), strict);
    } catch (const InputError& e) {
      return std::string(e.what()).substr(file.path().size());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error("blank.csv", "t,a\n0,1\n1,\n"), ":3: column a (2): blank cell; every cell must hold a finite number");
  EXPECT_EQ(error("nan.csv", "t,a\n0,nan\n"), ":2: column a (2): \"nan\" is not a finite number");
  EXPECT_EQ(error("inf.csv", "t,a\ninf,1\n"), ":2: column t (1): \"inf\" is not a finite number");
  EXPECT_EQ(error("overflow.csv", "t,a\n0,1e999\n"), ":2: column a (2): \"1e999\" is not a finite number");
  EXPECT_EQ(error("header-only.csv", "t,a\n"), ":2: no data rows below the header");
  const TempFile good("good.csv", "t,a\n0,1\n1,2\n");
  EXPECT_EQ(ReadCsv(good.path(), strict).Column("a")[1], 2);
}

TEST(ReadCsv, HeaderNamesMustBeUniqueNonEmptyUtf8) {
  const TempFile dup("dup.csv", "t,a,a\n0,1,2\n");
  EXPECT_EQ(ReadErrorOf(dup.path()), dup.path() + ":1: columns 2 and 3 are both named \"a\"; names must be unique");
  const TempFile latin1("latin1.csv", "t,caf\xE9\n0,1\n");
  EXPECT_EQ(ReadErrorOf(latin1.path()), latin1.path() + ":1: column 2 of the header (\"caf\\xE9\") has a byte that is "
                                                        "not UTF-8 at byte 4; channel names must be UTF-8 text");
  const TempFile unnamed("unnamed.csv", "t,,b\n0,1,2\n");
  EXPECT_EQ(ReadErrorOf(unnamed.path()), unnamed.path() + ":1: column 2 of the header has no name");
}

TEST(ReadCsv, HundredThousandRowsAreFast) {
  const TempFile file("large.csv");
  constexpr std::size_t kRows = 100000;
  std::vector<std::vector<double>> columns(4, std::vector<double>(kRows));
  for (std::size_t i = 0; i < kRows; ++i) {
    columns[0][i] = 1e-3 * static_cast<double>(i);
    columns[1][i] = std::sin(columns[0][i]);
    columns[2][i] = -1e5 * std::cos(columns[0][i]);
    columns[3][i] = i % 1000 == 0 ? std::nan("") : std::exp(-columns[0][i]);
  }
  {
    std::ofstream out(file.path());
    WriteCsv(out, {"t", "s", "c", "e"}, columns);
  }
  const auto start = std::chrono::steady_clock::now();
  const CsvTable table = ReadCsv(file.path());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(table.Column("e").size(), kRows);
  EXPECT_NEAR(table.Column("s")[54321], columns[1][54321], 1e-9);
  EXPECT_TRUE(std::isnan(table.Column("e")[5000]));
  // Some 30 ms when optimised; the bound only catches pathological parsing, even in unoptimised builds.
  EXPECT_LT(seconds, 2.0);
}

}  // namespace
}  // namespace drillwave::io
