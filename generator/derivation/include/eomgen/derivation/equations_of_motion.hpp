#pragma once
// Lagrange's equations with Pfaffian constraints, M(q) qdd = F(q, qd, t, u) + Xi^T lambda,
// derived in Kane's form (partial velocities), which equals Lagrange's for holonomic
// coordinates and avoids differentiating the Lagrangian:
//   M_jk = sum_B m V_j . V_k + W_j . J W_k                     ( = d2T / dqd_j dqd_k )
//   F_k  = Q_k - sum_B m V_k . a0 + W_k . (J alpha0 + omega x J omega)
// with V_k, W_k the partial (angular) velocities and a0, alpha0 the accelerations at qdd = 0.
//
// The two forms are identical when every rotation's rate relation is Poisson's equation for all
// values of its parameters (principal rotations, Euler angles, Rodrigues and modified Rodrigues
// parameters). Quaternions and axis/angle satisfy it only on their norm constraint; there M is
// the same and F differs from literal Lagrange by a multiple of the constraint gradient, so the
// accelerations of the KKT system agree and only lambda differs (it is then zero for a norm
// constraint that transmits no force, as it should be).
#include <ginac/ginac.h>

#include <limits>

#include "eomgen/mechanics/mechanical_system.hpp"
#include "eomgen/symbolic/subexpressions.hpp"

namespace eomgen {

/// Where the derivation resolves the vectors of points (positions, partial velocities,
/// accelerations).
///  - inertial: in the inertial frame, each bound to a shared intermediate. Linear in the size of
///    the shared graph: the form for long chains.
///  - local: each term stays in the frame it arose in, and the entries of M, F, T and V are
///    multiplied out. Dot products then bring only relative rotations (a run of principal rotations
///    about one axis as one angle), a body's own angle cancels as in a hand derivation, and
///    parameter-only products collect into coefficients computed once per parameter set. Its
///    size grows like the fourth power of a chain's depth: the form for small models.
/// derive_equations tries both on models of at most local_resolution_limit coordinates, unless an
/// entry of the local form would multiply out too large, and keeps the one whose M and F take
/// fewer estimated operations.
enum class KinematicsResolution { inertial, local };

/// Models with more coordinates than this are derived in the inertial resolution only.
inline constexpr std::size_t local_resolution_limit = 12;

/// How M and F were derived.
///  - closed_form: Kane's equations above, each entry a sum over the bodies that move with both
///    its coordinates (in the resolution kept). A chain's entries grow with its depth: n^3/6
///    terms in all.
///  - recursions: the composite-rigid-body algorithm for M and Newton-Euler at qdd = 0 for F
///    (composite_body.hpp), each entry a few operations on shared intermediates: n^2/2 entries.
/// derive_equations takes the recursions for a tree without constraints of more than
/// local_resolution_limit coordinates, whose closed form would be the larger (generated code
/// took the recursions there already; composite_body_test compares the two).
enum class DynamicsForm { closed_form, recursions };

/// The derived equations. Every matrix may refer to the intermediates of `subexpressions`.
struct EquationsOfMotion {
  Subexpressions subexpressions;
  GiNaC::matrix mass_matrix;                   ///< M, n x n, symmetric
  GiNaC::matrix forcing;                       ///< F, n x 1
  GiNaC::matrix constraint_jacobian;           ///< Xi, m x n
  GiNaC::matrix constraint_rate_term;          ///< Xi_t, m x 1
  GiNaC::matrix constraint_acceleration_term;  ///< dXi/dt qd + dXi_t/dt, m x 1
  GiNaC::matrix holonomic_residuals;           ///< phi(q, t) of the holonomic rows, m_h x 1
  GiNaC::ex kinetic_energy;                    ///< T
  GiNaC::ex potential_energy;                  ///< V
  std::size_t coordinate_count = 0;            ///< n
  std::size_t constraint_count = 0;            ///< m
  KinematicsResolution resolution = KinematicsResolution::inertial;  ///< the form kept
  DynamicsForm dynamics = DynamicsForm::closed_form;                 ///< how M and F were derived
  /// Estimated operations of M and F in each form (NaN for a form not derived, or given up); see
  /// KinematicsResolution.
  double estimated_operations_inertial = 0, estimated_operations_local = 0;
  /// Estimated operations of M and F from the recursions, when they are the form kept (else NaN).
  double estimated_operations_recursions = std::numeric_limits<double>::quiet_NaN();
};

/// Derives the equations of motion. Pure: the system is only read.
/// \throws DerivationError if an expression cannot be differentiated (e.g. an input in a rotation).
EquationsOfMotion derive_equations(const MechanicalSystem& system);

/// The equations in the given resolution only (for comparisons and benchmarks). In the local
/// resolution, where an entry would multiply out too large, the entries stay the sums they
/// arose as (still the equations) and the local estimate is NaN; derive_equations(system) then
/// keeps the inertial form.
EquationsOfMotion derive_equations(const MechanicalSystem& system, KinematicsResolution resolution);

}  // namespace eomgen
