// Well-formed UTF-8 (RFC 3629), which the lexer asks of strings and plot titles are cleaned to.
#include <gtest/gtest.h>

#include <string>

#include "eomgen/base/utf8.hpp"

namespace eomgen {
namespace {

TEST(Utf8, SequencesOfOneToFourBytesHaveTheirLength) {
  const std::string text = "a\xc3\xa9\xe2\x82\xac\xf0\x9f\x9a\xb2";  // a, e-acute, euro, bicycle
  EXPECT_EQ(utf8_sequence_length(text, 0), 1u);
  EXPECT_EQ(utf8_sequence_length(text, 1), 2u);
  EXPECT_EQ(utf8_sequence_length(text, 3), 3u);
  EXPECT_EQ(utf8_sequence_length(text, 6), 4u);
  EXPECT_EQ(invalid_utf8_at(text), std::string::npos);
}

TEST(Utf8, MalformedSequencesAreFoundAtTheirFirstByte) {
  EXPECT_EQ(invalid_utf8_at("ok \xff"), 3u);                // a byte that starts nothing
  EXPECT_EQ(invalid_utf8_at("x\x80"), 1u);                  // a stray continuation byte
  EXPECT_EQ(invalid_utf8_at("x\xc3"), 1u);                  // truncated
  EXPECT_EQ(invalid_utf8_at("\xc0\xaf"), 0u);               // overlong '/'
  EXPECT_EQ(invalid_utf8_at("\xe0\x80\xaf"), 0u);           // overlong, three bytes
  EXPECT_EQ(invalid_utf8_at("ab\xed\xa0\x80"), 2u);         // a surrogate
  EXPECT_EQ(invalid_utf8_at("\xf4\x90\x80\x80"), 0u);       // above U+10FFFF
  EXPECT_EQ(invalid_utf8_at("\xf4\x8f\xbf\xbf"), std::string::npos);  // U+10FFFF itself
}

}  // namespace
}  // namespace eomgen
