#pragma once
/// \file
/// Assembly: the consistent state nearest a requested one (docs/conventions.md, "Assembly").
///
/// The caller gives a state [q; qd] and says which of its entries it holds (the values a user
/// gave) and which are guesses. Assembly keeps every held value and moves the guesses as little
/// as possible until
///   phi(q, t) = 0   and   Xi(q, t) qd + Xi_t(q, t) = 0,
/// distances measured with weights sqrt(M_jj) taken at the request, so that metres and radians
/// compare by the kinetic energy they carry (a light wheel's angle moves before a heavy
/// chassis' position).
///
/// Positions: a damped Newton restoration onto phi = 0 from the request, with minimum-norm
/// steps in that metric (so the iterate leaves the request as little as each step allows, and
/// stays on the branch of the mechanism nearest it, where plain Newton from zeros may jump to
/// another), then Gauss-Newton steps toward the nearest consistent point: each solves the
/// constraints linearized at the current point for the point nearest the request, and is
/// restored onto phi = 0 and kept only if it comes nearer. Rates: the same problem is linear,
/// one solve. Every solve is of minimum norm and rank-revealing (eomrt/minimum_norm.hpp), so
/// redundant rows and singular configurations cost nothing but their rank.
///
/// Where the held values admit no solution (three given angles of a four-bar that do not close
/// its loop, a given forward speed and wheel rate that disagree), they are released: held
/// entries then weigh `held_weight` times more than guesses, everything moves, and the report
/// says so; the caller names what moved. Rates are first solved with the preferred entries held
/// too (the declared independent speeds a caller did not give stay at their guesses), then
/// without them, then released.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "eomrt/lu_factorization.hpp"
#include "eomrt/minimum_norm.hpp"
#include "eomrt/model_traits.hpp"
#include "eomrt/regularity.hpp"

namespace eomrt {

/// How assembly ended.
enum class AssemblyStatus {
  ok,                 ///< consistent, every held value kept
  held_values_moved,  ///< consistent, but held values had to move (the report says which part)
  unreachable,        ///< no consistent state found (the report names the worst row)
  non_finite,         ///< a term was NaN or infinite on the way
};

/// A short English description of a status.
inline const char* describe(AssemblyStatus s) {
  switch (s) {
    case AssemblyStatus::ok:
      return "consistent, every given value kept";
    case AssemblyStatus::held_values_moved:
      return "consistent, but the given values could not all be kept";
    case AssemblyStatus::unreachable:
      return "no state near the request satisfies the constraints";
    case AssemblyStatus::non_finite:
      return "a term is not a finite number near the request";
  }
  return "unknown status";
}

/// Settings of assembly.
template <class Scalar>
struct AssemblyOptions {
  /// largest accepted |phi_i| and |(Xi qd + Xi_t)_i|, relative to 1 plus the size of the row's
  /// terms (sum_j |Xi_ij| (1 + |q_j|), respectively sum_j |Xi_ij qd_j| + |Xi_t_i|)
  Scalar tolerance = Scalar(1e-10);
  int max_iterations = 50;  ///< Newton iterations per restoration, and Gauss-Newton steps
  /// how much more a held value weighs than a guess once held values must move
  Scalar held_weight = Scalar(100);
};

/// What assembly did.
template <class Scalar>
struct AssemblyReport {
  AssemblyStatus status = AssemblyStatus::ok;
  bool positions_released = false;  ///< the held coordinates had to move
  bool rates_released = false;      ///< the held rates had to move
  /// unreachable: the row of Xi (a constraint) with the largest relative residual, and that
  /// residual (absolute); -1 where none
  int worst_row = -1;
  Scalar worst_residual = Scalar(0);
  bool worst_is_position = false;  ///< the worst row's residual is phi's, not Xi qd + Xi_t's
  int evaluations = 0;             ///< of the constraint terms
};

namespace detail {

/// The assembly of one constraint problem (see the file comment). Problem provides the Eigen
/// types Coordinates (nq), Holonomic (nh), Gradients (nh x nq), Constraints (nc) and Jacobian
/// (nc x nq), fixed or dynamic, and
///   bool positions(const Coordinates& q, Holonomic& phi, Gradients& Phi)  (phi and dphi/dq)
///   bool rates(const Coordinates& q, Jacobian& Xi, Constraints& Xi_t)
///   bool mass_diagonal(const Coordinates& q, Coordinates& d)
/// each false where a term is not finite, and holonomic_count(), constraint_count() and
/// holonomic_row(k), the row of Xi of phi_k.
template <class Problem>
class Assembly {
 public:
  using Coordinates = typename Problem::Coordinates;
  using Holonomic = typename Problem::Holonomic;
  using Gradients = typename Problem::Gradients;
  using Constraints = typename Problem::Constraints;
  using Jacobian = typename Problem::Jacobian;
  using Scalar = typename Coordinates::Scalar;
  using Mask = Eigen::Array<bool, Coordinates::RowsAtCompileTime, 1>;

