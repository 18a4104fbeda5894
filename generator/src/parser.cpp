// parse_model / load_model, and the checks that need the whole model.
#include <Eigen/Dense>
#include <fmt/format.h>

#include <fstream>
#include <random>
#include <sstream>

#include "eomgen/error.hpp"
#include "eomgen/model.hpp"
#include "model_elaborator.hpp"

namespace eomgen {
namespace syntax {

// Checks that need every statement: an empty system, unused coordinates, and constraints
// that are zero or linearly dependent at a generic state.
void Elaborator::checks() {
  const MechanicalSystem& sys = model_.system;
  const Variables& vars = sys.variables();
  const SourceLocation top{file_, 1, 1};
  if (vars.coordinate_count() == 0)
    throw SourceError(top, "the model declares no coordinates: expected 'coordinate NAME, ...'");
  if (sys.particles().empty() && sys.rigid_bodies().empty())
    throw SourceError(top, "the model has no particle or body, so it has no mass: expected 'particle' or 'body'");
  for (std::size_t k = 0; k < vars.coordinate_count(); ++k)
    if (!used_coordinates_.count(vars.coordinates()[k].name))
      throw SourceError(model_.coordinate_locations[k],
                        fmt::format("coordinate '{}' is declared but never used", vars.coordinates()[k].name));

  // Xi at a generic state: parameters at their defaults, coordinates and rates at irrational-
  // looking values no special configuration is likely to hit
  const auto& constraints = sys.constraints();
  if (constraints.empty()) return;
  std::mt19937 rng(20261121);
  std::uniform_real_distribution<double> value(0.31, 1.17);
  GiNaC::exmap state = sys.parameter_defaults();
  state[vars.time()] = 0.73;
  for (const auto& c : vars.coordinates()) {
    state[c.q] = value(rng);
    state[c.qd] = value(rng);
  }
  const std::size_t n = vars.coordinate_count();
  Eigen::MatrixXd xi(0, static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const Constraint& c = constraints[i];
    Eigen::RowVectorXd row(n);
    for (std::size_t k = 0; k < n; ++k) {
      const auto& coord = vars.coordinates()[k];
      const GiNaC::ex d = c.expression.diff(GiNaC::ex_to<GiNaC::symbol>(
          GiNaC::ex(c.kind == Constraint::Kind::holonomic ? coord.q : coord.qd)));
      GiNaC::ex v;
      try {
        v = d.subs(state, GiNaC::subs_options::no_pattern).evalf();
      } catch (const GiNaC::pole_error&) {  // e.g. 1/l with a parameter l that defaults to 0
        v = GiNaC::I;                       // reported below as not a real number
      }
      if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real())
        throw SourceError(model_.constraint_locations[i],
                          fmt::format("constraint '{}': its Jacobian is not a real number at a generic state", c.name));
      row[static_cast<Eigen::Index>(k)] = GiNaC::ex_to<GiNaC::numeric>(v).to_double();
    }
    if (row.norm() < 1e-12)
      throw SourceError(model_.constraint_locations[i],
                        fmt::format("constraint '{}' is identically zero: its Jacobian vanishes at a generic state", c.name));
    Eigen::MatrixXd grown(xi.rows() + 1, xi.cols());
    grown << xi, row;
    Eigen::FullPivLU<Eigen::MatrixXd> lu(grown);
    lu.setThreshold(1e-9);
    if (lu.rank() < grown.rows())
      throw SourceError(model_.constraint_locations[i],
                        fmt::format("constraint '{}' is linearly dependent on the constraints before it at a "
                                    "generic state", c.name));
    xi = grown;
  }
}

}  // namespace syntax

Model parse_model(const std::string& text, const std::string& file_name,
                  const std::map<std::string, double>& overrides) {
  const auto statements = syntax::parse_statements(text, file_name);
  syntax::Elaborator elaborator(file_name, overrides);
  Model model = elaborator.run(statements);
  if (model.name.empty()) {
    std::string stem = file_name.substr(file_name.find_last_of('/') + 1);
    model.name = stem.substr(0, stem.find('.'));
  }
  return model;
}

Model load_model(const std::string& path, const std::map<std::string, double>& overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("{}: error: cannot read the model file", path));
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_model(buffer.str(), path, overrides);
}

}  // namespace eomgen
