#pragma once
// Matrix algebra of model expressions: what sums, products, negations and powers
// (model_expression.cpp) do with columns and matrices, and how messages name their shapes.
#include <ginac/ginac.h>

#include <string>

#include "eomgen/base/error.hpp"
#include "model_elaborator.hpp"

namespace eomgen::syntax {

/// The largest entry of a matrix product, counted as operations written out (see matrix_product).
inline constexpr double max_matrix_entry_size = 100000;

/// A column or a matrix: a value with a shape.
bool has_shape(const Value& v);

/// "a 3x3 matrix", "a 3x1 column"; for scalars and vectors, kind_name. A matrix operation fails
/// on shapes, so its message names them.
std::string shape_name(const Value& v);

/// left * right for two values with shapes: the columns of left must match the rows of right.
/// The result is a column when it has one column, and a scalar when it is 1x1 (a row times a
/// column), so that it multiplies further like any scalar. \throws SourceError at `at`.
Value matrix_product(const Value& left, const Value& right, const SourceLocation& at);

/// The transpose M^T: a column becomes a 1 x n matrix and back.
Value transposed(const Value& v);

/// The error for base^exponent where either is not a scalar, saying what to write instead.
SourceError non_scalar_power(const Value& base, const Value* exponent, const SourceLocation& at);

}  // namespace eomgen::syntax
