#pragma once
// EXPECT_THROW_MESSAGE(statement, exception_type, message): `statement` throws an exception_type
// (or a class derived from it) whose what() equals `message`, or matches it when `message` is a
// gmock string matcher (HasSubstr, StartsWith, AllOf(...), ContainsRegex). Checking the message
// and not only the type is what makes a misuse test fail when a different check fires first.
//
//   EXPECT_THROW_MESSAGE(integrate_fixed(rk4, f, 0.0, x0, 1.0, -0.1), std::invalid_argument,
//                        "integrate_fixed: step h expected positive and finite, got -0.1");
//   EXPECT_THROW_MESSAGE(v.add_coordinate("t"), ModelError, HasSubstr("'t'"));
//
// A failure shows the statement, the exception it threw (or that it threw none) and its message.
// A statement with a comma outside parentheses (a template argument list) must be parenthesized.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <ostream>
#include <utility>

namespace eomgen::testing::detail {

// the statement as a callable that gtest prints as its source text
template <class F>
struct Statement {
  F run;
  const char* text;
  void operator()() const { run(); }
};

template <class F>
Statement<F> make_statement(F run, const char* text) {
  return {std::move(run), text};
}

template <class F>
void PrintTo(const Statement<F>& s, std::ostream* os) {
  *os << s.text;
}

}  // namespace eomgen::testing::detail

#define EXPECT_THROW_MESSAGE(statement_, exception_type, message)                                             \
  EXPECT_THAT(::eomgen::testing::detail::make_statement([&] { static_cast<void>(statement_); }, #statement_), \
              ::testing::ThrowsMessage<exception_type>(message))
