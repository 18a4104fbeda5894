#include "eomgen/report/equation_printer.hpp"

#include "eomgen/symbolic/expression_map.hpp"
#include "eomgen/symbolic/expression_size.hpp"
#include "eomgen/symbolic/graph_calculus.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include "eomgen/base/error.hpp"
#include "eomgen/report/expression_printer.hpp"
#include "eomgen/symbolic/simplify.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

// one printed equation, "label = value"
struct Entry {
  std::string label;      // text and Markdown: "M[1,2]"
  std::string tex_label;  // LaTeX (math mode): "M_{1,2}"
  ex value;
};

// one part of the equations under a heading
struct Section {
  std::string title;      // text and Markdown
  std::string tex_title;  // LaTeX (text mode)
  std::string note;       // plain text, e.g. which constraint each row is
  std::vector<Entry> entries;
};

struct PartKey {
  const char* key;
  bool EquationParts::*flag;
};

// the keys of --only, in printing order
constexpr PartKey part_keys[] = {
    {"M", &EquationParts::mass_matrix},          {"F", &EquationParts::forcing},
    {"Xi", &EquationParts::constraint_jacobian}, {"Xi_t", &EquationParts::constraint_rate_term},
    {"b", &EquationParts::constraint_acceleration_term}, {"phi", &EquationParts::holonomic_residuals},
    {"T", &EquationParts::kinetic_energy},       {"V", &EquationParts::potential_energy},
    {"outputs", &EquationParts::outputs},        {"tau", &EquationParts::inverse_dynamics},
    {"g", &EquationParts::gravity_forces},       {"C", &EquationParts::coriolis_matrix},
    {"J", &EquationParts::output_jacobians},     {"regressor", &EquationParts::regressor},
};

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? separator : "") + items[i];
  return out;
}

// escapes text for LaTeX text mode (names with '_', units such as m/s^2)
std::string tex_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      // accents on nothing rather than \textasciicircum, which needs the TS1 fonts
      case '\\': out += "$\\backslash$"; break;
      case '^': out += "\\^{}"; break;
      case '~': out += "\\~{}"; break;
      case '_': case '{': case '}': case '$': case '&': case '#': case '%': out += std::string("\\") + c; break;
      default: out += c;
    }
  }
  return out;
}

std::vector<std::string> output_labels(const Output& o) {
  if (o.labels.size() == o.components.size()) return o.labels;
  if (o.components.size() == 1) return {o.name};
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < o.components.size(); ++i) labels.push_back(fmt::format("{}_{}", o.name, i + 1));
  return labels;
}

std::vector<std::string> constraint_names(const MechanicalSystem& s, bool holonomic_only) {
  std::vector<std::string> names;
  for (const Constraint& c : s.constraints())
    if (!holonomic_only || c.kind == Constraint::Kind::holonomic) names.push_back(c.name);
  return names;
}

std::string row_note(const std::vector<std::string>& names) {
  std::vector<std::string> rows;
  for (std::size_t i = 0; i < names.size(); ++i) rows.push_back(fmt::format("{} = {}", i + 1, names[i]));
  return "rows: " + join(rows, ", ");
}

// entries of a column (or of each row of a matrix), labelled name[i] or name[i,j] (1-based)
std::vector<Entry> matrix_entries(const GiNaC::matrix& m, const std::string& name, const std::string& tex,
                                  bool column, bool upper_only = false) {
  std::vector<Entry> out;
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = upper_only ? i : 0; j < m.cols(); ++j)
      out.push_back(column ? Entry{fmt::format("{}[{}]", name, i + 1), fmt::format("{}_{{{}}}", tex, i + 1), m(i, j)}
                           : Entry{fmt::format("{}[{},{}]", name, i + 1, j + 1),
                                   fmt::format("{}_{{{},{}}}", tex, i + 1, j + 1), m(i, j)});
  return out;
}

