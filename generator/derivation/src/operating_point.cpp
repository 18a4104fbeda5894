#include "eomgen/derivation/operating_point.hpp"

#include <fmt/format.h>

#include <cmath>

#include "eomgen/base/error.hpp"
#include "eomgen/mechanics/variables.hpp"
#include "eomrt/assembly.hpp"

namespace eomgen {

namespace {

using Evaluate = std::function<NumericEquations(const NamedValues&)>;

/// The constraint terms of a model at named points, as eomrt's assembly asks for them: the
/// coordinates and rates it varies are written into a copy of the point, the rest (parameters,
/// inputs, t) stay as given. A pole of the model (an Error from the evaluation) counts as a
/// term that is not finite, where assembly shortens its step.
class PointTerms {
 public:
  using Coordinates = Eigen::VectorXd;
  using Holonomic = Eigen::VectorXd;
  using Gradients = Eigen::MatrixXd;
  using Constraints = Eigen::VectorXd;
  using Jacobian = Eigen::MatrixXd;

  PointTerms(const Model& model, const Evaluate& evaluate, NamedValues point)
      : evaluate_(evaluate), coordinates_(model.system.variables().coordinates()), point_(std::move(point)) {
    const auto& constraints = model.system.constraints();
    for (std::size_t r = 0; r < constraints.size(); ++r)
      if (constraints[r].kind == Constraint::Kind::holonomic) holonomic_.push_back(static_cast<int>(r));
    constraint_count_ = static_cast<Eigen::Index>(constraints.size());
  }

  Eigen::Index holonomic_count() const { return static_cast<Eigen::Index>(holonomic_.size()); }
  Eigen::Index constraint_count() const { return constraint_count_; }
  int holonomic_row(Eigen::Index k) const { return holonomic_[static_cast<std::size_t>(k)]; }

  bool positions(const Coordinates& q, Holonomic& phi, Gradients& Phi) {
    const NumericEquations* e = at(q);
    if (!e) return false;
    phi = e->holonomic_residuals;
    Phi.resize(holonomic_count(), q.size());
    for (Eigen::Index k = 0; k < Phi.rows(); ++k) Phi.row(k) = e->constraint_jacobian.row(holonomic_row(k));
    return phi.allFinite() && Phi.allFinite();
  }
  bool rates(const Coordinates& q, Jacobian& Xi, Constraints& Xi_t) {
    const NumericEquations* e = at(q);
    if (!e) return false;
    Xi = e->constraint_jacobian;
    Xi_t = e->constraint_rate_term;
    return Xi.allFinite() && Xi_t.allFinite();
  }
  bool mass_diagonal(const Coordinates& q, Coordinates& d) {
    const NumericEquations* e = at(q);
    if (!e) return false;
    d = e->mass_matrix.diagonal();
    return d.allFinite();
  }

 private:
  /// the equations at q (rates as in the point: the constraint terms do not depend on them)
  const NumericEquations* at(const Coordinates& q) {
    for (Eigen::Index j = 0; j < q.size(); ++j) point_[coordinates_[static_cast<std::size_t>(j)].name] = q(j);
    try {
      last_ = evaluate_(point_);
    } catch (const Error&) {
      return nullptr;
    }
    return &last_;
  }

