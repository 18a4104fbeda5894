#pragma once
// expect_model_error(text, line, column, message): parsing the model text throws a SourceError at
// that line and column whose message contains `message`. model_error_text(text, file): the whole
// message, for tests that assert it all.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "eomgen/base/error.hpp"
#include "eomgen/language/model_file.hpp"

namespace eomgen::testing {

inline void expect_model_error(const std::string& text, int line, int column, const std::string& message) {
  SCOPED_TRACE("model text:\n" + text);
  try {
    parse_model(text, "test.eom");
    ADD_FAILURE() << "expected a SourceError";
  } catch (const SourceError& e) {
    EXPECT_EQ(e.location().line, line) << e.what();
    EXPECT_EQ(e.location().column, column) << e.what();
    EXPECT_THAT(e.message(), ::testing::HasSubstr(message));
  }
}

/// The full message (file:line:col: error: ...) of the SourceError that parsing `text` as the file
/// `file` throws; "no error" when it parses, and what else it threw otherwise.
inline std::string model_error_text(const std::string& text, const std::string& file) {
  try {
    parse_model(text, file);
  } catch (const SourceError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("not a SourceError: ") + e.what();
  }
  return "no error";
}

}  // namespace eomgen::testing
