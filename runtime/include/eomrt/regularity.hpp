#pragma once
/// \file
/// When a factorization counts as singular: one threshold and the tests that use it, shared by
/// the runtime's solves, the linearization and the generator's numeric evaluation, so that a
/// state is singular (or not) to all of them alike.
#include <Eigen/Core>

namespace eomrt {

/// Reciprocal condition number below which a factorization counts as singular: 1000 eps,
/// about 2e-13 in double. A solve with a worse conditioned matrix would return digits of
/// noise; failing loudly is the better service. DynamicsWorkspace::singular_rcond starts here.
template <class Scalar>
Scalar default_singular_rcond() {
  return Scalar(1000) * Eigen::NumTraits<Scalar>::epsilon();
}

/// Whether a Cholesky factorization L L^T of a symmetric matrix (Eigen::LLT, of any size) is
/// numerically positive definite: no failed pivot, and (min L_ii / max L_ii)^2 > threshold.
/// That ratio of the smallest to the largest pivot bounds 1/cond from above and drops to 0
/// exactly where a configuration makes M singular (a gimbal lock); it costs O(n), where
/// Eigen's rcond() estimate costs more than evaluating M and F of a small model.
template <class Llt, class Scalar>
bool cholesky_is_regular(const Llt& llt, const Scalar& threshold) {
  if (llt.info() != Eigen::Success) return false;
  const auto pivots = llt.matrixLLT().diagonal();
  if (pivots.size() == 0) return true;
  const Scalar smallest = pivots.minCoeff(), largest = pivots.maxCoeff();
  return smallest * smallest > threshold * largest * largest;
}

// An LU factorization's test (estimated reciprocal condition number above the threshold) is
// LuFactorization::is_regular (lu_factorization.hpp).

}  // namespace eomrt