// the selected parts as given by the derivation (possibly referring to intermediates)
// the selected functions for controllers, their terms referred to the merged intermediates by `renamed`
void function_sections(std::vector<Section>& out, const Model& model, const HeaderFunctions& h,
                       const EquationParts& parts, const GiNaC::exmap& renamed) {
  const auto referred = [&](const GiNaC::matrix& m) {
    GiNaC::matrix r(m.rows(), m.cols());
    for (unsigned i = 0; i < m.rows(); ++i)
      for (unsigned j = 0; j < m.cols(); ++j) r(i, j) = substitute(m(i, j), renamed);
    return r;
  };
  const unsigned n = h.mass_matrix.rows();
  if (parts.inverse_dynamics)
    out.push_back({fmt::format("Inverse dynamics tau = M qdd - F ({} x 1, {})", n, to_string(h.inverse_dynamics_form.form)),
                   fmt::format("Inverse dynamics $\\tau = M \\ddot{{q}} - F$ (${} \\times 1$)", n), "",
                   matrix_entries(referred(h.inverse_dynamics), "tau", "\\tau", true)});
  if (parts.gravity_forces && h.gravity_forces)
    out.push_back({fmt::format("Gravity forces g = dV/dq ({} x 1)", n),
                   fmt::format("Gravity forces $g = \\partial V / \\partial q$ (${} \\times 1$)", n), "",
                   matrix_entries(referred(*h.gravity_forces), "g", "g", true)});
  if (parts.coriolis_matrix && h.coriolis_matrix)
    out.push_back({fmt::format("Coriolis matrix C ({0} x {0}), with dM/dt - 2 C skew-symmetric", n),
                   fmt::format("Coriolis matrix $C$ (${0} \\times {0}$), with $\\dot{{M}} - 2 C$ skew-symmetric", n), "",
                   matrix_entries(referred(*h.coriolis_matrix), "C", "C", false)});
  if ((parts.gravity_forces || parts.coriolis_matrix) && !h.gravity_forces)
    out.push_back({"Gravity forces and Coriolis matrix: none", "Gravity forces and Coriolis matrix: none",
                   h.no_coriolis_and_gravity, {}});
  if (parts.output_jacobians)
    for (const OutputJacobian& j : h.output_jacobians) {
      const std::string& name = model.outputs[j.output].name;
      bool velocity = false;
      switch (j.level) {
        case OutputJacobian::Level::position: velocity = false; break;
        case OutputJacobian::Level::velocity: velocity = true; break;
      }
      const std::string tex = "\\text{" + tex_escape(name) + "}";
      out.push_back({fmt::format("Jacobian of output {} ({} x {}): J = {}", name, j.jacobian.rows(), n,
                                 velocity ? "dy/dqd" : "dy/dq"),
                     fmt::format("Jacobian of output {} (${} \\times {}$)", tex_escape(name), j.jacobian.rows(), n), "",
                     matrix_entries(referred(j.jacobian), "J_" + name, "J^{" + tex + "}", false)});
      out.push_back({fmt::format("Bias of output {}: Jdot qd, its {} at qdd = 0", name, velocity ? "rate" : "acceleration"),
                     fmt::format("Bias of output {}: $\\dot{{J}} \\dot{{q}}$", tex_escape(name)), "",
                     matrix_entries(referred(j.bias), "Jdot_qd_" + name, "(\\dot{J}\\dot{q})^{" + tex + "}", true)});
    }
  if (parts.regressor && h.regressor) {
    out.push_back({fmt::format("Regressor Y ({} x {}), with M qdd - F = Y pi + (loads other than gravity)", n,
                               h.regressor->cols()),
                   fmt::format("Regressor $Y$ (${} \\times {}$), with $M \\ddot{{q}} - F = Y \\pi + \\ldots$", n,
                               h.regressor->cols()),
                   "", matrix_entries(referred(*h.regressor), "Y", "Y", false)});
    Section pi{"Inertial parameters pi (mass, first moment, inertia about the origin, in the body's frame)",
               "Inertial parameters $\\pi$", "", {}};
    for (std::size_t k = 0; k < h.inertial_parameter_names.size(); ++k)
      pi.entries.push_back({h.inertial_parameter_names[k], "\\text{" + tex_escape(h.inertial_parameter_names[k]) + "}",
                            substitute(h.inertial_parameters(unsigned(k), 0), renamed)});
    out.push_back(std::move(pi));
    if (const BaseParameters* base = h.base_parameters ? &*h.base_parameters : nullptr) {
      Section kept{fmt::format("Base parameters ({} of {}): Y pi = Y_base pi_base, Y_base the columns of Y named "
                               "first in each", base->names.size(), h.inertial_parameter_names.size()),
                   "Base parameters", "", {}};
      for (std::size_t k = 0; k < base->names.size(); ++k) {
        GiNaC::ex value = 0;
        for (Eigen::Index j = 0; j < base->combination.cols(); ++j)
          if (const double c = base->combination(static_cast<Eigen::Index>(k), j); c != 0)
            value += GiNaC::numeric(c) * substitute(h.inertial_parameters(static_cast<unsigned>(j), 0), renamed);
        kept.entries.push_back({base->names[k], "\\text{" + tex_escape(base->names[k]) + "}", value});
      }
      out.push_back(std::move(kept));
    }
  } else if (parts.regressor) {
    out.push_back({"Regressor: none", "Regressor: none", h.no_regressor, {}});
  }
}

