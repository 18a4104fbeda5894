#pragma once
// The derived equations in numbers at one state, and the accelerations and multipliers they
// imply. For checking a model by hand and for tests (the CLI's `eval`); every call
// substitutes into GiNaC expressions, so this is not the way to simulate.
#include <Eigen/Dense>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "eomgen/symbolic/double_evaluator.hpp"
#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/derivation/header_functions.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomrt/kkt_system.hpp"

namespace eomgen {

/// Numbers by name: coordinates ("q1"), rates ("q1_dot"), inputs, time "t", and parameters
/// (overriding their defaults).
using NamedValues = std::map<std::string, double>;

/// M, F, ... of EquationsOfMotion evaluated at one state; sizes n coordinates, m constraints,
/// m_h holonomic constraints.
struct NumericEquations {
  Eigen::MatrixXd mass_matrix;                   ///< M, n x n
  Eigen::VectorXd forcing;                       ///< F, n
  Eigen::MatrixXd constraint_jacobian;           ///< Xi, m x n
  Eigen::VectorXd constraint_rate_term;          ///< Xi_t, m
  Eigen::VectorXd constraint_acceleration_term;  ///< dXi/dt qd + dXi_t/dt, m
  Eigen::VectorXd holonomic_residuals;           ///< phi, m_h
  double kinetic_energy = 0.0;                   ///< T
  double potential_energy = 0.0;                 ///< V
  /// (label, value) of every output component, in the model's order ("tip_1", "tip_2", ...).
  std::vector<std::pair<std::string, double>> outputs;
};

/// The functions for controllers (header_functions.hpp) in numbers at one state and accelerations.
struct NumericControllerFunctions {
  Eigen::VectorXd inverse_dynamics;           ///< M qdd - F, n
  Eigen::MatrixXd gravity_forces, coriolis_matrix;  ///< G (n) and C (n x n); empty where the model has none
  struct OutputJacobian {
    std::string output;  ///< the output's name
    Eigen::MatrixXd jacobian;
    Eigen::VectorXd bias;
  };
  std::vector<OutputJacobian> output_jacobians;
  Eigen::MatrixXd regressor;           ///< Y, n x npi; empty where the model has none
  Eigen::VectorXd inertial_parameters;  ///< pi
};

/// Evaluates `functions` (derive_header_functions of the same model and equations) at the state
/// `values` and the accelerations `qdd`.
/// \throws Error as evaluate_equations.
NumericControllerFunctions evaluate_controller_functions(const Model& model, const ModelEquations& eom,
                                                         const HeaderFunctions& functions, const NamedValues& values,
                                                         const Eigen::VectorXd& qdd);

/// Accelerations and multipliers of M qdd = F + Xi^T lambda, Xi qdd + (dXi/dt qd + dXi_t/dt) = 0.
struct AccelerationSolution {
  Eigen::VectorXd qdd;     ///< dim n
  Eigen::VectorXd lambda;  ///< dim m (empty without constraints)
};

/// The substitution symbol -> number for a state: coordinates, rates, inputs and t default to
/// 0, parameters to their default values.
/// \throws Error for a name that is not a coordinate, rate, input, parameter or "t"; the
///   message lists the accepted names.
GiNaC::exmap numeric_substitution(const Model& model, const NamedValues& values);

/// A double evaluator holding the state `values` (see numeric_substitution) and every
/// intermediate of `eom` computed from it, in order.
/// \throws Error as numeric_substitution does, or for an intermediate that is not real
DoubleEvaluator evaluator_at(const Model& model, const ModelEquations& eom, const NamedValues& values);

/// Every entry of m as a finite double; `name` names m in messages.
/// \throws Error for an entry that is not a finite real number
Eigen::MatrixXd evaluate_matrix(const GiNaC::matrix& m, const DoubleEvaluator& eval, const std::string& name);

/// Evaluates every part of `eom` (derived from model.system) and the model's outputs at the
/// state `values` (see numeric_substitution).
/// \throws Error as numeric_substitution does, or naming the entry that is not a finite real
///   number at this state (a division by zero, a square root of a negative number).
NumericEquations evaluate_equations(const Model& model, const ModelEquations& eom,
                                    const NamedValues& values);

/// The KKT matrix [[M, -Xi^T], [-Xi, 0]] of docs/conventions.md at the state of `equations`,
/// factorized by the runtime's KktSystem, so that the generator and the generated code's
/// runtime find the same states singular.
/// \throws Error if the KKT matrix is singular (its rank in the message): the constraints are
///   dependent, or M is singular on the directions they allow.
eomrt::KktSystem<double> factorize_kkt(const NumericEquations& equations);

/// Solves for qdd and lambda. Without constraints: M qdd = F by Cholesky, M tested as the
/// runtime does (eomrt::cholesky_is_regular). With them: the KKT system of docs/conventions.md,
/// [[M, -Xi^T], [-Xi, 0]] [qdd; lambda] = [F; dXi/dt qd + dXi_t/dt] (factorize_kkt), so that a
/// singular M with a regular KKT matrix (quaternion attitude with its norm constraint) works.
/// \throws Error if M is not positive definite (no constraints) or the KKT matrix is singular.
AccelerationSolution solve_accelerations(const NumericEquations& equations);

/// Why M is singular at the state `values` (of a model without constraints), for a message:
/// a coordinate singularity (M regular at nearby states: the gimbal lock of Euler angles),
/// naming the coordinates of M's null direction; or coordinates that are redundant everywhere.
std::string explain_singular_mass_matrix(const Model& model, const ModelEquations& eom, const NamedValues& values,
                                         const Eigen::MatrixXd& mass_matrix);

/// The KKT solve of solve_accelerations with `kkt` = factorize_kkt(equations) already at hand.
AccelerationSolution solve_accelerations(const NumericEquations& equations, const eomrt::KktSystem<double>& kkt);

}  // namespace eomgen
