// io/csv: the exact written format, round trips with NaN, bad rows named by file and line, and reading speed.
#include "drillwave/io/csv.hpp"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
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

// A flag has nothing out of range: CsvOptions are valid either way (core/validity.hpp's common contract).
TEST(CsvOptions, AreValidEitherWay) {
  std::string error;
  EXPECT_TRUE(CsvOptions{}.IsValid(&error));
  EXPECT_TRUE(CsvOptions{true}.IsValid(&error));
  EXPECT_EQ(error, "");
}

TEST(WriteCsv, WritesHeaderAndTenSignificantDigits) {
  std::ostringstream out;
  WriteCsv(out, {"time_s", "v"},
           {{0.0, 0.5, 1e-12}, {1.234567890123, std::nan(""), -std::numeric_limits<double>::infinity()}});
  EXPECT_EQ(out.str(), "time_s,v\n0,1.23456789\n0.5,nan\n1e-12,-inf\n");
}

// The formatting WriteCsv had before std::to_chars (issue 40), which it must keep byte for byte.
std::string PrintfText(double v) {
  if (std::isnan(v)) return "nan";
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

std::string CsvText(double v) {
  std::string text;
  AppendCsvNumber(text, v);
  return text;
}

TEST(AppendCsvNumber, IsPrintfsTextOnTrickyValues) {
  using limits = std::numeric_limits<double>;
  const double tricky[] = {
      0.0, -0.0, 1e-300, -1e-300, 1e300, -1e300, limits::denorm_min(), limits::min(), limits::max(), -limits::max(),
      limits::infinity(), -limits::infinity(), 0.1, -0.1, 1.0 / 3, 2.0 / 3, 123456789.123456789, 1e-5, 1e-4,
      9.99999999995e-5,                           // rounds up into fixed notation's range
      1e9, 1e10, 9999999999.4, 9999999999.5,       // fixed up to 10 digits; the last rounds up to 1e+10
      123456789.25, 123456789.75, 1234567890.5,    // exact ties, broken to the even digit
      1234567891.5, 12345678905.0, 12345678915.0,  // the same at other places
      0.5, 1.5, 2.5, 9.9999999995, 9.99999999949999, 1e-320, 5e-324, 1e308, 1.7976931348623157e308,
      6.02214076e23, -273.15, 1e21, 1e22, 4.35, 0.3};
  for (const double v : tricky) EXPECT_EQ(CsvText(v), PrintfText(v)) << std::hexfloat << v;
  EXPECT_EQ(CsvText(0.0), "0");
  EXPECT_EQ(CsvText(-0.0), "-0");
  EXPECT_EQ(CsvText(1e-300), "1e-300");
  EXPECT_EQ(CsvText(123456789.123456789), "123456789.1");
  EXPECT_EQ(CsvText(-limits::infinity()), "-inf");
  EXPECT_EQ(CsvText(std::nan("")), "nan");
  EXPECT_EQ(CsvText(-std::nan("")), "nan") << "never -nan";
  std::string row = "a,";
  AppendCsvNumber(row, 0.25);
  EXPECT_EQ(row, "a,0.25") << "appends";
}

TEST(AppendCsvNumber, IsPrintfsTextOnRandomValues) {
  std::mt19937_64 random(40);
  auto expect_same = [](double v) {
    const std::string text = CsvText(v);
    ASSERT_EQ(text, PrintfText(v)) << std::hexfloat << v;
  };
  // Any bit pattern: every exponent, subnormals, infinities and NaNs with any sign and payload.
  for (int i = 0; i < 50000; ++i) {
    const std::uint64_t bits = random();
    double v;
    std::memcpy(&v, &bits, sizeof v);
    expect_same(v);
  }
  // 11-digit integers ending in 5 are exact ties of rounding to 10 digits; scaled by powers of ten, near-ties.
  std::uniform_int_distribution<std::int64_t> tie(1000000000, 9999999999);
  std::uniform_int_distribution<int> exponent(-30, 30);
  for (int i = 0; i < 50000; ++i) {
    const double v = static_cast<double>(10 * tie(random) + 5);
    expect_same(v);
    expect_same(-v * std::pow(10.0, exponent(random)));
  }
  // Binary fractions have exact decimal expansions, some of them ties at the 11th digit.
  std::uniform_int_distribution<std::int64_t> mantissa(1, std::int64_t{1} << 40);
  std::uniform_int_distribution<int> shift(1, 40);
  for (int i = 0; i < 50000; ++i) expect_same(std::ldexp(static_cast<double>(mantissa(random)), -shift(random)));
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
  std::printf("[ measured ] %zu rows read in %.3f s\n", table.Column("e").size(), seconds);  // some 30 ms optimised
}

}  // namespace
}  // namespace drillwave::io