std::vector<Section> raw_sections(const Model& model, const ModelEquations& eom, const EquationParts& parts) {
  const std::size_t n = eom.coordinate_count, m = eom.constraint_count;
  const std::string rows = row_note(constraint_names(model.system, false));
  std::vector<Section> out;
  if (parts.mass_matrix)
    out.push_back({fmt::format("Mass matrix M ({0} x {0}, symmetric: upper triangle shown)", n),
                   fmt::format("Mass matrix $M$ (${0} \\times {0}$, symmetric: upper triangle shown)", n), "",
                   matrix_entries(eom.mass_matrix, "M", "M", false, true)});
  if (parts.forcing)
    out.push_back({fmt::format("Forcing F ({} x 1)", n), fmt::format("Forcing $F$ (${} \\times 1$)", n), "",
                   matrix_entries(eom.forcing, "F", "F", true)});
  if (m > 0 && parts.constraint_jacobian)
    out.push_back({fmt::format("Constraint Jacobian Xi ({} x {})", m, n),
                   fmt::format("Constraint Jacobian $\\Xi$ (${} \\times {}$)", m, n), rows,
                   matrix_entries(eom.constraint_jacobian, "Xi", "\\Xi", false)});
  if (m > 0 && parts.constraint_rate_term)
    out.push_back({fmt::format("Constraint rate term Xi_t ({} x 1), with Xi qd + Xi_t = 0", m),
                   fmt::format("Constraint rate term $\\Xi_t$ (${} \\times 1$), with $\\Xi \\dot{{q}} + \\Xi_t = 0$", m),
                   rows, matrix_entries(eom.constraint_rate_term, "Xi_t", "(\\Xi_t)", true)});
  if (m > 0 && parts.constraint_acceleration_term)
    out.push_back({fmt::format("Constraint acceleration term b = dXi/dt qd + dXi_t/dt ({} x 1), "
                               "with Xi qdd + b = 0", m),
                   fmt::format("Constraint acceleration term $b = \\dot{{\\Xi}} \\dot{{q}} + \\dot{{\\Xi}}_t$ "
                               "(${} \\times 1$), with $\\Xi \\ddot{{q}} + b = 0$", m),
                   rows, matrix_entries(eom.constraint_acceleration_term, "b", "b", true)});
  if (eom.holonomic_residuals.rows() > 0 && parts.holonomic_residuals)
    out.push_back({fmt::format("Holonomic constraints phi(q, t) = 0 ({} x 1)", eom.holonomic_residuals.rows()),
                   fmt::format("Holonomic constraints $\\phi(q, t) = 0$ (${} \\times 1$)",
                               eom.holonomic_residuals.rows()),
                   row_note(constraint_names(model.system, true)),
                   matrix_entries(eom.holonomic_residuals, "phi", "\\phi", true)});
  if (parts.kinetic_energy) out.push_back({"Kinetic energy", "Kinetic energy", "", {{"T", "T", eom.kinetic_energy}}});
  if (parts.potential_energy)
    out.push_back({"Potential energy", "Potential energy", "", {{"V", "V", eom.potential_energy}}});
  if (parts.outputs && !model.outputs.empty()) {
    Section s{"Outputs", "Outputs", "", {}};
    std::size_t k = 0;
    for (const Output& o : model.outputs) {
      const std::vector<std::string> labels = output_labels(o);
      for (std::size_t i = 0; i < o.components.size(); ++i, ++k)
        s.entries.push_back({labels[i], "\\text{" + tex_escape(labels[i]) + "}", eom.output_component(k)});
    }
    out.push_back(std::move(s));
  }
  return out;
}

