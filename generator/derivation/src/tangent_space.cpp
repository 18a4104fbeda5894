#include "tangent_space.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "eomgen/base/error.hpp"

namespace eomgen {

namespace {

/// The `count` columns of `a` a column-pivoted QR takes first: the best-conditioned choice of
/// dependent coordinates (or rates) for the rows of `a`, in increasing order.
std::vector<Eigen::Index> pivot_columns(const Eigen::MatrixXd& a, Eigen::Index count) {
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  std::vector<Eigen::Index> columns;
  for (Eigen::Index i = 0; i < count; ++i) columns.push_back(qr.colsPermutation().indices()(i));
  std::sort(columns.begin(), columns.end());
  return columns;
}

/// An independent set of the rows of `a` (redundant constraints leave some dependent at a
/// state), by a column-pivoted QR of a^T; in increasing order.
std::vector<Eigen::Index> independent_rows(const Eigen::MatrixXd& a) {
  if (a.rows() == 0) return {};
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a.transpose());
  qr.setThreshold(1e-10);
  std::vector<Eigen::Index> rows;
  for (Eigen::Index i = 0; i < qr.rank(); ++i) rows.push_back(qr.colsPermutation().indices()(i));
  std::sort(rows.begin(), rows.end());
  return rows;
}

std::vector<Eigen::Index> complement(Eigen::Index n, const std::vector<Eigen::Index>& taken) {
  std::vector<Eigen::Index> rest;
  for (Eigen::Index i = 0; i < n; ++i)
    if (std::find(taken.begin(), taken.end(), i) == taken.end()) rest.push_back(i);
  return rest;
}


/// dq = Tq dq_kept: each holonomic constraint's dependent coordinate where its gradient is best
/// conditioned
Eigen::MatrixXd dependent_coordinates(const Model& model, const Eigen::MatrixXd& Xi, TangentSpace& space) {
  const Eigen::Index n = Xi.cols();
  const std::vector<Eigen::Index> holonomic_rows = holonomic_rows_of(model);
  Eigen::MatrixXd all_gradients(static_cast<Eigen::Index>(holonomic_rows.size()), n);
  for (Eigen::Index r = 0; r < all_gradients.rows(); ++r)
    all_gradients.row(r) = Xi.row(holonomic_rows[static_cast<std::size_t>(r)]);
  const Eigen::MatrixXd Phi = all_gradients(independent_rows(all_gradients), Eigen::all);
  const Eigen::Index nh = Phi.rows();
  space.q_dependent = nh > 0 ? pivot_columns(Phi, nh) : std::vector<Eigen::Index>{};
  space.q_kept = complement(n, space.q_dependent);
  const Eigen::Index nk = static_cast<Eigen::Index>(space.q_kept.size());
  Eigen::MatrixXd Tq = Eigen::MatrixXd::Zero(n, nk);
  for (Eigen::Index j = 0; j < nk; ++j) Tq(space.q_kept[static_cast<std::size_t>(j)], j) = 1;
  if (nh > 0) {
    const Eigen::PartialPivLU<Eigen::MatrixXd> phi_d(Eigen::MatrixXd(Phi(Eigen::all, space.q_dependent)));
    const Eigen::MatrixXd solved = -phi_d.solve(Eigen::MatrixXd(Phi(Eigen::all, space.q_kept)));
    for (Eigen::Index i = 0; i < nh; ++i) Tq.row(space.q_dependent[static_cast<std::size_t>(i)]) = solved.row(i);
  }
  return Tq;
}

}  // namespace

TangentSpace tangent_space(const Model& model, const Eigen::MatrixXd& all_rows, const Eigen::MatrixXd& all_C_q) {
  // an independent set of the rows: the others follow from them at this point
  const std::vector<Eigen::Index> rows = independent_rows(all_rows);
  const Eigen::MatrixXd Xi = all_rows(rows, Eigen::all), C_q = all_C_q(rows, Eigen::all);
  const Eigen::Index n = Xi.cols(), m = Xi.rows();
  TangentSpace space;
  const Eigen::MatrixXd Tq = dependent_coordinates(model, all_rows, space);
  for (std::size_t k : model.independent_speeds) space.v_independent.push_back(static_cast<Eigen::Index>(k));
  std::sort(space.v_independent.begin(), space.v_independent.end());
  space.v_dependent = space.v_independent.empty() ? pivot_columns(Xi, m) : complement(n, space.v_independent);
  if (space.v_independent.empty()) space.v_independent = complement(n, space.v_dependent);
  const Eigen::MatrixXd Xi_d = Xi(Eigen::all, space.v_dependent);
  const Eigen::PartialPivLU<Eigen::MatrixXd> xi_d(Xi_d);
  if (!(std::abs(Xi_d.determinant()) > 1e-12 * std::max(1.0, Xi.cwiseAbs().maxCoeff())))
    throw Error(fmt::format("linearizing {}: the declared independent speeds leave a singular block of Xi at the "
                            "operating point",
                            model.name));
  const Eigen::Index nk = Tq.cols(), ni = static_cast<Eigen::Index>(space.v_independent.size());
  Eigen::MatrixXd Gq = Eigen::MatrixXd::Zero(n, n), Gv = Eigen::MatrixXd::Zero(n, ni);
  for (Eigen::Index j = 0; j < ni; ++j) Gv(space.v_independent[static_cast<std::size_t>(j)], j) = 1;
  const Eigen::MatrixXd dep_v = -xi_d.solve(Eigen::MatrixXd(Xi(Eigen::all, space.v_independent)));
  const Eigen::MatrixXd dep_q = -xi_d.solve(C_q);
  for (Eigen::Index i = 0; i < m; ++i) {
    Gv.row(space.v_dependent[static_cast<std::size_t>(i)]) = dep_v.row(i);
    Gq.row(space.v_dependent[static_cast<std::size_t>(i)]) = dep_q.row(i);
  }
  space.T = Eigen::MatrixXd::Zero(2 * n, nk + ni);
  space.T.topLeftCorner(n, nk) = Tq;
  space.T.bottomLeftCorner(n, nk) = Gq * Tq;
  space.T.bottomRightCorner(n, ni) = Gv;
  space.P = Eigen::MatrixXd::Zero(nk + ni, 2 * n);
  for (Eigen::Index j = 0; j < nk; ++j) space.P(j, space.q_kept[static_cast<std::size_t>(j)]) = 1;
  for (Eigen::Index j = 0; j < ni; ++j) space.P(nk + j, n + space.v_independent[static_cast<std::size_t>(j)]) = 1;
  return space;
}

/// The holonomic constraints' rows of Xi, in order.
std::vector<Eigen::Index> holonomic_rows_of(const Model& model) {
  std::vector<Eigen::Index> rows;
  const auto& constraints = model.system.constraints();
  for (std::size_t r = 0; r < constraints.size(); ++r)
    if (constraints[r].kind == Constraint::Kind::holonomic) rows.push_back(static_cast<Eigen::Index>(r));
  return rows;
}

}  // namespace eomgen
