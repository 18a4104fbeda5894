#pragma once
// Two kinds of error, never mixed. Errors in user input (a model file, an API call, a command
// line) are Error subclasses, always checked. A broken internal invariant is a bug in eomgen:
// EOMGEN_DEMAND and EOMGEN_UNREACHABLE throw InternalError, which is not an Error, so no code
// that reports bad input catches it and the user is told it is a bug and where.
#include <stdexcept>
#include <string>

#include "eomgen/base/source_location.hpp"

namespace eomgen {

/// Base of every error the generator throws on bad input.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A model built through the API is invalid: duplicate or unknown name, bad mass or inertia,
/// a constraint that is not of the form it claims, an expression with an undeclared symbol.
class ModelError : public Error {
 public:
  using Error::Error;
};

/// The derivation met an expression it cannot handle (e.g. a time derivative of an input).
class DerivationError : public Error {
 public:
  using Error::Error;
};

/// Code emission met something it cannot print (an unknown symbol or function).
class EmitError : public Error {
 public:
  using Error::Error;
};

/// An error at a position in a model file; what() reads "file:line:col: error: message".
class SourceError : public Error {
 public:
  SourceError(SourceLocation location, const std::string& message)
      : Error(location.file + ":" + std::to_string(location.line) + ":" + std::to_string(location.column) +
              ": error: " + message),
        location_(std::move(location)),
        message_(message) {}
  const SourceLocation& location() const { return location_; }
  /// The message without the position.
  const std::string& message() const { return message_; }

 private:
  SourceLocation location_;
  std::string message_;
};

/// A bug in eomgen: an internal invariant does not hold. No input should cause it. what() reads
/// "internal error at generator/x/src/y.cpp:42: MESSAGE; this is a bug in eomgen, please report it".
class InternalError : public std::logic_error {
 public:
  InternalError(const char* file, int line, const std::string& message);
  /// The source file, from the repository root when it lies in generator/.
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  /// The message without the position.
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  int line_;
  std::string message_;
};

namespace detail {
[[noreturn]] void internal_error(const char* file, int line, const std::string& message);
[[noreturn]] void demand_failed(const char* file, int line, const char* condition, const std::string& message);
}  // namespace detail

}  // namespace eomgen

/// Checks an internal invariant, in every build type (it guards the generator, not a hot loop):
/// EOMGEN_DEMAND(index < size, "lowering: operand defined before use").
/// \throws InternalError naming the condition, the message, the file and the line.
#define EOMGEN_DEMAND(condition, message) \
  ((condition) ? static_cast<void>(0) : ::eomgen::detail::demand_failed(__FILE__, __LINE__, #condition, (message)))

/// Marks a branch no input can reach, such as the end of a switch that lists every enumerator
/// (the compiler sees that it does not return). \throws InternalError.
#define EOMGEN_UNREACHABLE(message) ::eomgen::detail::internal_error(__FILE__, __LINE__, (message))