// Index of each intermediate's symbol (lookups only: never iterated, so no order leaks out).
class IntermediateIndex {
 public:
  explicit IntermediateIndex(const Subexpressions& z) {
    for (std::size_t i = 0; i < z.size(); ++i) index_.emplace(z.definitions()[i].symbol, i);
  }
  // the position of e among the definitions, if e is an intermediate
  std::optional<std::size_t> find(const ex& e) const {
    if (!GiNaC::is_a<GiNaC::symbol>(e)) return std::nullopt;
    if (const std::size_t* i = index_.find(e)) return *i;
    return std::nullopt;
  }
  // calls f(i) for every intermediate i in e, at least once each, visiting each node of e not
  // in `visited` once
  template <class F>
  void visit(const ex& e, F&& f, ExpressionMap<bool>& visited) const {
    if (const auto i = find(e)) return f(*i);
    if (e.nops() == 0 || !visited.emplace(e, true).second) return;
    for (std::size_t k = 0; k < e.nops(); ++k) visit(e.op(k), f, visited);
  }

 private:
  mutable ExpressionMap<std::size_t> index_;  // a map ordered by GiNaC compared symbols at every step
};

// The sizes of the entries written out (each intermediate at its written-out size), and
// multiplied out as simplify_for_display would print them (before like terms combine, so an
// upper bound): the tree size alone misses how products of sums multiply out, and the bicycle's
// kinetic energy is a tree of a few thousand nodes and 340 KB once expanded.
ExpressionSizes written_out_sizes(const Subexpressions& z) {
  ExpressionSizes sizes;
  for (const auto& d : z.definitions()) sizes.define(d.symbol, d.value);
  return sizes;
}

double sections_size(const std::vector<Section>& sections, const EquationsOfMotion& eom) {
  ExpressionSizes sizes = written_out_sizes(eom.subexpressions);
  double total = 0;
  for (const Section& s : sections)
    for (const Entry& e : s.entries) total += sizes.tree(e.value);
  return total;
}

double sections_expanded_size(const std::vector<Section>& sections, const EquationsOfMotion& eom) {
  ExpressionSizes sizes = written_out_sizes(eom.subexpressions);
  double total = 0;
  for (const Section& s : sections)
    for (const Entry& e : s.entries) total += sizes.expanded(e.value).nodes;
  return total;
}

// the definitions the printed entries depend on, directly or through other definitions
Section where_section(const std::vector<Section>& sections, const Subexpressions& z) {
  const IntermediateIndex index(z);
  std::vector<bool> needed(z.size(), false);
  ExpressionMap<bool> visited;
  const auto mark = [&](std::size_t i) { needed[i] = true; };
  for (const Section& s : sections)
    for (const Entry& e : s.entries) index.visit(e.value, mark, visited);
  // a definition only refers to earlier ones, so one backward pass closes the set
  for (std::size_t i = z.size(); i-- > 0;)
    if (needed[i]) index.visit(z.definitions()[i].value, mark, visited);
  Section where{"", "", "", {}};
  for (std::size_t i = 0; i < z.size(); ++i)
    if (needed[i]) {
      const std::string name = z.definitions()[i].symbol.get_name();
      where.entries.push_back({name, tex_name(name), z.definitions()[i].value});
    }
  where.title = fmt::format("where ({} intermediates, each defined from earlier ones)", where.entries.size());
  where.tex_title = fmt::format("where ({} intermediates, each defined from earlier ones)", where.entries.size());
  return where;
}

// the order of factors: parameters first, then inputs, time, coordinates, rates, and the
// intermediates by number, as one writes m*l^2*theta_dot^2 by hand
ExpressionPrinter make_printer(const Model& model, const ModelEquations& eom) {
  const Variables& v = model.system.variables();
  std::vector<ex> order;
  for (const Parameter& p : v.parameters()) order.push_back(p.symbol);
  for (const DerivedParameter& d : v.derived_parameters()) order.push_back(d.symbol);
  for (const Input& u : v.inputs()) order.push_back(u.symbol);
  order.push_back(v.time());
  for (const Coordinate& c : v.coordinates()) order.push_back(c.q);
  for (const Coordinate& c : v.coordinates()) order.push_back(c.qd);
  for (const Coordinate& c : v.coordinates()) order.push_back(c.qdd);
  for (const auto& d : eom.subexpressions.definitions()) order.push_back(d.symbol);
  return ExpressionPrinter(order);
}