  Assembly(Problem& problem, const AssemblyOptions<Scalar>& options) : problem_(problem), options_(options) {
    // rows dependent to rounding (a redundant closure, a singular configuration) count as
    // dependent, by the threshold every other solve of the runtime uses (regularity.hpp)
    minimum_norm_.set_threshold(default_singular_rcond<Scalar>());
    minimum_norm_rates_.set_threshold(default_singular_rcond<Scalar>());
  }

  /// Assembles q and qd in place (see the file comment); q_held, qd_held: the given entries,
  /// qd_preferred: entries also held on the first attempt at the rates.
  AssemblyReport<Scalar> run(Coordinates& q, Coordinates& qd, const Mask& q_held, const Mask& qd_held,
                             const Mask& qd_preferred) {
    report_ = {};
    if (!problem_.mass_diagonal(q, weights_)) return failed(AssemblyStatus::non_finite);
    const Scalar largest = weights_.size() > 0 ? Scalar(weights_.cwiseAbs().maxCoeff()) : Scalar(0);
    const Scalar floor = largest > 0 ? Scalar(largest * Scalar(1e-6)) : Scalar(1);
    using std::sqrt;
    for (Eigen::Index j = 0; j < weights_.size(); ++j) {
      using std::abs;
      weights_(j) = sqrt(abs(weights_(j)) > floor ? Scalar(abs(weights_(j))) : floor);
    }
    if (!assemble_positions(q, q_held)) return report_;
    assemble_rates(q, qd, qd_held, qd_preferred);
    return report_;
  }

  /// after run(): the coordinates and rates a solve determined (left free, with a nonzero
  /// column in the constraints), held ones that were released included
  const Mask& solved_coordinates() const { return solved_q_; }
  const Mask& solved_rates() const { return solved_qd_; }

 private:
  AssemblyReport<Scalar>& failed(AssemblyStatus status) {
    report_.status = status;
    return report_;
  }

  /// the scaling S of the free columns: 1/w for a guess, 0 for a held entry, or 1/(held_weight
  /// w) for one released
  void scaling(const Mask& held, bool released, Coordinates& s) const {
    s.resize(weights_.size());
    for (Eigen::Index j = 0; j < s.size(); ++j)
      s(j) = !held(j) ? Scalar(1) / weights_(j) : released ? Scalar(1) / (options_.held_weight * weights_(j)) : Scalar(0);
  }

  /// max_i |r_i| / (1 + sum_j |X_ij| size_j + extra_i) and its row
  template <class Residual, class Matrix, class Size, class Extra>
  static Scalar relative_violation(const Residual& r, const Matrix& X, const Size& size, const Extra& extra,
                                   Eigen::Index* row = nullptr) {
    Scalar worst = 0;
    for (Eigen::Index i = 0; i < r.size(); ++i) {
      using std::abs;
      const Scalar v = abs(r(i)) / (Scalar(1) + (X.row(i).cwiseAbs() * size).value() + abs(extra(i)));
      if (!(v <= worst)) {  // NaN counts as worst
        worst = v;
        if (row) *row = i;
      }
    }
    return worst;
  }

