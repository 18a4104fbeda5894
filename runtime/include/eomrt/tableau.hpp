#pragma once
/// \file
/// Butcher tableaus of explicit Runge-Kutta methods, as constexpr data.
///
/// A method is its tableau: the fixed-step stepper in rk_fixed.hpp and the adaptive one in
/// rk_adaptive.hpp read a, b, c (and b_hat) from here, so adding a method means adding a
/// tableau and its row in integrators.hpp.
#include <cstddef>
#include <limits>
#include <type_traits>

namespace eomrt {

/// Coefficients are stored in the widest standard floating type and cast to the state's
/// scalar per step; storing doubles would cap a long double integration at double accuracy
/// (1/6 or 35/384 are not representable, and their rounding error would enter every step).
using Coefficient = long double;

/// Butcher tableau of an explicit Runge-Kutta method with S stages:
///   k_i = f(t + c_i h, x + h sum_{j<i} a_ij k_j),   x_next = x + h sum_i b_i k_i.
/// \tparam S  number of stages (= right-hand-side evaluations per step)
template <std::size_t S>
struct ButcherTableau {
  static constexpr std::size_t stages = S;
  /// stage coupling (S x S); only the strictly lower triangle is read, the method is explicit
  Coefficient a[S][S];
  /// weights of the propagated solution (dim S)
  Coefficient b[S];
  /// nodes (dim S): stage i is evaluated at t + c_i h, so c_i must equal sum_j a_ij
  Coefficient c[S];
  /// global convergence order of the solution built with b
  int order;
};

/// Embedded pair: the second weight row b_hat gives a solution of another order from the
/// same stages, and h sum_i (b_i - b_hat_i) k_i estimates the local error of the step.
/// Derives from ButcherTableau so every fixed-step routine accepts a pair too.
template <std::size_t S>
struct EmbeddedTableau : ButcherTableau<S> {
  /// embedded weights (dim S), used only for the error estimate
  Coefficient b_hat[S];
  /// global convergence order of the solution built with b_hat
  int embedded_order;
  /// weights d_i (dim S) of the dense output of a step from (t, x0) to (t + h, x1) of an FSAL
  /// pair: x(t + theta h) is the cubic Hermite interpolant of x0, x1, f0 = k_1 and f1 = k_S,
  /// plus theta^2 (1 - theta)^2 h sum_i d_i k_i, a term that leaves both ends and their
  /// derivatives unchanged. All zero (the default): the cubic interpolant alone, of order 3.
  Coefficient dense[S];
};

/// true for an EmbeddedTableau: the registry steps such a method adaptively.
template <class Tableau>
struct is_embedded_tableau : std::false_type {};
template <std::size_t S>
struct is_embedded_tableau<EmbeddedTableau<S>> : std::true_type {};
template <class Tableau>
inline constexpr bool is_embedded_tableau_v = is_embedded_tableau<Tableau>::value;

namespace detail {

constexpr Coefficient abs(Coefficient v) { return v < 0 ? -v : v; }

/// Rationals such as 9017/3168 are rounded, so sums are compared with a tolerance that
/// scales with the magnitude of the terms (several ulps per term).
constexpr bool sums_to(const Coefficient* terms, std::size_t n, Coefficient target) {
  Coefficient sum = 0;
  Coefficient magnitude = abs(target);
  for (std::size_t i = 0; i < n; ++i) {
    sum += terms[i];
    magnitude += abs(terms[i]);
  }
  const Coefficient eps = std::numeric_limits<Coefficient>::epsilon();
  return abs(sum - target) <= 8 * eps * (1 + magnitude);
}

}  // namespace detail

/// \return true if a is strictly lower triangular, i.e. each stage uses only earlier stages.
template <std::size_t S>
constexpr bool is_explicit(const ButcherTableau<S>& t) {
  for (std::size_t i = 0; i < S; ++i)
    for (std::size_t j = i; j < S; ++j)
      if (t.a[i][j] != 0) return false;
  return true;
}

/// \return true if every node c_i equals the row sum of a_i (to rounding); otherwise the
/// stages would sample f at times inconsistent with the states they are given, and
/// non-autonomous right-hand sides would lose order.
template <std::size_t S>
constexpr bool nodes_match_row_sums(const ButcherTableau<S>& t) {
  for (std::size_t i = 0; i < S; ++i)
    if (!detail::sums_to(t.a[i], S, t.c[i])) return false;
  return true;
}

/// \return true if the weights sum to one (to rounding): the first-order condition,
/// without which the method is not even consistent.
template <std::size_t S>
constexpr bool weights_sum_to_one(const ButcherTableau<S>& t) {
  return detail::sums_to(t.b, S, 1);
}

/// \return true if the tableau is explicit, its nodes are the row sums of a and its
/// weights sum to one.
template <std::size_t S>
constexpr bool is_consistent(const ButcherTableau<S>& t) {
  return is_explicit(t) && nodes_match_row_sums(t) && weights_sum_to_one(t);
}

/// \return is_consistent for the propagated method, and the embedded weights sum to one.
template <std::size_t S>
constexpr bool is_consistent(const EmbeddedTableau<S>& t) {
  return is_consistent(static_cast<const ButcherTableau<S>&>(t)) && detail::sums_to(t.b_hat, S, 1);
}

/// \return true if the last stage is evaluated at (t + h, x_next) ("first same as last"),
/// so an adaptive controller can reuse it as the first stage of the next step.
template <std::size_t S>
constexpr bool is_fsal(const ButcherTableau<S>& t) {
  if (t.c[S - 1] != 1) return false;
  for (std::size_t j = 0; j < S; ++j)
    if (t.a[S - 1][j] != t.b[j]) return false;
  return true;
}

// the tableaus keep the layout of the published tables
// clang-format off
/// Explicit (forward) Euler, course notes A.4.1: x_next = x + h f(t, x).
inline constexpr ButcherTableau<1> euler{
    /*a=*/{{0}},
    /*b=*/{1},
    /*c=*/{0},
    /*order=*/1};

/// Classical fourth-order Runge-Kutta, course notes A.4.2.
inline constexpr ButcherTableau<4> rk4{
    /*a=*/{{0, 0, 0, 0},
           {1.0L / 2, 0, 0, 0},
           {0, 1.0L / 2, 0, 0},
           {0, 0, 1, 0}},
    /*b=*/{1.0L / 6, 1.0L / 3, 1.0L / 3, 1.0L / 6},
    /*c=*/{0, 1.0L / 2, 1.0L / 2, 1},
    /*order=*/4};

/// Dormand-Prince 5(4) (J. R. Dormand, P. J. Prince, J. Comput. Appl. Math. 6(1), 1980),
/// the pair behind MATLAB's ode45: b propagates the 5th-order solution (local
/// extrapolation), b_hat is the 4th-order companion for the error estimate. FSAL: the
/// 7th stage is f at the new state, so a step costs 6 evaluations after the first.
/// The dense weights are those of Hairer's continuous extension (dopri5.f, CONTD5; due to
/// Shampine 1986), a 4th-order polynomial.
inline constexpr EmbeddedTableau<7> dormand_prince54{
    {/*a=*/{{0, 0, 0, 0, 0, 0, 0},
            {1.0L / 5, 0, 0, 0, 0, 0, 0},
            {3.0L / 40, 9.0L / 40, 0, 0, 0, 0, 0},
            {44.0L / 45, -56.0L / 15, 32.0L / 9, 0, 0, 0, 0},
            {19372.0L / 6561, -25360.0L / 2187, 64448.0L / 6561, -212.0L / 729, 0, 0, 0},
            {9017.0L / 3168, -355.0L / 33, 46732.0L / 5247, 49.0L / 176, -5103.0L / 18656, 0, 0},
            {35.0L / 384, 0, 500.0L / 1113, 125.0L / 192, -2187.0L / 6784, 11.0L / 84, 0}},
     /*b=*/{35.0L / 384, 0, 500.0L / 1113, 125.0L / 192, -2187.0L / 6784, 11.0L / 84, 0},
     /*c=*/{0, 1.0L / 5, 3.0L / 10, 4.0L / 5, 8.0L / 9, 1, 1},
     /*order=*/5},
    /*b_hat=*/
    {5179.0L / 57600, 0, 7571.0L / 16695, 393.0L / 640, -92097.0L / 339200, 187.0L / 2100,
     1.0L / 40},
    /*embedded_order=*/4,
    /*dense=*/
    {-12715105075.0L / 11282082432.0L, 0, 87487479700.0L / 32700410799.0L,
     -10690763975.0L / 1880347072.0L, 701980252875.0L / 199316789632.0L,
     -1453857185.0L / 822651844.0L, 69997945.0L / 29380423.0L}};
// clang-format on

// a typo in a coefficient should break the build, not a simulation
static_assert(is_consistent(euler), "euler: tableau is inconsistent");
static_assert(is_consistent(rk4), "rk4: tableau is inconsistent");
static_assert(is_consistent(dormand_prince54), "dormand_prince54: tableau is inconsistent");
static_assert(is_fsal(dormand_prince54), "dormand_prince54: last stage must equal b (FSAL)");

}  // namespace eomrt
