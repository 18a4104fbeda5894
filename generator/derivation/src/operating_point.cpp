#include "eomgen/derivation/operating_point.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "eomgen/base/error.hpp"
#include "eomgen/mechanics/variables.hpp"

namespace eomgen {

namespace {

using Indices = std::vector<Eigen::Index>;

bool is_among(const Indices& set, Eigen::Index i) { return std::find(set.begin(), set.end(), i) != set.end(); }


/// Up to `count` of `candidates` whose columns of `a` a column-pivoted QR takes first, skipping
/// columns that add nothing to the rank; in increasing order.
Indices pivoted(const Eigen::MatrixXd& a, const Indices& candidates, Eigen::Index count) {
  if (candidates.empty() || count <= 0) return {};
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Eigen::MatrixXd(a(Eigen::all, candidates)));
  qr.setThreshold(1e-12);
  Indices chosen;
  for (Eigen::Index i = 0; i < std::min(count, qr.rank()); ++i)
    chosen.push_back(candidates[static_cast<std::size_t>(qr.colsPermutation().indices()(i))]);
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

class Completion {
 public:
  using Evaluate = std::function<NumericEquations(const NamedValues&)>;
  Completion(const Model& model, const Evaluate& evaluate, const NamedValues& given)
      : model_(model), evaluate_(evaluate), coordinates_(model.system.variables().coordinates()) {
    result_.point = given;
    const auto& constraints = model.system.constraints();
    for (std::size_t r = 0; r < constraints.size(); ++r)
      if (constraints[r].kind == Constraint::Kind::holonomic) holonomic_.push_back(static_cast<Eigen::Index>(r));
    for (std::size_t j = 0; j < coordinates_.size(); ++j) {
      const auto index = static_cast<Eigen::Index>(j);
      if (!given.count(coordinates_[j].name)) free_q_.push_back(index);
      if (!given.count(coordinates_[j].name + "_dot")) free_qd_.push_back(index);
    }
  }

  ConstrainedPoint run() {
    solve_coordinates();
    solve_rates();
    require_satisfied();
    return result_;
  }

 private:
  double value(const std::string& name) const {
    const auto it = result_.point.find(name);
    return it == result_.point.end() ? 0.0 : it->second;
  }
  std::string q_name(Eigen::Index j) const { return coordinates_[static_cast<std::size_t>(j)].name; }
  std::string qd_name(Eigen::Index j) const { return q_name(j) + "_dot"; }
  Eigen::VectorXd rates() const {
    Eigen::VectorXd qd(static_cast<Eigen::Index>(coordinates_.size()));
    for (Eigen::Index j = 0; j < qd.size(); ++j) qd(j) = value(qd_name(j));
    return qd;
  }

  /// phi = 0 for one free coordinate per holonomic constraint, by Newton's method with halved
  /// steps (the constraint gradients are the holonomic rows of Xi)
  void solve_coordinates() {
    const Eigen::Index nh = static_cast<Eigen::Index>(holonomic_.size());
    if (nh == 0) return;
    NumericEquations e = evaluate_(result_.point);
    if (e.holonomic_residuals.cwiseAbs().maxCoeff() <= operating_point_tolerance) return;
    const auto gradients = [&](const NumericEquations& at) {
      Eigen::MatrixXd Phi(nh, at.constraint_jacobian.cols());
      for (Eigen::Index r = 0; r < nh; ++r) Phi.row(r) = at.constraint_jacobian.row(holonomic_[static_cast<std::size_t>(r)]);
      return Phi;
    };
    const Indices unknown = pivoted(gradients(e), free_q_, nh);
    if (unknown.empty()) return;  // reported by require_satisfied
    for (int iteration = 0; iteration < 50; ++iteration) {
      const Eigen::VectorXd r = e.holonomic_residuals;
      if (r.cwiseAbs().maxCoeff() <= 1e-3 * operating_point_tolerance) break;
      const Eigen::VectorXd step = -Eigen::MatrixXd(gradients(e)(Eigen::all, unknown)).completeOrthogonalDecomposition().solve(r);
      bool reduced = false;
      const NamedValues before = result_.point;
      for (double scale = 1; scale > 1e-6 && !reduced; scale /= 2) {
        for (std::size_t k = 0; k < unknown.size(); ++k)
          result_.point[q_name(unknown[k])] = value_in(before, q_name(unknown[k])) + scale * step(static_cast<Eigen::Index>(k));
        try {
          const NumericEquations next = evaluate_(result_.point);
          if (next.holonomic_residuals.cwiseAbs().maxCoeff() < r.cwiseAbs().maxCoeff()) e = next, reduced = true;
        } catch (const Error&) {
          // a pole of the model: a shorter step
        }
      }
      if (!reduced) {
        result_.point = before;
        break;
      }
    }
    for (Eigen::Index j : unknown) result_.solved.push_back(q_name(j));
  }