  Scalar phi_violation(const Coordinates& q, Eigen::Index* row = nullptr) const {
    return relative_violation(phi_, Phi_, (q.cwiseAbs().array() + Scalar(1)).matrix(), Holonomic::Zero(phi_.size()),
                              row);
  }

  /// the weighted distance from the request, over the entries scaled by s
  Scalar distance(const Coordinates& q, const Coordinates& q0, const Coordinates& s) const {
    Scalar d = 0;
    for (Eigen::Index j = 0; j < q.size(); ++j)
      if (s(j) != 0) d += (q(j) - q0(j)) * (q(j) - q0(j)) / (s(j) * s(j));
    return d;
  }

  bool evaluate_positions(const Coordinates& q) {
    ++report_.evaluations;
    return problem_.positions(q, phi_, Phi_);
  }

  /// Levenberg-Marquardt from q onto phi = 0, steps of minimum S-weighted norm (the columns S
  /// leaves out stay): the damping shortens the steps where the constraint gradients are near
  /// singular (between two assemblies of a loop), where a Newton step would leap to any branch,
  /// and vanishes near the solution, where the steps become Newton's. phi_ and Phi_ hold the end
  /// point's terms. \return whether it converged.
  bool restore(Coordinates& q, const Coordinates& s) {
    if (!evaluate_positions(q)) return false;
    const Scalar eps = std::numeric_limits<Scalar>::epsilon();
    Scalar mu = -1;
    for (int k = 0; k < options_.max_iterations; ++k) {
      const Scalar violation = phi_violation(q);
      if (violation <= 16 * eps) return true;
      A_ = Phi_ * s.asDiagonal();
      gram_.noalias() = A_ * A_.transpose();
      const Scalar scale = gram_.size() > 0 ? Scalar(gram_.diagonal().cwiseAbs().maxCoeff()) : Scalar(0);
      if (!(scale > 0)) return violation <= options_.tolerance;  // nothing left free moves phi
      // damped in proportion to how far off phi is: Newton's own steps close to the solution
      if (mu < 0) mu = scale * std::min(Scalar(1), Scalar(1000) * violation);
      const Scalar norm = phi_.norm();
      phi0_ = phi_;
      bool reduced = false;
      for (int attempt = 0; attempt < 30 && !reduced; ++attempt) {
        damped_ = gram_;
        damped_.diagonal().array() += mu;
        damped_lu_.compute(damped_);
        multipliers_ = phi_;
        damped_lu_.solve_in_place(multipliers_);
        step_ = -(s.asDiagonal() * (A_.transpose() * multipliers_));
        // Newton converges quadratically: once the step is at rounding level of q, phi is too
        if (step_.cwiseAbs().maxCoeff() <= 4 * eps * (1 + q.cwiseAbs().maxCoeff())) {
          if (mu > Scalar(1e-12) * scale) {  // a step damped to nothing, not Newton's
            mu = Scalar(1e-12) * scale;
            continue;
          }
          return violation <= options_.tolerance;
        }
        // the reduction of |phi|^2 the linearization predicts, and the one the step achieves:
        // a step whose ratio is poor left the region where the linearization holds (a leap
        // that may land on another branch) and is shortened
        predicted_ = phi0_ + Phi_ * step_;
        const Scalar predicted = norm * norm - predicted_.squaredNorm();
        trial_ = q + step_;
        if (evaluate_positions(trial_) && phi_.allFinite() &&
            norm * norm - phi_.squaredNorm() > Scalar(0.25) * predicted && phi_.norm() < norm) {
          reduced = true;
          mu = std::max(mu / 10, Scalar(1e-15) * scale);
        } else {
          mu *= 4;
          evaluate_positions(q);
        }
      }
      if (!reduced) {
        evaluate_positions(q);
        return phi_violation(q) <= options_.tolerance;
      }
      q = trial_;
    }
    return phi_violation(q) <= options_.tolerance;
  }