// ---- text and Markdown ----

std::string parameter_text(const Parameter& p) {
  return fmt::format("{} = {}", p.name, p.default_value) + (p.unit.empty() ? "" : " [" + p.unit + "]");
}

std::vector<std::string> constraint_texts(const MechanicalSystem& s) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < s.constraints().size(); ++i) {
    const Constraint& c = s.constraints()[i];
    out.push_back(fmt::format("{}. {} ({})", i + 1, c.name,
                              c.kind == Constraint::Kind::holonomic ? "holonomic" : "nonholonomic"));
  }
  return out;
}

std::vector<std::string> coordinate_names(const Variables& v) {
  std::vector<std::string> names;
  for (const Coordinate& c : v.coordinates()) names.push_back(c.name);
  return names;
}

std::vector<std::string> input_names(const Variables& v) {
  std::vector<std::string> names;
  for (const Input& u : v.inputs()) names.push_back(u.name);
  return names;
}

const char* const equation_text = "M(q) qdd = F(q, qd, t, u) + Xi^T lambda";

void print_text(std::ostream& out, const Model& model, const ModelEquations& eom,
                const std::vector<Section>& sections, const ExpressionPrinter& printer) {
  const Variables& v = model.system.variables();
  out << "Model " << model.name << (model.description.empty() ? "" : ": " + model.description) << "\n\n";
  out << fmt::format("Coordinates (n = {}): {}\n", v.coordinate_count(), join(coordinate_names(v), ", "));
  out << "Parameters:" << (v.parameters().empty() ? " none" : "") << "\n";
  for (const Parameter& p : v.parameters()) out << "  " << parameter_text(p) << "\n";
  if (!v.derived_parameters().empty())
    out << "Derived parameters (each computed from the parameters and those before it):\n";
  for (const DerivedParameter& d : v.derived_parameters())
    out << fmt::format("  {} = {} = {}{}\n", d.name, printer.text(d.definition), d.default_value,
                       d.unit.empty() ? "" : " [" + d.unit + "]");
  out << "Inputs: " << (v.inputs().empty() ? "none" : join(input_names(v), ", ")) << "\n";
  out << fmt::format("Constraints (m = {}):", eom.constraint_count) << (eom.constraint_count ? "" : " none") << "\n";
  for (const std::string& c : constraint_texts(model.system)) out << "  " << c << "\n";
  out << "\n" << equation_text << (eom.constraint_count ? ", Xi qd + Xi_t = 0" : "") << "\n";
  for (const Section& s : sections) {
    out << "\n" << s.title << "\n";
    if (!s.note.empty()) out << "  (" << s.note << ")\n";
    for (const Entry& e : s.entries) out << "  " << e.label << " = " << printer.text(e.value) << "\n";
  }
}

void print_markdown(std::ostream& out, const Model& model, const ModelEquations& eom,
                    const std::vector<Section>& sections, const ExpressionPrinter& printer) {
  const Variables& v = model.system.variables();
  auto code = [](std::vector<std::string> names) {
    for (auto& n : names) n = "`" + n + "`";
    return names.empty() ? std::string("none") : join(names, ", ");
  };
  out << "# Equations of motion: " << model.name << "\n\n";
  if (!model.description.empty()) out << model.description << "\n\n";
  out << fmt::format("- Coordinates (n = {}): {}\n", v.coordinate_count(), code(coordinate_names(v)));
  out << "- Inputs: " << code(input_names(v)) << "\n";
  out << fmt::format("- Constraints (m = {}): {}\n", eom.constraint_count,
                     eom.constraint_count ? join(constraint_texts(model.system), "; ") : "none");
  if (!v.parameters().empty()) {
    out << "\n| Parameter | Default | Unit |\n| --- | --- | --- |\n";
    for (const Parameter& p : v.parameters()) out << fmt::format("| `{}` | {} | {} |\n", p.name, p.default_value, p.unit);
  }
  if (!v.derived_parameters().empty()) {
    out << "\n| Derived parameter | Definition | Default | Unit |\n| --- | --- | --- | --- |\n";
    for (const DerivedParameter& d : v.derived_parameters())
      out << fmt::format("| `{}` | `{}` | {} | {} |\n", d.name, printer.text(d.definition), d.default_value, d.unit);
  }
  out << "\n`" << equation_text << "`" << (eom.constraint_count ? ", `Xi qd + Xi_t = 0`" : "") << "\n";
  for (const Section& s : sections) {
    out << "\n## " << s.title << "\n\n";
    if (!s.note.empty()) out << s.note << "\n\n";
    out << "```text\n";
    for (const Entry& e : s.entries) out << e.label << " = " << printer.text(e.value) << "\n";
    out << "```\n";
  }
}

