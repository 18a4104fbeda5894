#pragma once
/// \file
/// Calling a right-hand side f(t, x, dxdt) that may or may not be able to fail.
///
/// A right-hand side either returns void (it always succeeds) or bool (false: it could not
/// evaluate, e.g. the mass matrix is singular at x). The integrators stop with an rhs_failed
/// status on false and leave the reason to the caller, who knows what the callable computes.
#include <type_traits>

namespace eomrt {

/// Evaluates dxdt = f(t, x) for a right-hand side returning void or bool.
/// \param[in]  f     right-hand side f(t, x, dxdt); writes all n entries of dxdt
/// \param[in]  t     time
/// \param[in]  x     state (dim n)
/// \param[out] dxdt  derivative (dim n, pre-sized; f must not resize it)
/// \return true if f succeeded: always for a void f, f's own result for a bool f
template <class Rhs, class Scalar, class Vector>
bool evaluate_rhs(Rhs& f, Scalar t, const Vector& x, Vector& dxdt) {
  using Result = decltype(f(t, x, dxdt));
  // exactly bool: an int or Eigen::ComputationInfo (Success == 0) converts to bool with the
  // opposite meaning, so anything else is more likely a mistake than a status
  static_assert(std::is_void<Result>::value || std::is_same<Result, bool>::value,
                "evaluate_rhs: the right-hand side f(t, x, dxdt) must return void or bool");
  if constexpr (std::is_void<Result>::value) {
    f(t, x, dxdt);
    return true;
  } else {
    return f(t, x, dxdt);
  }
}

}  // namespace eomrt