  /// Restoration, then Gauss-Newton steps toward the consistent point nearest q0 (see the file
  /// comment). \return whether q is consistent.
  bool nearest(Coordinates& q, const Coordinates& q0, const Coordinates& s) {
    q = q0;
    if (!restore(q, s)) return false;
    const Scalar eps = std::numeric_limits<Scalar>::epsilon();
    Scalar d = distance(q, q0, s);
    for (int k = 0; k < options_.max_iterations; ++k) {
      // the point nearest q0 where the constraints linearized at q hold: q0 + S y with
      // Phi S y = -(phi + Phi (q0 - q)), y of minimum norm
      A_ = Phi_ * s.asDiagonal();
      minimum_norm_.compute(A_);
      offset_ = q0 - q;
      residual_ = phi_ + Phi_ * offset_;
      minimum_norm_.solve(residual_, y_);
      step_ = offset_ - s.asDiagonal() * y_;
      if (step_.cwiseAbs().maxCoeff() <= 64 * eps * (1 + q.cwiseAbs().maxCoeff())) break;
      bool nearer = false;
      for (Scalar alpha = 1; alpha >= Scalar(1) / 64 && !nearer; alpha /= 2) {
        candidate_ = q + alpha * step_;
        if (!restore(candidate_, s)) continue;
        const Scalar dc = distance(candidate_, q0, s);
        if (dc < d) nearer = true, d = dc;
      }
      if (!nearer) break;
      q = candidate_;
    }
    return evaluate_positions(q) && phi_violation(q) <= options_.tolerance;
  }

  /// the entries scaled by s whose column of X is not zero: those a solve determined
  template <class Matrix>
  static void determined(const Coordinates& s, const Matrix& X, Mask& out) {
    out = Mask::Constant(s.size(), false);
    for (Eigen::Index j = 0; j < s.size(); ++j) out(j) = s(j) != 0 && !X.col(j).isZero(0);
  }

  bool assemble_positions(Coordinates& q, const Mask& held) {
    solved_q_ = Mask::Constant(q.size(), false);
    if constexpr (Holonomic::RowsAtCompileTime == 0) {
      (void)held;  // a fixed size without holonomic rows: no position phase to compile
      return true;
    } else {
      if (problem_.holonomic_count() == 0) return true;
      if (!evaluate_positions(q)) return failed(AssemblyStatus::non_finite), false;
      if (phi_violation(q) <= options_.tolerance) return true;  // consistent already: left as given
      const Coordinates q0 = q;
      Coordinates s;
      scaling(held, false, s);
      if (nearest(q, q0, s)) return determined(s, Phi_, solved_q_), true;
      scaling(held, true, s);
      report_.positions_released = held.any();
      if (held.any() && nearest(q, q0, s)) {
        report_.status = AssemblyStatus::held_values_moved;
        determined(s, Phi_, solved_q_);
        return true;
      }
      if (!evaluate_positions(q) || !phi_.allFinite()) {
        q = q0;
        failed(AssemblyStatus::non_finite);
        return false;
      }
      // the residual where the released search ended, the nearest it came to closing
      Eigen::Index row = 0;
      phi_violation(q, &row);
      report_.status = AssemblyStatus::unreachable;
      report_.worst_row = problem_.holonomic_row(row);
      report_.worst_residual = phi_(row);
      report_.worst_is_position = true;
      q = q0;
      return false;
    
    }
  }

  /// qd0 + S y with Xi S y = -(Xi qd0 + Xi_t), y of minimum norm; \return whether it holds
  bool solve_rates(const Coordinates& qd0, const Coordinates& s, Coordinates& qd, Eigen::Index& row) {
    A_rates_ = Xi_ * s.asDiagonal();
    minimum_norm_rates_.compute(A_rates_);
    c_ = Xi_ * qd0 + Xi_t_;
    minimum_norm_rates_.solve(c_, y_);
    qd = qd0 - s.asDiagonal() * y_;
    c_ = Xi_ * qd + Xi_t_;
    return qd.allFinite() && relative_violation(c_, Xi_, qd.cwiseAbs(), Xi_t_, &row) <= options_.tolerance;
  }