  /// Xi qd + Xi_t = 0 for the free dependent rates, and as many free independent ones as the
  /// given dependent rates leave needed (see the header); a linear solve
  void solve_rates() {
    const NumericEquations e = evaluate_(result_.point);
    const Eigen::MatrixXd& Xi = e.constraint_jacobian;
    const Eigen::Index n = Xi.cols(), m = Xi.rows();
    if (m == 0 || velocity_violation(e) <= operating_point_tolerance) return;
    Indices dependent;
    if (model_.independent_speeds.empty()) {
      Indices all;
      for (Eigen::Index j = 0; j < n; ++j) all.push_back(j);
      dependent = pivoted(Xi, all, m);
    } else {
      for (Eigen::Index j = 0; j < n; ++j)
        if (std::find(model_.independent_speeds.begin(), model_.independent_speeds.end(), static_cast<std::size_t>(j)) ==
            model_.independent_speeds.end())
          dependent.push_back(j);
    }
    Indices unknown, others;
    for (Eigen::Index j : free_qd_) (is_among(dependent, j) ? unknown : others).push_back(j);
    unknown = pivoted(Xi, unknown, m);
    const Eigen::Index rank = unknown.empty() ? 0 : Eigen::MatrixXd(Xi(Eigen::all, unknown)).colPivHouseholderQr().rank();
    if (rank < m && !others.empty()) {
      // the directions the chosen dependent rates cannot reach, and the independent rates that do
      Eigen::MatrixXd projected = Xi(Eigen::all, others);
      if (!unknown.empty()) {
        const Eigen::HouseholderQR<Eigen::MatrixXd> qr(Eigen::MatrixXd(Xi(Eigen::all, unknown)));
        const Eigen::MatrixXd basis = qr.householderQ() * Eigen::MatrixXd::Identity(m, static_cast<Eigen::Index>(unknown.size()));
        projected -= basis * (basis.transpose() * projected);
      }
      Indices positions;
      for (std::size_t k = 0; k < others.size(); ++k) positions.push_back(static_cast<Eigen::Index>(k));
      for (Eigen::Index k : pivoted(projected, positions, m - rank)) unknown.push_back(others[static_cast<std::size_t>(k)]);
      std::sort(unknown.begin(), unknown.end());
    }
    if (unknown.empty()) return;
    Eigen::VectorXd qd = rates();
    for (Eigen::Index j : unknown) qd(j) = 0;
    const Eigen::VectorXd rest = Xi * qd + e.constraint_rate_term;
    const Eigen::VectorXd solved = Eigen::MatrixXd(Xi(Eigen::all, unknown)).completeOrthogonalDecomposition().solve(-rest);
    // a rate that is zero but for rounding (a bicycle's pitch rate) is written as 0
    const double scale = std::max(qd.cwiseAbs().maxCoeff(), solved.cwiseAbs().maxCoeff());
    for (std::size_t k = 0; k < unknown.size(); ++k) {
      const double v = solved(static_cast<Eigen::Index>(k));
      result_.point[qd_name(unknown[k])] = std::abs(v) <= 1e-14 * scale ? 0.0 : v;
      result_.solved.push_back(qd_name(unknown[k]));
    }
  }

