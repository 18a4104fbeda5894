#pragma once
// Typed errors of the generator. Errors in user input are always checked (never compiled out);
// internal invariants use assert.
#include <stdexcept>
#include <string>

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

}  // namespace eomgen