  void assemble_rates(const Coordinates& q, Coordinates& qd, const Mask& held, const Mask& preferred) {
    solved_qd_ = Mask::Constant(qd.size(), false);
    if (problem_.constraint_count() == 0) return;
    ++report_.evaluations;
    if (!problem_.rates(q, Xi_, Xi_t_)) {
      failed(AssemblyStatus::non_finite);
      return;
    }
    Eigen::Index row = 0;
    c_ = Xi_ * qd + Xi_t_;
    if (qd.allFinite() && relative_violation(c_, Xi_, qd.cwiseAbs(), Xi_t_) <= options_.tolerance) return;
    const Coordinates qd0 = qd;
    Coordinates s, solved;
    const Mask with_preferred = held || preferred;
    scaling(with_preferred, false, s);
    if (solve_rates(qd0, s, solved, row)) {
      qd = solved;
      determined(s, Xi_, solved_qd_);
      return;
    }
    scaling(held, false, s);
    if ((preferred && !held).any() && solve_rates(qd0, s, solved, row)) {
      qd = solved;
      determined(s, Xi_, solved_qd_);
      return;
    }
    if (held.any()) {
      scaling(held, true, s);
      report_.rates_released = true;
      if (solve_rates(qd0, s, solved, row)) {
        qd = solved;
        report_.status = AssemblyStatus::held_values_moved;
        determined(s, Xi_, solved_qd_);
        return;
      }
    }
    report_.status = solved.allFinite() ? AssemblyStatus::unreachable : AssemblyStatus::non_finite;
    report_.worst_row = static_cast<int>(row);
    report_.worst_residual = c_(row);
    report_.worst_is_position = false;
  }

  Problem& problem_;
  const AssemblyOptions<Scalar>& options_;
  AssemblyReport<Scalar> report_;
  Mask solved_q_, solved_qd_;
  Coordinates weights_, step_, trial_, candidate_, offset_, y_;
  Holonomic phi_, phi0_, predicted_, residual_, multipliers_;
  Gradients Phi_;
  Jacobian Xi_;
  Constraints Xi_t_, c_;
  Gradients A_;
  using Gram = Eigen::Matrix<Scalar, Gradients::RowsAtCompileTime, Gradients::RowsAtCompileTime>;
  Gram gram_, damped_;
  LuFactorization<Scalar, Gram::RowsAtCompileTime> damped_lu_;
  Jacobian A_rates_;
  MinimumNormSolver<Gradients> minimum_norm_;
  MinimumNormSolver<Jacobian> minimum_norm_rates_;
};

/// The constraint terms of a model at one time and parameter set, as Assembly asks for them.
template <class Model, class Scalar, class ParametersOrConstants>
class ModelConstraintTerms {
  using Types = ModelTypes<Model, Scalar>;
  // a model without holonomic rows never evaluates them: Assembly compiles no position phase
  // for its fixed types of zero rows (dynamic ones would instantiate Eigen's general products)
  static constexpr int nh_fixed = Model::nh;

 public:
  using Coordinates = typename Types::Coordinates;
  using Holonomic = Eigen::Matrix<Scalar, nh_fixed, 1>;
  using Gradients = Eigen::Matrix<Scalar, nh_fixed, Model::nq>;
  using Constraints = typename Types::ConstraintVector;
  using Jacobian = typename Types::ConstraintJacobian;

  ModelConstraintTerms(const ParametersOrConstants& p, const Scalar& t) : p_(p), t_(t) {}

  Eigen::Index holonomic_count() const { return Model::nh; }
  Eigen::Index constraint_count() const { return Model::nc; }
  int holonomic_row(Eigen::Index k) const {
    if constexpr (Model::nh > 0)
      return Model::holonomic_rows[static_cast<std::size_t>(k)];
    else
      return static_cast<int>(k);
  }

