// parse_model / load_model, and the checks that need the whole model.
#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <fstream>

#include "eomgen/base/bounded_read.hpp"
#include "eomgen/base/error.hpp"
#include "eomgen/language/model_file.hpp"
#include "eomgen/urdf/urdf_import.hpp"
#include "model_constraint_rows.hpp"
#include "model_elaborator.hpp"

namespace eomgen {
namespace syntax {

// The independent speeds of the null-space method: declared coordinates, each listed once, one
// per degree of freedom (nq - nc). Run by checks() once the redundant constraints are left out,
// which then asks the remaining, dependent speeds to be solvable from them.
void Elaborator::independent_speeds() {
  const Instance* declaration = nullptr;
  for (const Instance& in : instances_) {
    if (in.statement->kind != Statement::Kind::independent) continue;
    if (declaration) {
      const SourceLocation& first = declaration->statement->location;
      if (declaration->statement == in.statement)  // a loop expanded it more than once
        throw SourceError(in.statement->location, "'independent' is repeated by its loop: declare the independent "
                                                  "speeds once, outside a loop or in one that runs once");
      throw SourceError(in.statement->location,
                        fmt::format("'independent' is given twice: the independent speeds are already declared at "
                                    "{}:{}:{}", first.file, first.line, first.column));
    }
    declaration = &in;
  }
  if (!declaration) return;
  const Statement& s = *declaration->statement;
  const Variables& vars = model_.system.variables();
  std::vector<std::string> coordinate_names;
  for (const Coordinate& c : vars.coordinates()) coordinate_names.push_back(c.name);
  std::vector<SourceLocation> listed_at;  // parallel to model_.independent_speeds
  for (const Name& n : s.names) {
    const std::string name = resolve(n, declaration->environment);
    const auto symbol = vars.find(name);
    if (!symbol || vars.kind_of(*symbol) != SymbolKind::coordinate) {
      const auto declared = declared_.find(name);
      if (declared == declared_.end()) unknown_name(name, n.location, coordinate_names, "coordinate");
      // a rate is the likely slip: the speeds are named by their coordinates
      if (declared->second.kind == "rate")
        throw SourceError(n.location, fmt::format("independent: '{}' is a rate: expected its coordinate '{}' (the "
                                                  "independent speeds are the rates of the listed coordinates)",
                                                  name, name.substr(0, name.size() - 4)));
      const std::string& kind = declared->second.kind;
      throw SourceError(n.location, fmt::format("independent: '{}' is {} {}, expected a coordinate", name,
                                                std::string("aeiou").find(kind[0]) == std::string::npos ? "a" : "an",
                                                kind));
    }
    const std::size_t k = *vars.coordinate_index(*symbol);
    const auto twice = std::find(model_.independent_speeds.begin(), model_.independent_speeds.end(), k);
    if (twice != model_.independent_speeds.end()) {
      const SourceLocation& first = listed_at[static_cast<std::size_t>(twice - model_.independent_speeds.begin())];
      throw SourceError(n.location, fmt::format("independent: coordinate '{}' is listed twice (first at {}:{}:{})",
                                                name, first.file, first.line, first.column));
    }
    model_.independent_speeds.push_back(k);
    listed_at.push_back(n.location);
  }
  // signed: nc < nq, or the constraints would be dependent
  const long nq = static_cast<long>(vars.coordinate_count());
  const long nc = static_cast<long>(model_.system.constraints().size());
  if (nc == 0)
    throw SourceError(s.location, "'independent' in a model without constraints: every speed is independent; "
                                  "expected no 'independent' statement");
  if (!model_.redundant_constraints.empty())
    throw SourceError(s.location, fmt::format("'independent' in a model with a redundant constraint ('{}'): the "
                                              "null-space method needs independent rows; expected no 'independent' "
                                              "statement (the KKT solve takes independent rows at each state)",
                                              model_.redundant_constraints.front().constraint.name));
  const long ni = static_cast<long>(model_.independent_speeds.size());
  if (ni != nq - nc)
    throw SourceError(s.location, fmt::format("independent: expected nq - nc = {} - {} = {} coordinates (one per "
                                              "degree of freedom), got {}", nq, nc, nq - nc, ni));
  independent_location_ = s.location;
}

// Checks that need every statement: an empty system, unused coordinates, constraints that are
// zero at a generic state (and those redundant there left out), and declared independent speeds
// that leave the dependent ones unsolvable there.
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

