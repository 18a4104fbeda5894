#include "eomgen/derivation/linearization.hpp"

#include "eomgen/derivation/operating_point.hpp"
#include "eomgen/symbolic/graph_calculus.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <map>
#include <optional>
#include <random>
#include <set>

#include "eomgen/base/error.hpp"
#include "eomgen/mechanics/variables.hpp"
#include "chain_rule.hpp"
#include "linearization_program.hpp"
#include "tangent_space.hpp"
#include "eomrt/linearization.hpp"

namespace eomgen {

using GiNaC::ex;
using GiNaC::ex_to;
using GiNaC::symbol;

namespace {

/// An evaluator at the state `point` that also knows the accelerations and multipliers the
/// derivatives were taken at, and every derivative intermediate: the terms of `symbolic` can
/// then be evaluated in doubles (a pole becomes inf and a clear Error, not a GiNaC exception).
DoubleEvaluator terms_at(const Model& model, const ModelEquations& eom, const SymbolicLinearization& symbolic,
                         const NamedValues& point, const Eigen::VectorXd& qdd, const Eigen::VectorXd& lambda) {
  DoubleEvaluator eval = evaluator_at(model, eom, point);
  const auto& coordinates = model.system.variables().coordinates();
  for (std::size_t j = 0; j < coordinates.size(); ++j) eval.set(coordinates[j].qdd, qdd(static_cast<Eigen::Index>(j)));
  for (std::size_t r = 0; r < symbolic.lambda.size(); ++r) eval.set(symbolic.lambda[r], lambda(static_cast<Eigen::Index>(r)));
  for (const auto& d : symbolic.derivatives.definitions())
    eval.set(d.symbol, eval.value(d.value, "derivative " + d.symbol.get_name()));
  return eval;
}

/// A coordinate can cancel out of M and F only through identities GiNaC does not apply
/// (sin^2 + cos^2 = 1 where an axisymmetric body turns about its axis), so a column of K that
/// is not structurally zero is also tested in numbers: zero at several scattered states (and
/// accelerations) to rounding means the coordinate is cyclic. The states come from a fixed
/// seed, so the verdict is the same in every run.
void mark_cyclic_by_evaluation(const Model& model, const ModelEquations& eom, SymbolicLinearization& lin) {
  const Variables& vars = model.system.variables();
  const std::size_t n = vars.coordinates().size();
  std::vector<std::size_t> candidates;
  for (std::size_t k = 0; k < n; ++k)
    if (!lin.cyclic[k]) candidates.push_back(k);
  if (candidates.empty()) return;
  std::vector<bool> vanishes(n, true);
  std::mt19937 rng(20261122);
  std::uniform_real_distribution<double> value(-1.5, 1.5), time(0.0, 3.0);
  int points = 0;
  for (int attempt = 0; attempt < 12 && points < 4; ++attempt) {
    NamedValues at{{"t", time(rng)}};
    for (const Coordinate& c : vars.coordinates()) at[c.name] = value(rng), at[c.name + "_dot"] = value(rng);
    for (const Input& u : vars.inputs()) at[u.name] = value(rng);
    Eigen::VectorXd qdd(static_cast<Eigen::Index>(n));
    for (Eigen::Index j = 0; j < qdd.size(); ++j) qdd(j) = value(rng);
    try {
      const Eigen::MatrixXd K = evaluate_matrix(lin.K, terms_at(model, eom, lin, at, qdd, Eigen::VectorXd()), "K");
      const double scale = 1 + K.cwiseAbs().maxCoeff();
      for (std::size_t k : candidates) vanishes[k] = vanishes[k] && K.col(static_cast<Eigen::Index>(k)).cwiseAbs().maxCoeff() <= 1e-12 * scale;
      ++points;
    } catch (const Error&) {
      // a singular state (a pole of the model): try another
    }
  }
  if (points == 0) return;
  for (std::size_t k : candidates) lin.cyclic[k] = vanishes[k];
}

}  // namespace

SymbolicLinearization linearize_symbolic(const Model& model, const ModelEquations& eom) {
  const Variables& vars = model.system.variables();
  const std::size_t n = vars.coordinates().size(), nu = vars.inputs().size(), m = eom.constraint_count;
  std::vector<ex> variables;
  for (const Coordinate& c : vars.coordinates()) variables.push_back(c.q);
  for (const Coordinate& c : vars.coordinates()) variables.push_back(c.qd);
  for (const Input& u : vars.inputs()) variables.push_back(u.symbol);

  SymbolicLinearization lin;
  for (std::size_t r = 0; r < m; ++r) lin.lambda.emplace_back(fmt::format("lambda{}", r + 1));
  const ChainRule chain(eom.subexpressions, variables, lin.derivatives);
  lin.K = GiNaC::matrix(n, n);
  lin.D = GiNaC::matrix(n, n);
  lin.B_u = GiNaC::matrix(n, nu);
  lin.cyclic.assign(n, true);
  for (std::size_t i = 0; i < n; ++i) {
    ex residual = -eom.forcing(i, 0);
    for (std::size_t j = 0; j < n; ++j) residual += eom.mass_matrix(i, j) * vars.coordinates()[j].qdd;
    for (std::size_t r = 0; r < m; ++r) residual -= eom.constraint_jacobian(r, i) * lin.lambda[r];
    const std::vector<ex> gradient = chain.total(residual);
    for (std::size_t k = 0; k < n; ++k) {
      lin.K(i, k) = lin.derivatives.bind(gradient[k]);
      lin.D(i, k) = lin.derivatives.bind(gradient[n + k]);
      if (!lin.K(i, k).is_zero()) lin.cyclic[k] = false;
    }
    for (std::size_t k = 0; k < nu; ++k) lin.B_u(i, k) = lin.derivatives.bind(-gradient[2 * n + k]);
  }
  lin.S_q = GiNaC::matrix(m, n);
  lin.S_qd = GiNaC::matrix(m, n);
  lin.C_q = GiNaC::matrix(m, n);
  for (std::size_t r = 0; r < m; ++r) {
    ex acceleration = eom.constraint_acceleration_term(r, 0), velocity = eom.constraint_rate_term(r, 0);
    for (std::size_t j = 0; j < n; ++j) {
      acceleration += eom.constraint_jacobian(r, j) * vars.coordinates()[j].qdd;
      velocity += eom.constraint_jacobian(r, j) * vars.coordinates()[j].qd;
    }
    const std::vector<ex> d_acceleration = chain.total(acceleration), d_velocity = chain.total(velocity);
    for (std::size_t k = 0; k < n; ++k) {
      lin.S_q(r, k) = lin.derivatives.bind(d_acceleration[k]);
      lin.S_qd(r, k) = lin.derivatives.bind(d_acceleration[n + k]);
      lin.C_q(r, k) = lin.derivatives.bind(d_velocity[k]);
      if (!lin.S_q(r, k).is_zero() || !lin.C_q(r, k).is_zero()) lin.cyclic[k] = false;
    }
  }
  if (m == 0) mark_cyclic_by_evaluation(model, eom, lin);
  lin.program = compile_program(model, eom, lin);
  return lin;
}

namespace {

/// -0 from negating a zero would print as "-0"
void clear_negative_zeros(std::initializer_list<Eigen::MatrixXd*> matrices) {
  for (Eigen::MatrixXd* m : matrices) *m = m->unaryExpr([](double v) { return v == 0 ? 0.0 : v; });
}

/// The reduced A and B in the tangent space's states, without the states nothing depends on
/// when asked to drop them, and the names of what was kept, dropped and determined.
/// \return the kept states, as indices into the tangent space's [q_kept; v_independent]
std::vector<Eigen::Index> reduce(const Model& model, const TangentSpace& space, const LinearizeOptions& options,
                                 LinearModel& lin) {
  const auto& coordinates = model.system.variables().coordinates();
  const auto name = [&](Eigen::Index i) { return coordinates[static_cast<std::size_t>(i)].name; };
  const Eigen::MatrixXd A = space.P * lin.A_full * space.T, B = space.P * lin.B_full;
  const Eigen::Index nk = static_cast<Eigen::Index>(space.q_kept.size()), ns = A.rows();
  // a state nothing else in the reduced model depends on: a cyclic coordinate, or a speed
  // held constant to first order that enters nowhere (a wheel's spin). Dropping one can free
  // another (the rolling coin's heading moves only x and y), so this runs to a fixed point
  std::vector<bool> keep(static_cast<std::size_t>(ns), true);
  const double scale = std::max(1.0, A.cwiseAbs().maxCoeff());
  for (bool changed = options.drop_cyclic; changed;) {
    changed = false;
    for (Eigen::Index j = 0; j < ns; ++j) {
      if (!keep[static_cast<std::size_t>(j)]) continue;
      double largest = 0;
      for (Eigen::Index i = 0; i < ns; ++i)
        if (keep[static_cast<std::size_t>(i)]) largest = std::max(largest, std::abs(A(i, j)));
      if (largest <= operating_point_tolerance * scale) keep[static_cast<std::size_t>(j)] = false, changed = true;
    }
  }
  std::vector<Eigen::Index> rows;
  for (Eigen::Index j = 0; j < ns; ++j) {
    const Eigen::Index variable = j < nk ? space.q_kept[static_cast<std::size_t>(j)]
                                         : space.v_independent[static_cast<std::size_t>(j - nk)];
    const std::string state = j < nk ? name(variable) : name(variable) + "_dot";
    if (keep[static_cast<std::size_t>(j)]) {
      rows.push_back(j);
      lin.state_names.push_back(state);
    } else {
      lin.dropped.push_back(state);
    }
  }
  for (Eigen::Index i : space.q_dependent) lin.dependent.push_back(name(i));
  for (Eigen::Index i : space.v_dependent) lin.dependent.push_back(name(i) + "_dot");
  lin.A = A(rows, rows);
  lin.B = B(rows, Eigen::all);
  return rows;
}

/// The reduced second-order form (see LinearModel::M) where the kept coordinates are the
/// coordinates of the kept speeds and the coordinates' rows of A say dq' = dnu.
void reduced_second_order_form(const Model& model, const TangentSpace& space, const std::vector<Eigen::Index>& kept,
                               const Eigen::MatrixXd& mass_matrix, LinearModel& lin) {
  const auto& coordinates = model.system.variables().coordinates();
  const Eigen::Index nk = static_cast<Eigen::Index>(space.q_kept.size());
  std::vector<Eigen::Index> q, v;  // coordinate indices of the kept coordinates and speeds
  std::vector<Eigen::Index> speed_columns;  // the kept speeds' columns of G
  for (Eigen::Index j : kept) {
    if (j < nk) {
      q.push_back(space.q_kept[static_cast<std::size_t>(j)]);
    } else {
      v.push_back(space.v_independent[static_cast<std::size_t>(j - nk)]);
      speed_columns.push_back(j - nk);
    }
  }
  const auto names = [&](const std::vector<Eigen::Index>& indices, const char* suffix) {
    std::vector<std::string> out;
    for (Eigen::Index i : indices) out.push_back(coordinates[static_cast<std::size_t>(i)].name + suffix);
    return out;
  };
  const auto list = [](const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
    return out.empty() ? std::string("none") : out;
  };
  if (q != v) {
    lin.no_second_order = fmt::format("the kept coordinates ({}) are not those of the kept independent speeds ({})",
                                      list(names(q, "")), list(names(v, "_dot")));
    return;
  }
  const Eigen::Index k = static_cast<Eigen::Index>(q.size());
  const double scale = std::max(1.0, lin.A.cwiseAbs().maxCoeff());
  if (k == 0 || !lin.A.topLeftCorner(k, k).isZero(operating_point_tolerance * scale) ||
      !(lin.A.topRightCorner(k, k) - Eigen::MatrixXd::Identity(k, k)).isZero(operating_point_tolerance * scale)) {
    lin.no_second_order = k == 0 ? "no coordinates are kept"
                                 : "the kept coordinates' rates are not the independent speeds at this point";
    return;
  }
  const Eigen::Index n = mass_matrix.rows();
  const Eigen::MatrixXd G = space.T.bottomRightCorner(n, static_cast<Eigen::Index>(space.v_independent.size()))(
      Eigen::all, speed_columns);
  lin.M = G.transpose() * mass_matrix * G;
  lin.K = -lin.M * lin.A.bottomLeftCorner(k, k);
  lin.D = -lin.M * lin.A.bottomRightCorner(k, k);
  lin.B_u = lin.M * lin.B.bottomRows(k);
  lin.second_order_coordinates = names(q, "");
}

/// The reduced linear model of a constrained system (see the header).
void linearize_constrained(const Model& model, const SymbolicLinearization& symbolic,
                           const NamedValues& point, const LinearizeOptions& options, LinearModel& lin) {
  try {
    ConstrainedPoint completed = satisfy_constraints(
        model, [&](const NamedValues& at) { return PointEvaluation(model, *symbolic.program, at).equations(); }, point,
        options.guesses);
    lin.point = std::move(completed.point);
    lin.solved = std::move(completed.solved);
    lin.moved = std::move(completed.moved);
  } catch (const Error& e) {
    throw Error(fmt::format("linearizing {}: {}", model.name, e.what()));
  }
  PointEvaluation run(model, *symbolic.program, lin.point);
  const NumericEquations at = run.equations();
  const eomrt::KktSystem<double> kkt = factorize_kkt(at);
  const AccelerationSolution solution = solve_accelerations(at, kkt);
  lin.qdd0 = solution.qdd;
  run.set_accelerations(lin.qdd0, solution.lambda);
  const eomrt::LinearizationTerms<double> terms = run.terms();
  const Eigen::MatrixXd C_q = run.matrix(symbolic.program->C_q);
  Eigen::MatrixXd derivatives;
  eomrt::first_order_form(kkt, terms, derivatives, lin.A_full, lin.B_full);
  const TangentSpace space = tangent_space(model, at.constraint_jacobian, C_q);
  const std::vector<Eigen::Index> kept = reduce(model, space, options, lin);
  reduced_second_order_form(model, space, kept, at.mass_matrix, lin);
}

/// The linear model of an unconstrained system (see the header).
void linearize_unconstrained(const Model& model, const ModelEquations& eom, const SymbolicLinearization& symbolic,
                             const NamedValues& point, const LinearizeOptions& options, LinearModel& lin) {
  const auto& coordinates = model.system.variables().coordinates();
  const Eigen::Index n = static_cast<Eigen::Index>(coordinates.size());
  PointEvaluation run(model, *symbolic.program, point);
  const NumericEquations at = run.equations();
  lin.M = at.mass_matrix;
  const Eigen::LLT<Eigen::MatrixXd> llt(lin.M);
  if (!eomrt::cholesky_is_regular(llt, eomrt::default_singular_rcond<double>()))
    throw Error(fmt::format("linearizing {}: {}", model.name, explain_singular_mass_matrix(model, eom, point, lin.M)));
  lin.qdd0 = llt.solve(at.forcing);
  run.set_accelerations(lin.qdd0, Eigen::VectorXd());
  const eomrt::LinearizationTerms<double> terms = run.terms();
  lin.K = terms.K;
  lin.D = terms.D;
  lin.B_u = terms.B_u;
  for (const Coordinate& c : coordinates) lin.second_order_coordinates.push_back(c.name);
  lin.point = point;
  eomrt::first_order_form(llt, terms, lin.A_full, lin.B_full);
  // the state: the kept coordinates, then every rate
  std::vector<Eigen::Index> states;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (options.drop_cyclic && symbolic.cyclic[static_cast<std::size_t>(k)])
      lin.dropped.push_back(coordinates[static_cast<std::size_t>(k)].name);
    else
      states.push_back(k);
  }
  for (Eigen::Index k : states) lin.state_names.push_back(coordinates[static_cast<std::size_t>(k)].name);
  for (Eigen::Index k = 0; k < n; ++k) {
    states.push_back(n + k);
    lin.state_names.push_back(coordinates[static_cast<std::size_t>(k)].name + "_dot");
  }
  lin.A = lin.A_full(states, states);
  lin.B = lin.B_full(states, Eigen::all);
}

}  // namespace

