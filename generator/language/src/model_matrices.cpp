// Matrix algebra of model expressions (model_matrices.hpp).
#include "model_matrices.hpp"

#include <fmt/format.h>

#include "eomgen/symbolic/expression_size.hpp"

namespace eomgen::syntax {

bool has_shape(const Value& v) {
  switch (v.kind) {
    case Value::Kind::scalar:
    case Value::Kind::vector: return false;
    case Value::Kind::column:
    case Value::Kind::matrix: return true;
  }
  EOMGEN_UNREACHABLE("has_shape: a Value::Kind outside its enumerators");
}

std::string shape_name(const Value& v) {
  if (!has_shape(v)) return kind_name(v.kind);
  return fmt::format("a {}x{} {}", v.matrix.rows(), v.matrix.cols(),
                     v.kind == Value::Kind::column ? "column" : "matrix");
}

Value matrix_product(const Value& left, const Value& right, const SourceLocation& at) {
  EOMGEN_DEMAND(has_shape(left) && has_shape(right), "matrix_product: a factor without a shape");
  const unsigned inner = left.matrix.cols();
  if (right.matrix.rows() != inner)
    throw SourceError(at, fmt::format("cannot multiply {} and {}: expected a right factor with {} row{}, as many as "
                                      "the left has columns", shape_name(left), shape_name(right), inner,
                                      inner == 1 ? "" : "s"));
  const GiNaC::matrix product = left.matrix.mul(right.matrix);
  // Each product refers to its factors' entries, shared in memory, but the derivation works on
  // them written out: a chain of n rotations that vary is 3^n times as large as one.
  for (unsigned i = 0; i < product.rows(); ++i)
    for (unsigned j = 0; j < product.cols(); ++j)
      if (tree_size(product(i, j)) > max_matrix_entry_size)
        throw SourceError(at, fmt::format("the product's entries grow beyond {} operations written out: expected "
                                          "fewer products of matrices that vary (the derivation's work grows with "
                                          "their size)", max_matrix_entry_size));
  if (product.rows() == 1 && product.cols() == 1) return Value::of(product(0, 0));
  return Value::of_matrix(product);
}

Value transposed(const Value& v) {
  EOMGEN_DEMAND(has_shape(v), "transposed: a value without a shape");
  return Value::of_matrix(v.matrix.transpose());
}

SourceError non_scalar_power(const Value& base, const Value* exponent, const SourceLocation& at) {
  switch (base.kind) {
    case Value::Kind::vector:
      return SourceError(at, "cannot raise a vector to a power: use dot(v, v) for its squared length");
    case Value::Kind::column:
    case Value::Kind::matrix:
      return SourceError(at, fmt::format("cannot raise {} to a power: expected M^T, its transpose, the only exponent "
                                         "of a matrix or a column (for a power, write the product M*M)",
                                         shape_name(base)));
    case Value::Kind::scalar:
      break;
  }
  EOMGEN_DEMAND(exponent && exponent->kind != Value::Kind::scalar, "non_scalar_power: a scalar power");
  return SourceError(at, fmt::format("cannot raise a scalar to the power of {}: expected a scalar exponent",
                                     shape_name(*exponent)));
}

}  // namespace eomgen::syntax