  // Xi of an independent set of the constraints (the redundant ones noted): the dependent
  // speeds are solved from it
  const Eigen::MatrixXd xi = note_redundant_constraints().xi;
  const std::size_t n = vars.coordinate_count();

  // the null-space method solves the dependent speeds from Xi_d qd_d = -(Xi_i qd_i + Xi_t): Xi_d,
  // the columns of the coordinates not listed, must be invertible at least at a generic state
  independent_speeds();
  const std::vector<std::size_t>& independent = model_.independent_speeds;
  if (independent.empty()) return;
  std::vector<std::string> dependent;
  Eigen::MatrixXd xi_d(xi.rows(), 0);
  for (std::size_t k = 0; k < n; ++k) {
    if (std::find(independent.begin(), independent.end(), k) != independent.end()) continue;
    dependent.push_back(vars.coordinates()[k].name);
    xi_d.conservativeResize(Eigen::NoChange, xi_d.cols() + 1);
    xi_d.col(xi_d.cols() - 1) = xi.col(static_cast<Eigen::Index>(k));
  }
  Eigen::FullPivLU<Eigen::MatrixXd> lu(xi_d);
  lu.setThreshold(1e-9);
  if (lu.rank() < xi_d.rows()) {
    std::string names;
    for (const std::string& d : dependent) names += (names.empty() ? "'" : ", '") + d + "'";
    throw SourceError(independent_location_,
                      fmt::format("independent: the constraints cannot be solved for the rates of the other "
                                  "coordinates ({}) at a generic state: their columns of Xi are singular; expected "
                                  "other independent coordinates", names));
  }
}

}  // namespace syntax

Model parse_model(const std::string& text, const std::string& file_name,
                  const std::map<std::string, double>& overrides) {
  if (text.size() > syntax::max_model_bytes)
    throw SourceError({file_name, 1, 1}, fmt::format("the model is larger than {} MiB: expected a model file "
                                                     "(loops make large models from short text)",
                                                     syntax::max_model_bytes >> 20));
  const auto statements = syntax::parse_statements(text, file_name);
  syntax::Elaborator elaborator(file_name, overrides);
  Model model = elaborator.run(statements);
  if (model.name.empty()) {
    // an identifier, as a `model` statement would give: the name is written into JSON, CSV
    // headers and file names, and a file name may hold any byte but '/'
    const std::string stem = file_name.substr(file_name.find_last_of('/') + 1);
    for (const char c : stem.substr(0, stem.find('.')))
      model.name += std::isalnum(static_cast<unsigned char>(c)) && static_cast<unsigned char>(c) < 128 ? c : '_';
    if (model.name.empty() || std::isdigit(static_cast<unsigned char>(model.name[0]))) model.name = "model_" + model.name;
  }
  return model;
}

Model load_model(const std::string& path, const std::map<std::string, double>& overrides,
                 const urdf::ImportOptions& import_options) {
  // a robot's description: the model `eomgen import` writes from it, read as that text. The
  // import checks what the text could get wrong at its place in the URDF; a later error (an
  // override of a name the text lacks, say) names a place in the text `eomgen import` shows.
  if (urdf::is_urdf_path(path))
    return parse_model(urdf::import_urdf(path, import_options).text, path + " (as imported)", overrides);
  if (import_options.repair_inertia || import_options.floating_base || import_options.fix_massless_joints)
    throw Error(fmt::format("{}: a model file takes no URDF import options (repair_inertia, floating_base, fix_massless_joints)", path));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("{}: error: cannot read the model file", path));
  const std::string text = read_at_most(in, syntax::max_model_bytes);
  if (in.bad()) throw Error(fmt::format("{}: error: cannot read the model file", path));
  return parse_model(text, path, overrides);
}

}  // namespace eomgen
