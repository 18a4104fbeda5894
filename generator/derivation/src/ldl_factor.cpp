#include "ldl_factor.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

ex bound(const ex& e, Subexpressions& z) { return e.is_zero() ? ex(0) : z.bind(e); }

}  // namespace

LdlFactors ldl_factor(const matrix& D, Subexpressions& z, GiNaC::exvector& pivots) {
  const unsigned k = D.rows();
  LdlFactors f{matrix(k, k), matrix(k, 1)};
  matrix t(k, k);  // t_ab = L_ab d_b
  for (unsigned a = 0; a < k; ++a) {
    for (unsigned b = 0; b < a; ++b) {
      ex sum = D(a, b);
      for (unsigned m = 0; m < b; ++m) sum -= t(a, m) * f.L(b, m);
      t(a, b) = bound(sum, z);
      f.L(a, b) = bound(t(a, b) * f.inverse_d(b, 0), z);
    }
    ex d = D(a, a);
    for (unsigned m = 0; m < a; ++m) d -= t(a, m) * f.L(a, m);
    d = z.bind(d);
    pivots.push_back(d);
    f.inverse_d(a, 0) = z.bind(1 / d);
  }
  return f;
}

matrix forward_substitution(const matrix& L, const matrix& B, Subexpressions& z) {
  matrix X(B.rows(), B.cols());
  for (unsigned a = 0; a < B.rows(); ++a)
    for (unsigned c = 0; c < B.cols(); ++c) {
      ex sum = B(a, c);
      for (unsigned m = 0; m < a; ++m) sum -= L(a, m) * X(m, c);
      X(a, c) = bound(sum, z);
    }
  return X;
}

matrix ldl_solve(const LdlFactors& f, const matrix& b, Subexpressions& z) {
  const unsigned k = b.rows();
  const matrix y = forward_substitution(f.L, b, z);
  matrix x(k, b.cols());
  for (unsigned c = 0; c < b.cols(); ++c)
    for (unsigned a = k; a-- > 0;) {
      ex sum = f.inverse_d(a, 0) * y(a, c);
      for (unsigned m = a + 1; m < k; ++m) sum -= f.L(m, a) * x(m, c);
      x(a, c) = bound(sum, z);
    }
  return x;
}

}  // namespace eomgen
