#pragma once
// Every function a generated header holds, each derived in the form chosen for it, with its
// operation estimate: the one place that decides what a header computes and how. Code
// generation (eomgen/codegen/emit_model.hpp) only lowers and prints what this returns.
//
//   mass_matrix, forcing      Kane's closed form, or the composite-body M and Newton-Euler F
//   forward_dynamics          the articulated-body recursion, or M's LDL^T factors (trees)
//   forward_dynamics_derivatives  dqdd/dq, dqdd/dqd, dqdd/du: the chain rule through the
//                             recursion, or M^-1 of the linearization's K, D and B_u
//   inverse_dynamics          tau = M qdd - F, from M and F or by Newton-Euler
//   gravity_forces            g(q) = dV/dq
//   coriolis_matrix           C(q, qd) from the Christoffel symbols of M
//   output Jacobians          J = dy/dq of a position output, dy/dqd of a velocity output, and
//                             the bias Jdot qd: the output's acceleration (or rate) at qdd = 0
//   regressor                 M qdd - F = Y pi + (loads other than gravity), ten pi per body
// docs/controller-functions.md gives each with its formula and sign.
#include <Eigen/Core>
#include <ginac/ginac.h>

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eomgen/derivation/articulated_body.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/mechanics/model.hpp"
#include "eomgen/symbolic/subexpressions.hpp"

namespace eomgen {

struct SymbolicLinearization;  // eomgen/derivation/linearization.hpp

/// The header has G and C for models of at most this many coordinates (C has n^3 terms).
inline constexpr std::size_t coriolis_matrix_limit = 12;

/// How a function of the header is computed.
///  - closed_form: from the equations' entries (Kane's M and F and what follows from them)
///  - recursions: by a recursive algorithm of the tree of bodies
enum class FunctionForm { closed_form, recursions };

const char* to_string(FunctionForm form);

/// One function's chosen form and its estimated operations per call, with the other form's
/// estimate (NaN where there is none).
struct FormChoice {
  FunctionForm form = FunctionForm::closed_form;
  double estimated_operations = 0;
  double estimated_operations_other = 0;
};

/// The Jacobian of one output, for an output whose components are positions (functions of q
/// and t) or velocities (linear in qd, as angular_velocity(B) or velocity(P)).
struct OutputJacobian {
  enum class Level { position, velocity };
  std::size_t output = 0;           ///< index into Model::outputs
  std::size_t first_component = 0;  ///< of its components in ModelEquations::outputs()
  Level level = Level::position;
  GiNaC::matrix jacobian;  ///< components x n: dy/dq (position) or dy/dqd (velocity)
  GiNaC::matrix bias;      ///< components x 1: ydd (position) or yd (velocity) at qdd = 0: Jdot qd (+ time terms)
};

/// The identifiable base parameters of the regressor: pi_base = combination pi, the columns of
/// Y kept (`independent`, in order) each standing for itself plus the multiples of the columns
/// that are their combinations; Y pi = Y_base pi_base with Y_base those columns of Y.
struct BaseParameters {
  std::vector<Eigen::Index> independent;
  Eigen::MatrixXd combination;     ///< r x npi
  std::vector<std::string> names;  ///< "BODY.Izz + 0.180625*OTHER.m", one per base parameter
};

/// The derivatives of the forward dynamics of an unconstrained model, qdd = M^-1 F (the
/// header's forward_dynamics_derivatives), in the form of fewer estimated operations.
struct ForwardDynamicsDerivatives {
  enum class Form {
    /// the chain rule through the recursive forward dynamics' own intermediates
    chain_rule_through_recursion,
    /// -M^-1 K, -M^-1 D and M^-1 B_u with one LDL^T factorization of M for every column, K, D
    /// and B_u those of the linearization (Lagrange's residual R = M qdd - F) at qdd = M^-1 F
    mass_matrix_and_linearization,
    /// the same solves, K, D and B_u by the chain rule through the Newton-Euler recursion of R
    /// at qdd = M^-1 F (a tree of bodies)
    mass_matrix_and_newton_euler,
  };
  /// qdd = M^-1 F itself, n x 1, from the intermediates the derivatives share (every form
  /// computes it on the way)
  GiNaC::matrix accelerations;
  GiNaC::matrix by_coordinates;  ///< dqdd/dq, n x n
  GiNaC::matrix by_rates;        ///< dqdd/dqd, n x n
  GiNaC::matrix by_inputs;       ///< dqdd/du, n x nu
  /// all positive exactly when M is positive definite (the generated code checks them)
  GiNaC::exvector pivots;
  Form form = Form::mass_matrix_and_linearization;
  double estimated_operations = 0;
  /// every form derived, with its estimate, in the order of Form
  std::vector<std::pair<Form, double>> candidates;
  /// the intermediates the entries refer to beyond the header's others, each set after those
  /// it refers to
  std::vector<std::unique_ptr<Subexpressions>> intermediates;
};

const char* to_string(ForwardDynamicsDerivatives::Form form);

struct HeaderFunctions {
  const ModelEquations* equations = nullptr;
  const SymbolicLinearization* linearization = nullptr;  ///< linearization_terms, when asked for