  const Evaluate& evaluate_;
  const std::vector<Coordinate>& coordinates_;
  NamedValues point_;
  std::vector<int> holonomic_;
  Eigen::Index constraint_count_ = 0;
  NumericEquations last_;
};

double value_of(const NamedValues& given, const NamedValues& guesses, const std::string& name) {
  if (const auto it = given.find(name); it != given.end()) return it->second;
  if (const auto it = guesses.find(name); it != guesses.end()) return it->second;
  return 0.0;
}

std::string list(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
  return out.empty() ? std::string("none") : out;
}

}  // namespace

std::string describe_moved(const std::vector<MovedValue>& moved) {
  std::string out;
  for (const MovedValue& m : moved)
    out += fmt::format("{}{} = {:.10g} (given {:.10g}, moved by {:.3g})", out.empty() ? "" : ", ", m.name, m.used,
                       m.requested, m.used - m.requested);
  return out;
}

ConstrainedPoint satisfy_constraints(const Model& model, const ModelEquations& eom, const NamedValues& given,
                                     const NamedValues& guesses) {
  return satisfy_constraints(
      model, [&](const NamedValues& at) { return evaluate_equations(model, eom, at); }, given, guesses);
}

ConstrainedPoint satisfy_constraints(const Model& model, const Evaluate& evaluate, const NamedValues& given,
                                     const NamedValues& guesses) {
  const auto& coordinates = model.system.variables().coordinates();
  const auto& constraints = model.system.constraints();
  const Eigen::Index n = static_cast<Eigen::Index>(coordinates.size());
  ConstrainedPoint result;
  result.point = given;
  for (const auto& [name, value] : guesses)
    if (!given.count(name)) result.point[name] = value;
  if (constraints.empty()) return result;

  Eigen::VectorXd q(n), qd(n);
  using Mask = eomrt::detail::Assembly<PointTerms>::Mask;
  Mask q_held(n), qd_held(n), preferred = Mask::Constant(n, false);
  for (Eigen::Index j = 0; j < n; ++j) {
    const std::string& name = coordinates[static_cast<std::size_t>(j)].name;
    q(j) = value_of(given, guesses, name);
    qd(j) = value_of(given, guesses, name + "_dot");
    q_held(j) = given.count(name) > 0;
    qd_held(j) = given.count(name + "_dot") > 0;
  }
  for (std::size_t k : model.independent_speeds) preferred(static_cast<Eigen::Index>(k)) = true;
  const Eigen::VectorXd q0 = q, qd0 = qd;

  PointTerms terms(model, evaluate, result.point);
  const eomrt::AssemblyOptions<double> options;
  eomrt::detail::Assembly<PointTerms> assembly(terms, options);
  const eomrt::AssemblyReport<double> report = assembly.run(q, qd, q_held, qd_held, preferred);
  switch (report.status) {
    case eomrt::AssemblyStatus::ok:
    case eomrt::AssemblyStatus::held_values_moved:
      break;
    case eomrt::AssemblyStatus::unreachable: {
      const std::string& name = constraints[static_cast<std::size_t>(report.worst_row)].name;
      std::vector<std::string> given_names;
      for (const auto& [key, value] : given) given_names.push_back(key);
      throw Error(fmt::format("no state near the point satisfies the constraint '{}': the nearest the search came, "
                              "with every value free to move, leaves {} = {:.3g} (given: {}); check the model's "
                              "dimensions, or give values near an assembly",
                              name, report.worst_is_position ? "phi" : "Xi qd + Xi_t", report.worst_residual,
                              list(given_names)));
    }
    case eomrt::AssemblyStatus::non_finite:
      throw Error("the constraints' terms are not finite numbers near the point (a pole or a singularity of the "
                  "model); give values away from it");
  }
  // the point: what was given or guessed, and what was solved or moved (a name neither given
  // nor solved stays an implicit 0)
  const double scale = std::max(qd.cwiseAbs().maxCoeff(), qd0.cwiseAbs().maxCoeff());
  for (Eigen::Index j = 0; j < n; ++j) {
    const std::string& name = coordinates[static_cast<std::size_t>(j)].name;
    const bool solved = assembly.solved_coordinates()(j) && !q_held(j);
    if (solved) result.solved.push_back(name);
    if (q_held(j) && q(j) != q0(j)) result.moved.push_back({name, q0(j), q(j)});
    if (solved || q_held(j) || guesses.count(name)) result.point[name] = q(j);
  }
  for (Eigen::Index j = 0; j < n; ++j) {
    const std::string name = coordinates[static_cast<std::size_t>(j)].name + "_dot";
    // a rate that is zero but for rounding (a bicycle's pitch rate) is written as 0
    const double v = std::abs(qd(j)) <= 1e-14 * scale && !qd_held(j) ? 0.0 : qd(j);
    const bool solved = assembly.solved_rates()(j) && !qd_held(j);
    if (solved) result.solved.push_back(name);
    if (qd_held(j) && v != qd0(j)) result.moved.push_back({name, qd0(j), v});
    if (solved || qd_held(j) || guesses.count(name)) result.point[name] = v;
  }
  return result;
}

}  // namespace eomgen