LinearModel linearize(const Model& model, const ModelEquations& eom, const SymbolicLinearization& symbolic,
                      const NamedValues& point, const LinearizeOptions& options) {
  EOMGEN_DEMAND(symbolic.program != nullptr, "linearize: a SymbolicLinearization without its compiled program");
  LinearModel lin;
  for (const Input& u : model.system.variables().inputs()) lin.input_names.push_back(u.name);
  if (eom.constraint_count > 0) {
    linearize_constrained(model, symbolic, point, options, lin);
  } else {
    NamedValues at = point;  // without constraints a guess is the value
    for (const auto& [name, value] : options.guesses) at.emplace(name, value);
    linearize_unconstrained(model, eom, symbolic, at, options, lin);
  }
  clear_negative_zeros({&lin.A, &lin.B, &lin.K, &lin.D, &lin.B_u, &lin.A_full, &lin.B_full});
  return lin;
}

Equilibrium find_equilibrium(const Model& model, const ModelEquations& eom, const SymbolicLinearization& symbolic,
                             const NamedValues& guess, int max_iterations) {
  const Variables& vars = model.system.variables();
  const Eigen::Index n = static_cast<Eigen::Index>(vars.coordinates().size());
  const Eigen::Index m = static_cast<Eigen::Index>(eom.constraint_count);
  const std::vector<Eigen::Index> holonomic_rows = holonomic_rows_of(model);
  const Eigen::Index nh = static_cast<Eigen::Index>(holonomic_rows.size());

  Equilibrium eq;
  eq.point = guess;
  const auto set_q = [&](const Eigen::VectorXd& q) {
    for (Eigen::Index j = 0; j < n; ++j) eq.point[vars.coordinates()[static_cast<std::size_t>(j)].name] = q(j);
  };
  Eigen::VectorXd q(n);
  if (nh > 0) {
    // the guess's coordinates first onto the closure, nearest the guess (assembly): Newton's
    // method below then starts where phi = 0, and an unreachable closure is named as such
    NamedValues held, guesses;
    for (const auto& [name, value] : guess) {
      const bool coordinate = std::any_of(vars.coordinates().begin(), vars.coordinates().end(),
                                          [&](const Coordinate& c) { return c.name == name; });
      (coordinate ? guesses : held)[name] = value;
    }
    try {
      const ConstrainedPoint assembled = satisfy_constraints(model, eom, held, guesses);
      for (const Coordinate& c : vars.coordinates())
        if (const auto it = assembled.point.find(c.name); it != assembled.point.end()) eq.point[c.name] = it->second;
    } catch (const Error& e) {
      throw Error(fmt::format("finding an equilibrium of {}: the guess cannot be brought onto the constraints: {}",
                              model.name, e.what()));
    }
  }
  for (Eigen::Index j = 0; j < n; ++j) {
    const auto it = eq.point.find(vars.coordinates()[static_cast<std::size_t>(j)].name);
    q(j) = it == eq.point.end() ? 0.0 : it->second;
  }
  // residual [F + Xi^T lambda; phi] at q, with lambda the least-squares fit when asked for
  const auto residual = [&](const Eigen::VectorXd& at_q, Eigen::VectorXd& lambda, bool fit_lambda, NumericEquations& e) {
    set_q(at_q);
    e = evaluate_equations(model, eom, eq.point);
    if (fit_lambda && m > 0)
      lambda = e.constraint_jacobian.transpose().completeOrthogonalDecomposition().solve(-e.forcing);
    Eigen::VectorXd r(n + nh);
    r.head(n) = e.forcing + e.constraint_jacobian.transpose() * lambda;
    r.tail(nh) = e.holonomic_residuals;
    return r;
  };
  eq.lambda = Eigen::VectorXd::Zero(m);
  NumericEquations e;
  Eigen::VectorXd r = residual(q, eq.lambda, true, e);
  const double tolerance = 1e-12 * std::max(1.0, r.cwiseAbs().maxCoeff());
  for (; eq.iterations < max_iterations; ++eq.iterations) {
    if (r.cwiseAbs().maxCoeff() <= tolerance) break;
    const Eigen::MatrixXd K =
        evaluate_matrix(symbolic.K, terms_at(model, eom, symbolic, eq.point, Eigen::VectorXd::Zero(n), eq.lambda), "K");
    // d(F + Xi^T lambda)/dq = -K (K = dR/dq with R = M qdd - F - Xi^T lambda, qdd = 0)
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n + nh, n + m);
    J.topLeftCorner(n, n) = -K;
    J.topRightCorner(n, m) = e.constraint_jacobian.transpose();
    for (Eigen::Index i = 0; i < nh; ++i) J.row(n + i).head(n) = e.constraint_jacobian.row(holonomic_rows[static_cast<std::size_t>(i)]);
    const Eigen::VectorXd step = -J.completeOrthogonalDecomposition().solve(r);
    // halve the step until the residual falls (Newton's full step can overshoot far from home)
    double scale = 1;
    Eigen::VectorXd q_next, lambda_next, r_next;
    NumericEquations e_next;
    for (int halvings = 0; halvings < 30; ++halvings, scale /= 2) {
      q_next = q + scale * step.head(n);
      lambda_next = eq.lambda + scale * step.tail(m);
      try {
        r_next = residual(q_next, lambda_next, false, e_next);
      } catch (const Error&) {
        continue;  // a pole of the model: shorter
      }
      if (r_next.cwiseAbs().maxCoeff() < r.cwiseAbs().maxCoeff()) break;
    }
    if (!(r_next.size() == r.size() && r_next.cwiseAbs().maxCoeff() < r.cwiseAbs().maxCoeff())) break;
    q = q_next;
    eq.lambda = lambda_next;
    r = r_next;
    e = e_next;
  }
  set_q(q);
  eq.residual = r.cwiseAbs().maxCoeff();
  if (!(eq.residual <= tolerance)) {
    // say which part is left: the forces' balance, or the closure of the constraints
    Eigen::Index worst = 0;
    r.cwiseAbs().maxCoeff(&worst);
    const auto& constraints = model.system.constraints();
    const std::string part =
        worst < n ? fmt::format("the forces do not balance: F + Xi^T lambda = {:.3g} on {}", r(worst),
                                vars.coordinates()[static_cast<std::size_t>(worst)].name)
                  : fmt::format("the constraint '{}' does not close: phi = {:.3g}",
                                constraints[static_cast<std::size_t>(holonomic_rows[static_cast<std::size_t>(worst - n)])].name,
                                r(worst));
    throw Error(fmt::format("finding an equilibrium of {}: Newton's method stopped after {} iterations with "
                            "residual {:.3g} ({}); try another guess",
                            model.name, eq.iterations, eq.residual, part));
  }
  return eq;
}

