// The error types' contract: where, what, and the parameters a message advises; and the library's messages name its
// parameters, never a front end's flags (the command-line tool maps them, tests/apps/error_policy_test.cpp).
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/core/error.hpp"

namespace drillwave {
namespace {

TEST(InputError, KeepsItsLocationMessageAndTheParametersItAdvises) {
  const InputError e("/model/bit/inertia_kgm2", "2 s simulated is too long; raise max_samples", {"max_samples"});
  EXPECT_STREQ(e.what(), "/model/bit/inertia_kgm2: 2 s simulated is too long; raise max_samples");
  EXPECT_EQ(e.json_path(), "/model/bit/inertia_kgm2");
  EXPECT_EQ(e.message(), "2 s simulated is too long; raise max_samples");
  EXPECT_EQ(e.mentioned_parameters(), std::vector<std::string>{"max_samples"});
  EXPECT_STREQ(InputError("", "alone").what(), "alone");
}

TEST(ParameterError, IsAnInputErrorNamingTheParameter) {
  try {
    throw ParameterError("draw_count", "expected a whole number in [0, 100000]");
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "draw_count: expected a whole number in [0, 100000]");
    ASSERT_NE(dynamic_cast<const ParameterError*>(&e), nullptr);
    EXPECT_EQ(dynamic_cast<const ParameterError&>(e).parameter(), "draw_count");
  }
}

// A flag in a library message speaks to one front end only: Python's users set max_samples=, not --max-samples.
TEST(LibraryMessages, NameNoCommandLineFlag) {
  const std::regex flag_in_literal(R"re("(?:[^"\n]*[ (])?--[a-z][a-z]+[^"\n]*")re");
  int files = 0;
  for (const char* dir : {"/lib/src", "/lib/include"}) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(std::string(DRILLWAVE_SOURCE_DIR) + dir)) {
      if (!entry.is_regular_file()) continue;
      std::ifstream in(entry.path());
      std::string line;
      for (int number = 1; std::getline(in, line); ++number) {
        const std::string code = line.substr(0, line.find("//"));
        if (std::regex_search(code, flag_in_literal) && code.find("report") == std::string::npos)
          ADD_FAILURE() << entry.path().string() << ":" << number << ": " << line;
      }
      ++files;
    }
  }
  EXPECT_GT(files, 100);
}

}  // namespace
}  // namespace drillwave
