// The two kinds of error: bad input is an Error; a broken internal invariant is an
// InternalError that says it is a bug in eomgen and where.
#include "eomgen/base/error.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "eomgen/derivation/linearization.hpp"

namespace eomgen {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

TEST(InternalError, DemandThatHoldsDoesNothingAndBuildsNoMessage) {
  int messages = 0;
  auto message = [&] {
    ++messages;
    return std::string("never built");
  };
  EXPECT_NO_THROW(EOMGEN_DEMAND(1 + 1 == 2, message()));
  EXPECT_EQ(messages, 0);
}

TEST(InternalError, FailedDemandNamesTheBugTheConditionAndWhere) {
  const int line = __LINE__ + 2;
  try {
    EOMGEN_DEMAND(2 + 2 == 5, "arithmetic: the sum is off");
    FAIL() << "no InternalError thrown";
  } catch (const InternalError& e) {
    EXPECT_EQ(e.file(), "tests/base/error_test.cpp");
    EXPECT_EQ(e.line(), line);
    EXPECT_EQ(e.message(), "arithmetic: the sum is off (failed: 2 + 2 == 5)");
    EXPECT_EQ(std::string(e.what()), "internal error at tests/base/error_test.cpp:" + std::to_string(line) +
                                         ": arithmetic: the sum is off (failed: 2 + 2 == 5); this is a bug in "
                                         "eomgen, please report it");
  }
}

TEST(InternalError, UnreachableThrowsWithTheFileAndLine) {
  const int line = __LINE__ + 1;
  auto branch = [] { EOMGEN_UNREACHABLE("a branch no input reaches"); };
  try {
    branch();
    FAIL() << "no InternalError thrown";
  } catch (const InternalError& e) {
    EXPECT_EQ(e.line(), line);
    EXPECT_THAT(e.what(), StartsWith("internal error at tests/base/error_test.cpp:"));
    EXPECT_THAT(e.what(), HasSubstr(": a branch no input reaches; this is a bug in eomgen"));
  }
}

// code that reports bad input catches Error: it must not report a bug as the user's mistake
TEST(InternalError, IsNotAnInputError) {
  bool caught_as_input_error = false;
  try {
    try {
      EOMGEN_UNREACHABLE("a bug");
    } catch (const Error&) {
      caught_as_input_error = true;
    }
  } catch (const InternalError&) {
  }
  EXPECT_FALSE(caught_as_input_error);
}

// a value outside an enum's enumerators reaches the end of a switch that lists them all
TEST(InternalError, SwitchesOverEveryEnumeratorStopAtAnUnlistedValue) {
  try {
    to_string(static_cast<LinearStability>(42));
    FAIL() << "no InternalError thrown";
  } catch (const InternalError& e) {
    EXPECT_EQ(e.file(), "generator/derivation/src/linearization.cpp");
    EXPECT_THAT(e.message(), HasSubstr("LinearStability"));
  }
  EXPECT_THROW(to_string(static_cast<LyapunovVerdict>(42)), InternalError);
  EXPECT_STREQ(to_string(LinearStability::unstable), "unstable");
}

TEST(SourceError, KeepsThePositionApartFromTheMessage) {
  const SourceError e({"m.eom", 3, 7}, "unknown name 'x'");
  EXPECT_STREQ(e.what(), "m.eom:3:7: error: unknown name 'x'");
  EXPECT_EQ(e.message(), "unknown name 'x'");
  EXPECT_EQ(e.location().line, 3);
}

}  // namespace
}  // namespace eomgen