  bool positions(const Coordinates& q, Holonomic& phi, Gradients& Phi) {
    if constexpr (Model::nh > 0) {
      Model::holonomic_residuals(t_, q, p_, phi);
      Model::constraint_jacobian(t_, q, p_, xi_);
      for (int k = 0; k < Model::nh; ++k) Phi.row(k) = xi_.row(Model::holonomic_rows[static_cast<std::size_t>(k)]);
      return phi.allFinite() && Phi.allFinite();
    } else {
      (void)q, (void)phi, (void)Phi;
      return true;
    }
  }

  bool rates(const Coordinates& q, Jacobian& Xi, Constraints& Xi_t) {
    Model::constraint_jacobian(t_, q, p_, Xi);
    Model::constraint_rate_term(t_, q, p_, Xi_t);
    return Xi.allFinite() && Xi_t.allFinite();
  }

  bool mass_diagonal(const Coordinates& q, Coordinates& d) {
    const Coordinates zero = Coordinates::Zero();
    const typename Types::Inputs u = Types::Inputs::Zero();
    Model::mass_matrix_and_forcing(t_, q, zero, u, p_, m_, f_);
    d = m_.diagonal();
    return d.allFinite();
  }

 private:
  const ParametersOrConstants& p_;
  Scalar t_;
  Jacobian xi_;
  typename Types::MassMatrix m_;
  typename Types::Coordinates f_;
};

}  // namespace detail

/// Which entries of a state [q; qd] a caller holds (gave), the others being guesses.
template <class Model>
using HeldEntries = Eigen::Array<bool, 2 * Model::nq, 1>;

/// Assembles a model's state in place: the consistent state nearest x, holding the entries
/// `held` marks (see the file comment). The declared independent speeds (Model::independent_
/// speeds) not held stay at their guesses where the constraints allow. Without constraints x
/// is left as it is. Needs no heap with the model's fixed sizes.
/// \param[in]     p        parameters, or their Constants (model_traits.hpp)
/// \param[in]     t        time
/// \param[in,out] x        the request [q; qd] on entry, the assembled state on return (the
///                         request where the status is unreachable or non_finite for positions)
/// \param[in]     held     the entries given, to keep
/// \param[in]     options  tolerance and iterations
/// \return what was done: ok, held_values_moved (x consistent, some held entries moved: compare
///         with the request), unreachable (worst_row names the constraint) or non_finite
template <class Model, class Scalar,
          class ParametersOrConstants = typename ModelTypes<Model, Scalar>::Parameters>
AssemblyReport<Scalar> assemble(const ParametersOrConstants& p, const Scalar& t,
                                typename ModelTypes<Model, Scalar>::State& x, const HeldEntries<Model>& held,
                                const AssemblyOptions<Scalar>& options = {}) {
  static_assert(is_parameter_argument_v<Model, Scalar, ParametersOrConstants>,
                "eomrt: p must be the model's Parameters or its Constants");
  if constexpr (Model::nc == 0) {
    (void)p, (void)t, (void)x, (void)held, (void)options;
    return {};
  } else {
    constexpr int nq = Model::nq;
    using Terms = detail::ModelConstraintTerms<Model, Scalar, ParametersOrConstants>;
    Terms terms(p, t);
    typename Terms::Coordinates q = x.template head<nq>(), qd = x.template tail<nq>();
    typename detail::Assembly<Terms>::Mask preferred = decltype(preferred)::Constant(false);
    if constexpr (has_independent_speeds_v<Model>)
      for (int k : Model::independent_speeds) preferred(k) = true;
    const AssemblyReport<Scalar> report = detail::Assembly<Terms>(terms, options)
                                              .run(q, qd, held.template head<nq>(), held.template tail<nq>(), preferred);
    x << q, qd;
    return report;
  }
}

}  // namespace eomrt
