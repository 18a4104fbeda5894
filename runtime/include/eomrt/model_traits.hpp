#pragma once
/// \file
/// What the runtime needs from a model: the contract every generated model header meets and a
/// hand-written model can meet too.
///
/// A model is a class (not an object: all members are static) providing
///   static constexpr int nq, nu, nc, nh   coordinates, inputs, constraints (rows of Xi),
///                                         holonomic constraints (rows of phi)
///   static constexpr std::array<int, nh> holonomic_rows   row of Xi of each entry of phi
///   template <class S> struct Parameters  default-constructible with the model's values
///   template <class S> static void mass_matrix_and_forcing(t, q, qd, u, p, M, F)
///   template <class S> static void constraint_jacobian(t, q, p, Xi)
///   template <class S> static void constraint_rate_term(t, q, p, Xi_t)
///   template <class S> static void constraint_acceleration_term(t, q, qd, p, b)
///   template <class S> static void holonomic_residuals(t, q, p, phi)
///   template <class S> static S kinetic_energy(t, q, qd, p), potential_energy(t, q, p)
/// with the fixed-size Eigen argument types of ModelTypes below, and optionally
///   static constexpr int ny + outputs(t, q, qd, u, p, y)      named outputs
///   static constexpr int ni + std::array<int, ni> independent_speeds   for the null-space method
///   template <class S> static bool forward_dynamics(t, q, qd, u, p, qdd)   qdd of M qdd = F
///                                         without M (false: M not positive definite or qdd not
///                                         finite); generated for trees without constraints
///   template <class S> class Constants    the parameter-only values, computed once per
///                                         parameter set: explicit Constants(const Parameters<S>&),
///                                         parameters() returning the copy it was built from, and
///                                         every function above taking it in place of p
/// A model with Constants is evaluated with them wherever the runtime evaluates it repeatedly
/// for one parameter set (simulate); the algorithms taking p accept either (a braced {} stands
/// for default Parameters, as it always did).
/// The equations are M(q) qdd = F + Xi^T lambda with Xi qd + Xi_t = 0 and, at acceleration
/// level, Xi qdd + b = 0 (docs/conventions.md).
#include <Eigen/Core>
#include <array>
#include <type_traits>
#include <utility>

