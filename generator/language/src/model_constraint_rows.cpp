// A constraint's row of Xi and its Xi_t in numbers at a state.
#include "model_constraint_rows.hpp"

#include "model_elaborator.hpp"

namespace eomgen::syntax {

std::optional<RateRow> rate_row_at(const Constraint& c, const Variables& vars, const GiNaC::exmap& state) {
  const bool holonomic = c.kind == Constraint::Kind::holonomic;
  const std::size_t n = vars.coordinate_count();
  RateRow row{Eigen::RowVectorXd(static_cast<Eigen::Index>(n)), 0};
  GiNaC::exmap rates_at_zero;
  for (std::size_t k = 0; k < n; ++k) {
    const Coordinate& coordinate = vars.coordinates()[k];
    const std::optional<double> entry = value_at(c.expression.diff(holonomic ? coordinate.q : coordinate.qd), state);
    if (!entry) return std::nullopt;
    row.xi[static_cast<Eigen::Index>(k)] = *entry;
    rates_at_zero[coordinate.qd] = 0;
  }
  const GiNaC::ex xi_t = holonomic ? c.expression.diff(vars.time())
                                   : c.expression.subs(rates_at_zero, GiNaC::subs_options::no_pattern);
  const std::optional<double> value = value_at(xi_t, state);
  if (!value) return std::nullopt;
  row.xi_t = *value;
  return row;
}

}  // namespace eomgen::syntax
