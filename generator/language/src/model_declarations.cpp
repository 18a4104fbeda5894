// Declarations of a model file: parameters, coordinates and inputs. Parameters with a number for
// a value become parameters of the system; those defined from other parameters (`parameter d1 =
// 0.45*L1`) become its derived parameters: symbols of their own, which the equations name, and
// whose definitions are computed once per parameter set (DerivedParameter says why).
#include <fmt/format.h>

#include <cmath>

#include "eomgen/base/error.hpp"
#include "definition_in_progress.hpp"
#include "model_elaborator.hpp"

namespace eomgen::syntax {

using GiNaC::ex;
using Kind = Statement::Kind;

// A loop variable is looked up before every other name, so one named like a parameter,
// coordinate, rate, frame or element would silently replace it inside the loop.
void Elaborator::reject_hiding_loop_variables() const {
  for (const auto& [var, at] : loop_variables_) {
    const auto it = declared_.find(var);
    if (it == declared_.end()) continue;
    const SourceLocation& there = it->second.location;
    throw SourceError(at, fmt::format("loop variable '{}' hides the {} '{}' declared at {}:{}:{}: expected "
                                      "another loop variable name", var, it->second.kind, var, there.file,
                                      there.line, there.column));
  }
}

void Elaborator::declarations() {
  Variables& vars = model_.system.variables();
  for (const Instance& in : instances_) units_.note(*in.statement);
  // every name first: a derived parameter may use a parameter defined later in the file, and
  // must be told so when it names a coordinate or an input declared later
  for (std::size_t i = 0; i < instances_.size(); ++i) {
    const Statement& s = *instances_[i].statement;
    if (s.kind == Kind::parameter) {
      const std::string name = resolve(s.name, instances_[i].environment);
      declare(name, "parameter", s.name.location);
      parameter_instances_[name] = i;
    } else if (s.kind == Kind::coordinate || s.kind == Kind::input) {
      for (const Name& n : s.names) {
        const std::string name = resolve(n, instances_[i].environment);
        declare(name, s.kind == Kind::coordinate ? "coordinate" : "input", n.location);
        if (s.kind != Kind::coordinate) continue;
        declare(name + "_dot", "rate", n.location);
        declare(name + "_ddot", "acceleration", n.location);
      }
    }
  }
  // symbols in the order of the file, which GiNaC's order of terms follows
  for (const Instance& in : instances_) {
    const Statement& s = *in.statement;
    if (s.kind == Kind::parameter) {
      parameter_value(resolve(s.name, in.environment));
    } else if (s.kind == Kind::coordinate || s.kind == Kind::input) {
      for (std::size_t i = 0; i < s.names.size(); ++i) {
        const Name& n = s.names[i];
        const std::optional<Unit>& unit = s.units[i];
        const std::string name = resolve(n, in.environment);
        try {
          if (s.kind == Kind::coordinate) {
            units_.coordinate(vars.add_coordinate(name, unit ? unit->text : ""), unit);
            model_.coordinate_locations.push_back(n.location);
          } else {
            units_.input(vars.add_input(name, unit ? unit->text : ""), unit, n.location);
          }
        } catch (const ModelError& e) {
          throw SourceError(n.location, e.what());
        }
      }
    }
  }
}

void Elaborator::reject_in_parameter(const std::string& kind, const std::string& name, const SourceLocation& at) const {
  throw SourceError(at, fmt::format("parameter '{}': expected an expression of numbers, consts and other parameters, "
                                    "got the {} '{}'", parameters_in_progress_.back(), kind, name));
}

// Built on demand, from the first expression that names the parameter or in its turn in the
// file, so a derived parameter may use one defined after it and a cycle is found where it closes.
ex Elaborator::parameter_value(const std::string& name) {
  if (auto it = parameter_values_.find(name); it != parameter_values_.end()) return it->second;
  const Instance& in = instances_[parameter_instances_.at(name)];
  const Statement& s = *in.statement;
  const DefinitionInProgress building(parameters_in_progress_, "parameter", name, s.name.location, "parameters");
  const std::string what = fmt::format("parameter '{}'", name);
  const ex value = scalar(s.value, in.environment, what);
  Variables& vars = model_.system.variables();
  if (GiNaC::is_a<GiNaC::numeric>(value) || GiNaC::is_a<GiNaC::numeric>(value.evalf())) {
    const double number = constant(s.value, in.environment, what).to_double();
    const Parameter p = vars.add_parameter(name, number, s.unit ? s.unit->text : "");
    units_.parameter(p, s.unit, s.name.location);
    return parameter_values_[name] = p.symbol;
  }
  // every name in it was a number, a const or a parameter (name_value refuses the others), each
  // built before this one: a function of the parameters declared so far
  DerivedParameter d;
  try {
    d = vars.add_derived_parameter(name, value, s.unit ? s.unit->text : "");
  } catch (const ModelError& e) {
    throw SourceError(start_of(*s.value), e.what());
  }
  model_.derived_parameter_locations.push_back(s.name.location);
  units_.derived_parameter(d, s.unit, start_of(*s.value), what);
  return parameter_values_[name] = d.symbol;
}

}  // namespace eomgen::syntax
