#include "base_parameters.hpp"

#include <fmt/format.h>

#include <Eigen/QR>

#include <cmath>
#include <random>
#include <set>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"

namespace eomgen {
namespace {

// A column is independent of those kept before it when what is left of it after projecting on
// them is more than this fraction of it; a column below this fraction of the largest is zero.
constexpr double independence = 1e-8;

// Y at `states` random states (a fixed seed: the same columns in every run), stacked
Eigen::MatrixXd stacked_regressor(const Model& model, const ModelEquations& eom, const HeaderFunctions& h,
                                  const NamedValues& parameters, int states) {
  const Variables& vars = model.system.variables();
  const auto n = static_cast<Eigen::Index>(vars.coordinate_count());
  std::mt19937 rng(20261205);
  std::uniform_real_distribution<double> uniform(-1.5, 1.5);
  Eigen::MatrixXd W(n * states, h.regressor->cols());
  for (int s = 0; s < states; ++s) {
    NamedValues at = parameters;
    at["t"] = 0.5 + 0.25 * uniform(rng);
    for (const Coordinate& c : vars.coordinates()) at[c.name] = uniform(rng), at[c.name + "_dot"] = uniform(rng);
    Eigen::VectorXd qdd(n);
    for (Eigen::Index k = 0; k < n; ++k) qdd(k) = uniform(rng);
    W.middleRows(s * n, n) = evaluate_controller_functions(model, eom, h, at, qdd).regressor;
  }
  return W;
}

// the columns kept in order: each that is independent of those before it
std::vector<Eigen::Index> independent_columns(const Eigen::MatrixXd& W) {
  const double largest = W.colwise().norm().maxCoeff();
  std::vector<Eigen::Index> kept;
  Eigen::MatrixXd basis(W.rows(), 0);
  for (Eigen::Index j = 0; j < W.cols(); ++j) {
    const double norm = W.col(j).norm();
    if (norm <= independence * largest) continue;  // no state moves it: not identifiable at all
    Eigen::VectorXd rest = W.col(j);
    for (int pass = 0; pass < 2; ++pass) rest -= basis * (basis.transpose() * rest);  // twice: orthogonal to rounding
    if (rest.norm() <= independence * norm) continue;
    basis.conservativeResize(Eigen::NoChange, basis.cols() + 1);
    basis.col(basis.cols() - 1) = rest / rest.norm();
    kept.push_back(j);
  }
  return kept;
}

// pi_base = C pi: the identity on the kept columns, each other column as their combination
Eigen::MatrixXd combinations(const Eigen::MatrixXd& W, const std::vector<Eigen::Index>& kept) {
  Eigen::MatrixXd B(W.rows(), static_cast<Eigen::Index>(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k) B.col(static_cast<Eigen::Index>(k)) = W.col(kept[k]);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(B);
  const Eigen::MatrixXd C = qr.solve(W);  // Y = Y_B C: column j of Y is Y_B C(:, j)
  // round-off: a coefficient within 1e-11 of a decimal of at most ten places is that decimal
  // (the URDF's lengths and their products are such decimals; 1e-13 is 0)
  return C.unaryExpr([](double c) {
    double scale = 1;
    for (int places = 0; places <= 10; ++places, scale *= 10) {
      const double rounded = std::round(c * scale) / scale;
      if (std::abs(c - rounded) <= 1e-11 * (1 + std::abs(c))) return rounded == 0 ? 0.0 : rounded;
    }
    return c;
  });
}

}  // namespace

BaseParameters find_base_parameters(const Model& model, const ModelEquations& eom, const HeaderFunctions& h) {
  if (!h.regressor) throw DerivationError("base parameters: the model has no regressor (" + h.no_regressor + ")");
  const Variables& vars = model.system.variables();
  const int columns = static_cast<int>(h.regressor->cols());
  const int n = static_cast<int>(vars.coordinate_count());
  const int states = 2 * columns / std::max(n, 1) + 4;  // twice as many rows as columns, and a few more
  NamedValues defaults;
  for (const Parameter& p : vars.parameters()) defaults[p.name] = p.default_value;
  const Eigen::MatrixXd W = stacked_regressor(model, eom, h, defaults, states);
  BaseParameters base;
  base.independent = independent_columns(W);
  base.combination = combinations(W, base.independent);

  // the combinations are numbers only where no parameter of Y changes them
  std::set<std::string> moving;
  {
    for (const Parameter& p : vars.parameters()) {
      NamedValues changed = defaults;
      changed[p.name] = p.default_value == 0 ? 0.37 : 1.37 * p.default_value;
      const Eigen::MatrixXd W2 = stacked_regressor(model, eom, h, changed, states);
      if ((W2 - W).norm() == 0) continue;  // Y does not read it
      const std::vector<Eigen::Index> kept = independent_columns(W2);
      const Eigen::MatrixXd C2 = combinations(W2, base.independent);
      if (kept != base.independent || (C2 - base.combination).cwiseAbs().maxCoeff() > 1e-7 * (1 + base.combination.cwiseAbs().maxCoeff()))
        moving.insert(p.name);
    }
  }
  if (!moving.empty()) {
    std::string names;
    for (const std::string& m : moving) names += (names.empty() ? "" : ", ") + m;
    throw DerivationError(fmt::format("base parameters: their combinations depend on the parameters {} (a geometry "
                                      "of parameters); they are found as numbers only where the geometry is numbers "
                                      "(a robot imported from URDF): use the full regressor",
                                      names));
  }
  for (std::size_t b = 0; b < base.independent.size(); ++b) {
    std::string name = h.inertial_parameter_names[static_cast<std::size_t>(base.independent[b])];
    for (Eigen::Index j = 0; j < base.combination.cols(); ++j) {
      const double c = base.combination(static_cast<Eigen::Index>(b), j);
      if (j == base.independent[b] || c == 0) continue;
      name += fmt::format(" {} {}{}", c < 0 ? "-" : "+", std::abs(c) == 1 ? "" : fmt::format("{:.12g}*", std::abs(c)),
                          h.inertial_parameter_names[static_cast<std::size_t>(j)]);
    }
    base.names.push_back(name);
  }
  return base;
}

}  // namespace eomgen