// ---- LaTeX ----

// printed characters per row of an align* (ExpressionPrinter::latex_width, an estimate): the
// widened article page holds about 75 beside a short label
constexpr double latex_line_width = 65;

void print_latex(std::ostream& out, const Model& model, const ModelEquations& eom,
                 const std::vector<Section>& sections, const ExpressionPrinter& printer) {
  const Variables& v = model.system.variables();
  out << "\\documentclass[10pt]{article}\n\\usepackage{amsmath}\n\\allowdisplaybreaks\n"
         "\\addtolength{\\textwidth}{4cm}\n\\addtolength{\\oddsidemargin}{-2cm}\n"
         "\\addtolength{\\evensidemargin}{-2cm}\n\\begin{document}\n\n";
  out << "\\section*{Equations of motion: " << tex_escape(model.name) << "}\n\n";
  if (!model.description.empty()) out << tex_escape(model.description) << "\n\n";
  // one $...$ per name, so a long list can break between names
  std::vector<std::string> coordinates, parameters;
  for (const Coordinate& c : v.coordinates()) coordinates.push_back("$" + printer.latex(c.q) + "$");
  for (const Parameter& p : v.parameters())
    parameters.push_back(fmt::format("${} = {}$", printer.latex(p.symbol), p.default_value) +
                         (p.unit.empty() ? "" : "~" + tex_escape(p.unit)));
  std::vector<std::string> derived;
  for (const DerivedParameter& d : v.derived_parameters())
    derived.push_back(fmt::format("${} = {} = {}$", printer.latex(d.symbol), printer.latex(d.definition), d.default_value) +
                      (d.unit.empty() ? "" : "~" + tex_escape(d.unit)));
  std::vector<std::string> inputs;
  for (const Input& u : v.inputs()) inputs.push_back("$" + printer.latex(u.symbol) + "$");
  out << "\\begin{itemize}\n";
  out << fmt::format("\\item Coordinates ($n = {}$): {}\n", v.coordinate_count(), join(coordinates, ", "));
  out << "\\item Parameters: " << (parameters.empty() ? "none" : join(parameters, "; ")) << "\n";
  if (!derived.empty()) out << "\\item Derived parameters: " << join(derived, "; ") << "\n";
  out << "\\item Inputs: " << (inputs.empty() ? "none" : join(inputs, ", ")) << "\n";
  out << fmt::format("\\item Constraints ($m = {}$): ", eom.constraint_count)
      << (eom.constraint_count ? tex_escape(join(constraint_texts(model.system), "; ")) : "none") << "\n";
  out << "\\end{itemize}\n\n\\[ M(q)\\,\\ddot{q} = F(q, \\dot{q}, t, u) + \\Xi^{T} \\lambda"
      << (eom.constraint_count ? ", \\qquad \\Xi \\dot{q} + \\Xi_t = 0" : "") << " \\]\n";
  for (const Section& s : sections) {
    out << "\n\\section*{" << s.tex_title << "}\n";
    if (!s.note.empty()) out << tex_escape(s.note) << "\n";
    out << "\\begin{align*}\n";
    for (std::size_t k = 0; k < s.entries.size(); ++k) {
      // long entries continue on further rows of the alignment, each led by its + or -
      const std::vector<std::string> lines = printer.latex_lines(s.entries[k].value, latex_line_width);
      out << "  " << s.entries[k].tex_label << " &= " << join(lines, " \\\\\n  &\\quad ")
          << (k + 1 < s.entries.size() ? " \\\\\n" : "\n");
    }
    out << "\\end{align*}\n";
  }
  out << "\n\\end{document}\n";
}