namespace eomrt {

/// The fixed-size Eigen types of a model's arguments for one scalar type.
template <class Model, class Scalar>
struct ModelTypes {
  static constexpr int nq = Model::nq;
  static constexpr int nu = Model::nu;
  static constexpr int nc = Model::nc;
  static constexpr int nh = Model::nh;
  using Coordinates = Eigen::Matrix<Scalar, nq, 1>;                 ///< q, qd, qdd (dim nq)
  using State = Eigen::Matrix<Scalar, 2 * nq, 1>;                   ///< x = [q; qd] (dim 2 nq)
  using Inputs = Eigen::Matrix<Scalar, nu, 1>;                      ///< u (dim nu)
  using MassMatrix = Eigen::Matrix<Scalar, nq, nq>;                 ///< M (nq x nq)
  using ConstraintJacobian = Eigen::Matrix<Scalar, nc, nq>;         ///< Xi (nc x nq)
  using ConstraintVector = Eigen::Matrix<Scalar, nc, 1>;            ///< Xi_t, b, lambda (dim nc)
  using HolonomicVector = Eigen::Matrix<Scalar, nh, 1>;             ///< phi (dim nh)
  using Parameters = typename Model::template Parameters<Scalar>;  ///< p
};

namespace detail {

template <class...>
using void_t = void;

template <class Model, class Scalar, class = void>
struct has_constants : std::false_type {};
template <class Model, class Scalar>
struct has_constants<Model, Scalar, void_t<typename Model::template Constants<Scalar>>>
    : std::true_type {};

template <class Model, class Scalar, bool = has_constants<Model, Scalar>::value>
struct parameter_set {
  using type = typename Model::template Parameters<Scalar>;
};
template <class Model, class Scalar>
struct parameter_set<Model, Scalar, true> {
  using type = typename Model::template Constants<Scalar>;
};

template <class Model, class Scalar, class = void>
struct has_outputs : std::false_type {};
template <class Model, class Scalar>
struct has_outputs<Model, Scalar,
                   void_t<decltype(Model::ny),
                          decltype(Model::outputs(
                              std::declval<const Scalar&>(),
                              std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
                              std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
                              std::declval<const typename ModelTypes<Model, Scalar>::Inputs&>(),
                              std::declval<const typename ModelTypes<Model, Scalar>::Parameters&>(),
                              std::declval<Eigen::Matrix<Scalar, Model::ny, 1>&>()))>>
    : std::true_type {};

template <class Model, class Scalar, class = void>
struct has_forward_dynamics : std::false_type {};
template <class Model, class Scalar>
struct has_forward_dynamics<
    Model, Scalar,
    std::enable_if_t<std::is_convertible_v<
        decltype(Model::forward_dynamics(std::declval<const Scalar&>(),
                                         std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
                                         std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
                                         std::declval<const typename ModelTypes<Model, Scalar>::Inputs&>(),
                                         std::declval<const typename ModelTypes<Model, Scalar>::Parameters&>(),
                                         std::declval<typename ModelTypes<Model, Scalar>::Coordinates&>())),
        bool>>> : std::true_type {};

// a model without prefers_forward_dynamics that has forward_dynamics() prefers it
template <class Model, class = void>
struct prefers_forward_dynamics : std::true_type {};
template <class Model>
struct prefers_forward_dynamics<Model, void_t<decltype(Model::prefers_forward_dynamics)>>
    : std::bool_constant<Model::prefers_forward_dynamics> {};

template <class Model, class = void>
struct has_independent_speeds : std::false_type {};
template <class Model>
struct has_independent_speeds<Model, void_t<decltype(Model::ni), decltype(Model::independent_speeds)>>
    : std::bool_constant<(Model::ni > 0)> {};

// the functions of the contract taking P as their parameter argument (Parameters or Constants)
template <class Model, class Scalar, class P, class = void>
struct meets_model_contract : std::false_type {};
template <class Model, class Scalar, class P>
struct meets_model_contract<
    Model, Scalar, P,
    void_t<decltype(Model::holonomic_rows),
           decltype(Model::mass_matrix_and_forcing(
               std::declval<const Scalar&>(),
               std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
               std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
               std::declval<const typename ModelTypes<Model, Scalar>::Inputs&>(),
               std::declval<const P&>(),
               std::declval<typename ModelTypes<Model, Scalar>::MassMatrix&>(),
               std::declval<typename ModelTypes<Model, Scalar>::Coordinates&>())),
           decltype(Model::constraint_jacobian(
               std::declval<const Scalar&>(),
               std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
               std::declval<const P&>(),
               std::declval<typename ModelTypes<Model, Scalar>::ConstraintJacobian&>())),
           decltype(Model::constraint_rate_term(
               std::declval<const Scalar&>(),
               std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
               std::declval<const P&>(),
               std::declval<typename ModelTypes<Model, Scalar>::ConstraintVector&>())),
           decltype(Model::constraint_acceleration_term(
               std::declval<const Scalar&>(),
               std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
               std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
               std::declval<const P&>(),
               std::declval<typename ModelTypes<Model, Scalar>::ConstraintVector&>())),
           decltype(Model::holonomic_residuals(
               std::declval<const Scalar&>(),
               std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
               std::declval<const P&>(),
               std::declval<typename ModelTypes<Model, Scalar>::HolonomicVector&>())),
           decltype(Scalar(Model::kinetic_energy(
               std::declval<const Scalar&>(),
               std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
               std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
               std::declval<const P&>()))),
           decltype(Scalar(Model::potential_energy(
               std::declval<const Scalar&>(),
               std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
               std::declval<const P&>())))>>
    : std::true_type {};

// Constants built explicitly from Parameters, giving them back
template <class Model, class Scalar, class = void>
struct constants_are_built_from_parameters : std::false_type {};
template <class Model, class Scalar>
struct constants_are_built_from_parameters<
    Model, Scalar,
    std::enable_if_t<std::is_same_v<
        decltype(std::declval<const typename Model::template Constants<Scalar>&>().parameters()),
        const typename Model::template Parameters<Scalar>&>>>
    : std::bool_constant<
          std::is_constructible_v<typename Model::template Constants<Scalar>,
                                  const typename Model::template Parameters<Scalar>&> &&
          !std::is_convertible_v<const typename Model::template Parameters<Scalar>&,
                                 typename Model::template Constants<Scalar>>> {};

}  // namespace detail

/// True when the model computes its parameter-only values once per parameter set (Constants).
template <class Model, class Scalar = double>
inline constexpr bool has_constants_v = detail::has_constants<Model, Scalar>::value;

/// What the runtime evaluates a model with for one parameter set: Model::Constants<Scalar>
/// (the parameter-only values computed once) where the model has them, else its Parameters.
template <class Model, class Scalar>
using ParameterSet = typename detail::parameter_set<Model, Scalar>::type;

/// True for the types the model's functions take as their parameter argument: its Parameters
/// and, if it has them, its Constants.
template <class Model, class Scalar, class P>
inline constexpr bool is_parameter_argument_v =
    std::is_same_v<P, typename Model::template Parameters<Scalar>> ||
    std::is_same_v<P, ParameterSet<Model, Scalar>>;

/// The ParameterSet of parameters p: Constants(p), or a copy of p for a model without Constants.
template <class Model, class Scalar>
ParameterSet<Model, Scalar> make_parameter_set(
    const typename Model::template Parameters<Scalar>& p) noexcept {
  return ParameterSet<Model, Scalar>(p);
}

/// True when the model provides named outputs (ny and outputs()).
template <class Model, class Scalar = double>
inline constexpr bool has_outputs_v = detail::has_outputs<Model, Scalar>::value;

/// True when the model computes qdd itself (forward_dynamics(), e.g. by the articulated-body
/// algorithm), so that forward_dynamics_unconstrained need not factorize M.
template <class Model, class Scalar = double>
inline constexpr bool has_forward_dynamics_v = detail::has_forward_dynamics<Model, Scalar>::value;

/// True when forward_dynamics_unconstrained takes the model's forward_dynamics(): it has one, and
/// does not declare `static constexpr bool prefers_forward_dynamics = false` (a generated model
/// says false where M, F and a Cholesky solve take fewer operations, as for small models).
template <class Model, class Scalar = double>
inline constexpr bool uses_forward_dynamics_v =
    has_forward_dynamics_v<Model, Scalar> && detail::prefers_forward_dynamics<Model>::value;

/// True when the model declares independent speeds for the null-space method (ni > 0).
template <class Model>
inline constexpr bool has_independent_speeds_v = detail::has_independent_speeds<Model>::value;

/// Rejects, at compile time and with a readable message, a class that does not meet the
/// contract above. Every runtime entry point calls it, so a wrong model fails at its use.
template <class Model, class Scalar>
constexpr bool check_model() {
  static_assert(std::is_integral_v<std::remove_cv_t<decltype(Model::nq)>> &&
                    std::is_integral_v<std::remove_cv_t<decltype(Model::nu)>> &&
                    std::is_integral_v<std::remove_cv_t<decltype(Model::nc)>> &&
                    std::is_integral_v<std::remove_cv_t<decltype(Model::nh)>>,
                "eomrt model: nq, nu, nc and nh must be static integral constants");
  static_assert(Model::nq > 0, "eomrt model: nq must be positive");
  static_assert(Model::nc >= 0 && Model::nc < Model::nq, "eomrt model: 0 <= nc < nq expected");
  static_assert(Model::nh >= 0 && Model::nh <= Model::nc, "eomrt model: 0 <= nh <= nc expected");
  static_assert(std::is_default_constructible_v<typename ModelTypes<Model, Scalar>::Parameters>,
                "eomrt model: Parameters<Scalar> must be default-constructible");
  static_assert(detail::meets_model_contract<Model, Scalar,
                                             typename ModelTypes<Model, Scalar>::Parameters>::value,
                "eomrt model: expected holonomic_rows and static mass_matrix_and_forcing, "
                "constraint_jacobian, constraint_rate_term, constraint_acceleration_term, "
                "holonomic_residuals, kinetic_energy and potential_energy with the argument "
                "types of eomrt::ModelTypes (see model_traits.hpp)");
  if constexpr (has_constants_v<Model, Scalar>) {
    static_assert(detail::constants_are_built_from_parameters<Model, Scalar>::value,
                  "eomrt model: Constants<Scalar> must have an explicit constructor from "
                  "Parameters<Scalar> and parameters() returning const Parameters<Scalar>&");
    static_assert(detail::meets_model_contract<Model, Scalar, ParameterSet<Model, Scalar>>::value,
                  "eomrt model: a model with Constants must offer every function of the contract "
                  "taking them in place of the Parameters (see model_traits.hpp)");
  }
  return true;
}

}  // namespace eomrt
