#pragma once
// D = L diag(d) L^T of a symmetric matrix of expressions, written out as intermediates: the
// articulated-body recursion factors each joint's D_i with it, and the mass-matrix path of the
// forward dynamics factors M. Exact zeros stay zeros (nothing is bound for them), so a sparse
// matrix costs only its fill-in.
#include <ginac/ginac.h>

#include "eomgen/symbolic/subexpressions.hpp"

namespace eomgen {

struct LdlFactors {
  GiNaC::matrix L;          ///< unit lower triangular (the diagonal is not stored: read as 1)
  GiNaC::matrix inverse_d;  ///< 1 / d_a, k x 1
};

/// Factors D; each pivot d_a is appended to \p pivots (for the check that all are positive).
LdlFactors ldl_factor(const GiNaC::matrix& D, Subexpressions& z, GiNaC::exvector& pivots);

/// L^-1 B by forward substitution.
GiNaC::matrix forward_substitution(const GiNaC::matrix& L, const GiNaC::matrix& B, Subexpressions& z);

/// X of L diag(d) L^T X = B, column by column (B of any number of columns).
GiNaC::matrix ldl_solve(const LdlFactors& f, const GiNaC::matrix& b, Subexpressions& z);

}  // namespace eomgen
