#pragma once
// Typed errors of the generator. Errors in user input are always checked (never compiled out);
// internal invariants use assert.
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

}  // namespace eomgen