// whether the sections print in terms of the intermediates (PrintOptions)
bool shared_form(const std::vector<Section>& sections, const ModelEquations& eom, const PrintOptions& options) {
  switch (options.intermediates) {
    case IntermediateForm::written_out: return false;
    case IntermediateForm::shared: return true;
    case IntermediateForm::automatic:
      return eom.subexpressions.size() > options.max_intermediates ||
             sections_size(sections, eom) > options.max_written_out_size ||
             sections_expanded_size(sections, eom) > options.max_multiplied_out_size;
  }
  EOMGEN_UNREACHABLE("shared_form: an IntermediateForm outside its enumerators");
}

}  // namespace

EquationParts parse_equation_parts(const std::string& list) {
  EquationParts parts;
  for (const PartKey& p : part_keys) parts.*(p.flag) = false;
  std::vector<std::string> accepted;
  for (const PartKey& p : part_keys) accepted.push_back(p.key);
  std::istringstream in(list);
  std::string key;
  bool any = false;
  while (std::getline(in, key, ',')) {
    const auto it = std::find_if(std::begin(part_keys), std::end(part_keys),
                                 [&](const PartKey& p) { return key == p.key; });
    if (it == std::end(part_keys))
      throw Error(fmt::format("selecting parts to print: unknown part '{}'; accepted: {}", key, join(accepted, ", ")));
    parts.*(it->flag) = true;
    any = true;
  }
  if (!any) throw Error(fmt::format("selecting parts to print: the list is empty; accepted: {}", join(accepted, ", ")));
  return parts;
}

double written_out_size(const Model& model, const ModelEquations& eom, const EquationParts& parts) {
  return sections_size(raw_sections(model, eom, parts), eom);
}

double multiplied_out_size(const Model& model, const ModelEquations& eom, const EquationParts& parts) {
  return sections_expanded_size(raw_sections(model, eom, parts), eom);
}

bool uses_shared_form(const Model& model, const ModelEquations& eom, const PrintOptions& options) {
  return shared_form(raw_sections(model, eom, options.parts), eom, options);
}

void print_equations(std::ostream& out, const Model& model, const ModelEquations& equations,
                     const PrintOptions& options, const HeaderFunctions* functions) {
  // the functions for controllers refer to intermediates of their own: printed with the
  // equations' in one list
  std::optional<ModelEquations> merged;
  GiNaC::exmap renamed;
  if (options.parts.needs_header_functions()) {
    if (!functions)
      throw Error("printing the functions for controllers (tau, g, C, J, regressor) needs derive_header_functions");
    merged = with_function_intermediates(equations, *functions, renamed);
  }
  const ModelEquations& eom = merged ? *merged : equations;
  std::vector<Section> sections = raw_sections(model, eom, options.parts);
  if (functions && merged) function_sections(sections, model, *functions, options.parts, renamed);
  // each derived parameter written out in the parameters, in order (when asked for)
  GiNaC::exmap derived;
  if (options.expand_derived_parameters)
    for (const DerivedParameter& d : model.system.variables().derived_parameters())
      derived[d.symbol] = d.definition.subs(derived, GiNaC::subs_options::no_pattern);
  const auto written_out = [&](const ex& e) { return derived.empty() ? e : substitute(e, derived); };
  if (shared_form(sections, eom, options)) {
    Section where = where_section(sections, eom.subexpressions);
    if (!where.entries.empty()) sections.push_back(std::move(where));
    for (Section& s : sections)
      for (Entry& e : s.entries) e.value = written_out(e.value);
  } else {
    for (Section& s : sections)
      for (Entry& e : s.entries) e.value = simplify_for_display(written_out(eom.subexpressions.expand(e.value)));
  }
  const ExpressionPrinter printer = make_printer(model, eom);
  switch (options.format) {
    case EquationFormat::text: print_text(out, model, eom, sections, printer); break;
    case EquationFormat::latex: print_latex(out, model, eom, sections, printer); break;
    case EquationFormat::markdown: print_markdown(out, model, eom, sections, printer); break;
  }
}

std::string format_equations(const Model& model, const ModelEquations& eom, const PrintOptions& options,
                             const HeaderFunctions* functions) {
  std::ostringstream out;
  print_equations(out, model, eom, options, functions);
  return out.str();
}

}  // namespace eomgen