  static double value_in(const NamedValues& values, const std::string& name) {
    const auto it = values.find(name);
    return it == values.end() ? 0.0 : it->second;
  }

  /// max over rows of |Xi qd + Xi_t| relative to the size of the row's terms
  double velocity_violation(const NumericEquations& e, Eigen::Index* worst = nullptr) const {
    const Eigen::VectorXd qd = rates();
    double largest = 0;
    for (Eigen::Index r = 0; r < e.constraint_jacobian.rows(); ++r) {
      const double residual = e.constraint_jacobian.row(r).dot(qd) + e.constraint_rate_term(r);
      const double size = 1 + e.constraint_jacobian.row(r).cwiseProduct(qd.transpose()).cwiseAbs().sum() +
                          std::abs(e.constraint_rate_term(r));
      if (std::abs(residual) / size > largest) {
        largest = std::abs(residual) / size;
        if (worst) *worst = r;
      }
    }
    return largest;
  }

  static std::string list(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
    return out.empty() ? std::string("none") : out;
  }

  /// the rates a constraint row involves (nonzero entries of Xi at the point), for the message
  std::string involved(const NumericEquations& e, Eigen::Index row) const {
    std::vector<std::string> names;
    for (Eigen::Index j = 0; j < e.constraint_jacobian.cols(); ++j)
      if (e.constraint_jacobian(row, j) != 0) names.push_back(qd_name(j));
    return list(names);
  }

  void require_satisfied() const {
    const NumericEquations e = evaluate_(result_.point);
    const auto& constraints = model_.system.constraints();
    for (Eigen::Index r = 0; r < e.holonomic_residuals.size(); ++r) {
      const double residual = e.holonomic_residuals(r);
      if (std::abs(residual) <= operating_point_tolerance) continue;
      const Eigen::Index row = holonomic_[static_cast<std::size_t>(r)];
      std::vector<std::string> free;
      for (Eigen::Index j : free_q_) free.push_back(q_name(j));
      throw Error(fmt::format(
          "the operating point violates the constraint '{}' (residual {:.3g}); {}; give coordinates that satisfy it",
          constraints[static_cast<std::size_t>(row)].name, residual,
          free.empty() ? std::string("every coordinate is given")
                       : fmt::format("Newton's method could not solve it for the coordinates left out ({}) from there",
                                     list(free))));
    }
    Eigen::Index worst = 0;
    if (velocity_violation(e, &worst) > operating_point_tolerance)
      throw Error(fmt::format("the operating point violates the constraint '{}' (residual {:.3g}); leave out one of "
                              "the rates it involves ({}) to have it solved, or give rates that satisfy it",
                              constraints[static_cast<std::size_t>(worst)].name,
                              e.constraint_jacobian.row(worst).dot(rates()) + e.constraint_rate_term(worst),
                              involved(e, worst)));
  }

  const Model& model_;
  const Evaluate& evaluate_;
  const std::vector<Coordinate>& coordinates_;
  Indices holonomic_, free_q_, free_qd_;
  ConstrainedPoint result_;
};

}  // namespace

ConstrainedPoint satisfy_constraints(const Model& model, const ModelEquations& eom, const NamedValues& given) {
  return satisfy_constraints(
      model, [&](const NamedValues& at) { return evaluate_equations(model, eom, at); }, given);
}

ConstrainedPoint satisfy_constraints(const Model& model,
                                     const std::function<NumericEquations(const NamedValues&)>& evaluate,
                                     const NamedValues& given) {
  return Completion(model, evaluate, given).run();
}

}  // namespace eomgen
