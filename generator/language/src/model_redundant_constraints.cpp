// Constraints that are redundant: at a generic state the row of Xi of each is a combination of the
// rows of constraints before it in the file, and so is its Xi_t. Each stays in the system, with a
// note: which rows are dependent can change with the state (of a Segway's two wheels on one axle,
// both forbidding the same sideways slip, the rows along a.2 at heading 0 and those along a.1 at
// heading pi/2), so no one row can be left out everywhere; the solves take an independent set
// at each state instead (runtime/include/eomrt/kkt_system.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "eomgen/base/error.hpp"
#include "model_constraint_rows.hpp"
#include "model_elaborator.hpp"

namespace eomgen::syntax {
namespace {

// 'a', 'a' and 'b', 'a', 'b' and 'c'
std::string name_list(const std::vector<std::string>& names) {
  std::string list;
  for (std::size_t k = 0; k < names.size(); ++k)
    list += (k == 0 ? "" : k + 1 == names.size() ? " and " : ", ") + ("'" + names[k] + "'");
  return list;
}

}  // namespace

// Tested in file order, so that the later of two dependent constraints is the one left out: the
// one the reader added last, and the one the note then points at.
ConstraintRows Elaborator::note_redundant_constraints() {
  const MechanicalSystem& sys = model_.system;
  const Variables& vars = sys.variables();
  const auto& constraints = sys.constraints();
  const GiNaC::exmap state = generic_states().front();
  const Eigen::Index n = static_cast<Eigen::Index>(vars.coordinate_count());
  ConstraintRows kept{Eigen::MatrixXd(0, n), Eigen::VectorXd(0)};
  std::vector<std::string> kept_names;
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const Constraint& c = constraints[i];
    const SourceLocation& at = model_.constraint_locations[i];
    const std::optional<RateRow> row = rate_row_at(c, vars, state);
    if (!row)
      throw SourceError(at, fmt::format("constraint '{}': its row of Xi qd + Xi_t is not a real number at a generic "
                                        "state", c.name));
    if (row->xi.norm() < 1e-12)
      throw SourceError(at, fmt::format("constraint '{}' is identically zero: its Jacobian vanishes at a generic state",
                                        c.name));
    Eigen::MatrixXd grown(kept.xi.rows() + 1, n);
    grown << kept.xi, row->xi;
    Eigen::FullPivLU<Eigen::MatrixXd> lu(grown);
    lu.setThreshold(1e-9);
    if (lu.rank() == grown.rows()) {
      kept.xi = std::move(grown);
      kept.xi_t.conservativeResize(kept.xi_t.size() + 1);
      kept.xi_t[kept.xi_t.size() - 1] = row->xi_t;
      kept_names.push_back(c.name);
      continue;
    }
    // the rows kept are independent, so the combination is unique
    const Eigen::VectorXd weights = kept.xi.transpose().colPivHouseholderQr().solve(row->xi.transpose());
    std::vector<std::string> depends_on;
    double combined_xi_t = 0, xi_t_scale = std::fabs(row->xi_t);
    for (Eigen::Index j = 0; j < weights.size(); ++j) {
      if (std::fabs(weights[j]) * kept.xi.row(j).norm() > 1e-9 * row->xi.norm())
        depends_on.push_back(kept_names[static_cast<std::size_t>(j)]);
      combined_xi_t += weights[j] * kept.xi_t[j];
      xi_t_scale += std::fabs(weights[j] * kept.xi_t[j]);
    }
    const bool one = depends_on.size() == 1;
    const std::string combination =
        fmt::format("{} {}", one ? "a multiple of that of" : "a combination of those of", name_list(depends_on));
    // Xi qd = -Xi_t for the others then gives this row's Xi qd, and it holds only if its Xi_t
    // is that combination too: x = 0 and x = t have one row of Xi, and no motion meets both
    if (std::fabs(row->xi_t - combined_xi_t) > 1e-9 * std::max(xi_t_scale, row->xi.norm()))
      throw SourceError(at, fmt::format("constraint '{}' contradicts the constraints before it: at a generic state its "
                                        "row of Xi is {}, but its Xi_t is not the same combination of theirs, so no "
                                        "motion satisfies them all: expected a constraint that agrees with them, or "
                                        "none", c.name, combination));
    std::string message = fmt::format("constraint '{}' is redundant: at a generic state its row of Xi is {}; kept, "
                                      "the solves take independent rows at each state and give a row they leave out "
                                      "the multiplier 0 (docs/conventions.md, Redundant constraints)",
                                      c.name, combination);
    model_.notes.push_back({at, std::move(message)});
    model_.redundant_constraints.push_back({c, std::move(depends_on), at});
  }
  return kept;
}

}  // namespace eomgen::syntax