  GiNaC::matrix mass_matrix, forcing;  ///< M and F as the header computes them
  FormChoice mass_matrix_form;
  /// With forward_dynamics: whether the header tells the runtime to prefer it, from the
  /// estimates (M and F with the runtime's Cholesky path counted as 120 + 14 n^2 operations).
  std::optional<ForwardDynamics> forward_dynamics;
  std::string no_forward_dynamics;  ///< why there is none (constraints, not a tree)
  bool prefers_forward_dynamics = false;
  double mass_matrix_path_operations = 0;

  /// With a linearization and no constraints; or why there are none.
  std::optional<ForwardDynamicsDerivatives> forward_dynamics_derivatives;
  std::string no_forward_dynamics_derivatives;

  bool controller_functions = false;  ///< whether the functions below were derived (HeaderOptions)
  GiNaC::matrix inverse_dynamics;  ///< M qdd - F, n x 1
  FormChoice inverse_dynamics_form;

  /// g(q) = dV/dq and C(q, qd), or why the header has none (they need M and V free of t)
  std::optional<GiNaC::matrix> gravity_forces, coriolis_matrix;
  std::string no_coriolis_and_gravity;

  std::vector<OutputJacobian> output_jacobians;
  std::string no_output_jacobians;  ///< why there are none though outputs are positions, or empty

  /// Y of M qdd - F = Y pi + ..., pi the model's own inertial parameters, with their names and
  /// the point of each body they are about; or why there is none (the bodies form no tree)
  std::optional<GiNaC::matrix> regressor;
  GiNaC::matrix inertial_parameters;
  std::vector<std::string> inertial_parameter_names, inertial_parameter_origins;
  std::string no_regressor;
  /// the regressor reduced to the base parameters (HeaderOptions::base_regressor)
  std::optional<BaseParameters> base_parameters;

  /// Every set of intermediates the functions refer to, each after those it refers to.
  std::vector<const Subexpressions*> intermediates() const;

  // the intermediates derived here (recursions, derivatives), owned so that moving this object
  // keeps every pointer above valid
  std::vector<std::unique_ptr<Subexpressions>> owned;
};

/// The equations with every intermediate the functions derived here added to their own (one
/// list of intermediates, for printing), and `renamed` mapping each such intermediate to its
/// value there: substitute(term, renamed) refers a function's term to the merged list.
ModelEquations with_function_intermediates(const ModelEquations& equations, const HeaderFunctions& functions,
                                           GiNaC::exmap& renamed);

/// Which functions a header holds beyond those of every header (M, F, the constraint terms, the
/// energies, the outputs and the forward dynamics).
struct HeaderOptions {
  /// the inverse dynamics, G, C, the output Jacobians and the regressor (a simulation's program
  /// needs none of them, and compiles faster without)
  bool controller_functions = true;
  /// the regressor on the identifiable base parameters (`--regressor base`) instead of ten per body
  bool base_regressor = false;
  /// forward_dynamics_derivatives in that form, not the one of fewer operations (for tests and
  /// comparisons); none where the model does not admit it, no_forward_dynamics_derivatives saying why
  std::optional<ForwardDynamicsDerivatives::Form> forward_dynamics_derivatives_form;
};

/// Every function of the model's header. `linearization`, when given, is linearize_symbolic of
/// the same model and equations and must outlive the result, as must `equations`.
/// \throws DerivationError as derive_equations.
HeaderFunctions derive_header_functions(const Model& model, const ModelEquations& equations,
                                        const SymbolicLinearization* linearization = nullptr,
                                        const HeaderOptions& options = {});

}  // namespace eomgen
