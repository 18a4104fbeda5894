// Reading a user's file with a size limit: the whole of a small file, one byte past the limit of
// a large or endless one, and bytes read whole across chunk boundaries.
#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <sstream>
#include <streambuf>
#include <string>

#include "eomgen/base/bounded_read.hpp"

namespace eomgen {
namespace {

// an endless stream of one byte, as /dev/zero is
class Endless : public std::streambuf {
 public:
  explicit Endless(char c) : c_(c) {}

 protected:
  int_type underflow() override {
    std::fill(std::begin(buffer_), std::end(buffer_), c_);
    setg(buffer_, buffer_, buffer_ + sizeof buffer_);
    return traits_type::to_int_type(c_);
  }

 private:
  char c_;
  char buffer_[1000];
};

TEST(ReadAtMost, AFileUnderTheLimitIsReadWholeWithEveryByte) {
  std::string text;
  for (int k = 0; k < 200000; ++k) text += static_cast<char>(k % 251);  // crosses chunks, holds '\0'
  std::istringstream in(text);
  EXPECT_EQ(read_at_most(in, 1u << 20), text);
  EXPECT_FALSE(in.bad());
}

TEST(ReadAtMost, AFileOfExactlyTheLimitIsReadWhole) {
  const std::string text(70000, 'x');
  std::istringstream in(text);
  EXPECT_EQ(read_at_most(in, 70000).size(), 70000u);
}

TEST(ReadAtMost, AFileOverTheLimitGivesOneByteMoreThanTheLimit) {
  std::istringstream in(std::string(150000, 'y'));
  EXPECT_EQ(read_at_most(in, 100000).size(), 100001u);
}

TEST(ReadAtMost, AnEndlessStreamStopsOneBytePastTheLimit) {
  Endless zeros('\0');
  std::istream in(&zeros);
  const std::string text = read_at_most(in, 4u << 20);
  EXPECT_EQ(text.size(), (4u << 20) + 1);
  EXPECT_EQ(text.find_first_not_of('\0'), std::string::npos);
}

TEST(ReadAtMost, AnEmptyFileIsEmpty) {
  std::istringstream in("");
  EXPECT_EQ(read_at_most(in, 10), "");
  EXPECT_FALSE(in.bad());
}

}  // namespace
}  // namespace eomgen
