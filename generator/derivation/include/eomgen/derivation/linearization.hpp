#pragma once
// Linearization of Lagrange's equations about an operating point (notes, appendix A.2.2) and
// the stability verdicts of appendix A.3, with or without constraints.
//
// With R(q, qd, qdd, u, t) = M(q) qdd - F(q, qd, u, t), a perturbation about (q0, qd0, u0)
// with qdd0 = M^{-1} F at the point satisfies, to first order, the second-order form of the
// notes' section 5.5,
//   M dqdd + D dqd + K dq = B_u du,   K = dR/dq, D = dR/dqd, B_u = dF/du   (at qdd = qdd0),
// and the first-order form x = [q; qd]:
//   A = [[0, 1], [-M^{-1} K, -M^{-1} D]],   B = [[0], [M^{-1} B_u]].
// Keeping qdd0 in K is what makes the linearization right at operating points that are not
// at rest (a spinning top, a rolling wheel): dM/dq qdd0 is part of dR/dq.
//
// With constraints, R = M qdd - F - Xi^T lambda and S = Xi qdd + b (b = dXi/dt qd + dXi_t/dt)
// define qdd and lambda implicitly; the implicit function theorem gives their exact
// derivatives, d[qdd; lambda] = -[[M, -Xi^T], [Xi, 0]]^{-1} d[R; S], hence A of the full state
// [q; qd]. The constraint manifold is invariant under the flow, so its tangent space at the
// point is invariant under that A: in coordinates of the tangent space, independent
// coordinates (one dependent coordinate per holonomic constraint) and independent speeds (one
// dependent rate per constraint, from the model's `independent` statement or chosen by a
// pivoted QR of Xi at the point), the reduced A has no multipliers and no dependent states.
//
// The derivatives are exact: every intermediate z_i of the derivation gets its derivatives
// dz_i/dv as intermediates of their own (the chain rule through the shared graph), so nothing
// is differenced and nothing is written out as a tree.
//
// The numbers from the derivatives to A and B go through the runtime's own code
// (eomrt/linearization.hpp, eomrt/kkt_system.hpp: the same KKT solve and regularity tests),
// which the generated code's linearization_terms feed as well.
#include <Eigen/Dense>
#include <ginac/ginac.h>

#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/derivation/operating_point.hpp"
#include "eomgen/symbolic/subexpressions.hpp"