StabilityReport assess_stability(const Eigen::MatrixXd& A, double tolerance) {
  StabilityReport report;
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(A, false);
  if (solver.info() != Eigen::Success) throw Error("the eigenvalues of A did not converge");
  report.eigenvalues = solver.eigenvalues();
  std::vector<std::complex<double>> sorted(report.eigenvalues.data(),
                                           report.eigenvalues.data() + report.eigenvalues.size());
  // descending real part, then descending imaginary part: a deterministic order to print
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
    return a.real() != b.real() ? a.real() > b.real() : a.imag() > b.imag();
  });
  for (std::size_t i = 0; i < sorted.size(); ++i) report.eigenvalues(static_cast<Eigen::Index>(i)) = sorted[i];

  double scale = 1;
  for (const auto& l : sorted) scale = std::max(scale, std::abs(l));
  const double axis = tolerance * scale;
  bool any_right = false, all_left = true;
  for (const auto& l : sorted) {
    any_right = any_right || l.real() > axis;
    all_left = all_left && l.real() < -axis;
  }
  if (any_right) {
    report.linear = LinearStability::unstable;
    report.nonlinear = LyapunovVerdict::unstable;
    return report;
  }
  if (all_left) {
    report.linear = LinearStability::asymptotically_stable;
    report.nonlinear = LyapunovVerdict::asymptotically_stable;
    return report;
  }
  // on the imaginary axis: stable only if every such eigenvalue has as many eigenvectors as
  // its multiplicity (a Jordan block there grows like t^k)
  report.linear = LinearStability::stable;
  report.nonlinear = LyapunovVerdict::no_conclusion;
  const Eigen::Index n = A.rows();
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    if (std::abs(sorted[i].real()) > axis) continue;
    long multiplicity = 0;
    for (const auto& other : sorted) multiplicity += std::abs(other - sorted[i]) <= 1e3 * axis;
    if (multiplicity < 2) continue;
    Eigen::FullPivLU<Eigen::MatrixXcd> lu(A.cast<std::complex<double>>() -
                                          sorted[i] * Eigen::MatrixXcd::Identity(n, n));
    lu.setThreshold(1e3 * tolerance);
    if (n - lu.rank() < multiplicity) report.linear = LinearStability::unstable;
  }
  return report;
}

const char* to_string(LinearStability s) {
  switch (s) {
    case LinearStability::asymptotically_stable:
      return "asymptotically stable";
    case LinearStability::stable:
      return "stable (eigenvalues on the imaginary axis)";
    case LinearStability::unstable:
      return "unstable";
  }
  EOMGEN_UNREACHABLE("to_string: a LinearStability outside its enumerators");
}

const char* to_string(LyapunovVerdict v) {
  switch (v) {
    case LyapunovVerdict::asymptotically_stable:
      return "asymptotically stable";
    case LyapunovVerdict::unstable:
      return "unstable";
    case LyapunovVerdict::no_conclusion:
      return "no conclusion (eigenvalues on the imaginary axis)";
  }
  EOMGEN_UNREACHABLE("to_string: a LyapunovVerdict outside its enumerators");
}

}  // namespace eomgen