namespace eomgen {

struct LinearizationProgram;  // linearization.cpp

/// The second-order form's matrices as expressions in the model's symbols, the accelerations
/// qdd (standing for the operating point's qdd0) and the intermediates of `derivatives`.
struct SymbolicLinearization {
  Subexpressions derivatives{"dz"};  ///< dz_i/dv of the derivation's intermediates (and theirs)
  GiNaC::matrix K;                   ///< dR/dq, n x n
  GiNaC::matrix D;                   ///< dR/dqd, n x n
  GiNaC::matrix B_u;                 ///< dF/du, n x n_u
  // with constraints (m rows of Xi; lambda stands for the point's multipliers):
  GiNaC::matrix S_q;                 ///< d(Xi qdd + b)/dq, m x n
  GiNaC::matrix S_qd;                ///< d(Xi qdd + b)/dqd, m x n
  GiNaC::matrix C_q;                 ///< d(Xi qd + Xi_t)/dq, m x n: the velocity constraint's
  std::vector<GiNaC::realsymbol> lambda;  ///< the multipliers' symbols in K (which holds -d(Xi^T lambda)/dq)
  /// coordinates that appear nowhere in M and F (their columns of K are structurally zero):
  /// cyclic, so they may be dropped from the state
  std::vector<bool> cyclic;
  /// M, F, Xi, Xi_t, b and the terms above compiled into one ExpressionTape, so that each
  /// further operating point (a sweep's) costs numbers only
  std::shared_ptr<const LinearizationProgram> program;
};

/// Differentiates R = M qdd - F of `eom` (derived from model.system).
SymbolicLinearization linearize_symbolic(const Model& model, const ModelEquations& eom);

/// A linear model about one operating point.
struct LinearModel {
  std::vector<std::string> state_names;  ///< the kept coordinates, then every rate (NAME_dot)
  std::vector<std::string> input_names;
  std::vector<std::string> dropped;      ///< cyclic coordinates left out of the state
  /// constrained models: the coordinates and rates the constraints determine (not states)
  std::vector<std::string> dependent;
  Eigen::MatrixXd A, B;                  ///< first-order form dx' = A dx + B du
  /// the first-order form on the full state [q; qd] before any reduction (with constraints:
  /// of the KKT accelerations), as eomrt::linearization gives it from the generated code
  Eigen::MatrixXd A_full, B_full;
  /// second-order form M dq'' + D dq' + K dq = B_u du in `second_order_coordinates`:
  /// - without constraints, over all coordinates (also when cyclic ones are dropped from A);
  /// - with constraints, the reduced form in the kept independent coordinates, where each is
  ///   paired with its rate as an independent speed (a bicycle's lean and steer): with G the
  ///   kept speeds' columns of the null space (dqd = G dnu + ...), M = G^T M_full G, the
  ///   generalized mass of Kane's equations, and D, K, B_u = M times the reduced A's and B's
  ///   blocks, so that the form is Kane's equations linearized. Empty where the kept
  ///   coordinates and speeds do not pair up; `no_second_order` then says why.
  Eigen::MatrixXd M, D, K, B_u;
  std::vector<std::string> second_order_coordinates;
  std::string no_second_order;
  Eigen::VectorXd qdd0;  ///< accelerations at the point: zero at equilibria and steady motions
  /// the point linearized about: the given values and, with constraints, those solved from
  /// them (satisfy_constraints, operating_point.hpp), whose names `solved` lists
  NamedValues point;
  std::vector<std::string> solved;
  /// given values that had to move because they admit no consistent state (a full guess only
  /// near the constraints): each with its given and its used value
  std::vector<MovedValue> moved;
};

struct LinearizeOptions {
  /// leave coordinates that appear nowhere in M and F out of A (with constraints: every state,
  /// coordinate or speed, whose column of the reduced A vanishes at the point, to
  /// operating_point_tolerance; each removes an eigenvalue 0, such as a bicycle's heading or
  /// its rear wheel's spin)
  bool drop_cyclic = false;
  /// starting values of coordinates and rates the point leaves out, for the constraints' solve:
  /// it takes the consistent state nearest them (which of two assemblies of a loop, say)
  NamedValues guesses;
};

/// Evaluates the linearization at an operating point (names as in numeric_substitution:
/// coordinates, NAME_dot rates, inputs, t, parameters; the rest 0 or default). With
/// constraints, the coordinates and rates the point leaves out are first solved from them
/// (satisfy_constraints).
/// \throws Error if M (or the KKT matrix) is singular at the point, if the point cannot be
///   brought onto the constraints (naming the constraint), or for unknown names
LinearModel linearize(const Model& model, const ModelEquations& eom, const SymbolicLinearization& symbolic,
                      const NamedValues& point, const LinearizeOptions& options = {});

/// An equilibrium (or steady motion) found by Newton's method.
struct Equilibrium {
  NamedValues point;      ///< the guess with its coordinates replaced by the solution
  Eigen::VectorXd lambda;  ///< multipliers holding it (dim m)
  double residual = 0;     ///< max |F + Xi^T lambda| and |phi| at the solution
  int iterations = 0;
};

/// Solves F(q, qd, u, t) + Xi^T lambda = 0 and phi(q, t) = 0 for q and lambda from the guess
/// (rates, inputs, t and parameters held at their given values: qd = 0 for a static
/// equilibrium, constant rates for a steady motion), by Newton's method with the exact
/// Jacobian [[-K, Xi^T], [Phi, 0]] (K from `symbolic` at qdd = 0), minimum-norm steps where the
/// equilibria form a family (a cart anywhere on its rail) and halved steps where a full one
/// does not reduce the residual.
/// \throws Error if Newton does not converge from the guess
Equilibrium find_equilibrium(const Model& model, const ModelEquations& eom, const SymbolicLinearization& symbolic,
                             const NamedValues& guess, int max_iterations = 50);

/// Verdicts on an equilibrium from the eigenvalues of A.
enum class LinearStability { asymptotically_stable, stable, unstable };      ///< Theorem A.21 (the linear system)
enum class LyapunovVerdict { asymptotically_stable, unstable, no_conclusion };  ///< Theorem A.22 (the nonlinear one)

struct StabilityReport {
  Eigen::VectorXcd eigenvalues;  ///< sorted by real part, descending
  LinearStability linear;
  LyapunovVerdict nonlinear;
};

/// Eigenvalues of A and both verdicts. An eigenvalue counts as on the imaginary axis when
/// |Re| <= tolerance * max(1, max |eigenvalue|); repeated eigenvalues there make the linear
/// system unstable unless A is diagonalizable on them (checked by the rank of A - lambda 1).
StabilityReport assess_stability(const Eigen::MatrixXd& A, double tolerance = 1e-9);

const char* to_string(LinearStability s);
const char* to_string(LyapunovVerdict v);

}  // namespace eomgen
