#pragma once
// The scalar symbols of a model: time, generalized coordinates with their rates, parameters
// and inputs. Symbols are created in declaration order, which keeps GiNaC's term order (it
// follows symbol serial numbers) the same from run to run for the same model.
#include <ginac/ginac.h>

#include <optional>
#include <string>
#include <set>
#include <vector>

#include "eomgen/symbolic/double_evaluator.hpp"

namespace eomgen {

/// A generalized coordinate q with its rate qd = dq/dt and acceleration qdd.
struct Coordinate {
  std::string name;
  GiNaC::realsymbol q;
  GiNaC::realsymbol qd;
  GiNaC::realsymbol qdd;
  std::string unit;  // as the model wrote it, or empty
};

/// A constant of the model (length, mass, stiffness...) with its default value.
struct Parameter {
  std::string name;
  GiNaC::realsymbol symbol;
  double default_value = 0.0;
  std::string unit;
};

/// A parameter defined from others (`parameter d1 = 0.45*L1`). It is a symbol of its own in
/// the equations, so they refer to it by name, however often and however deeply it is used; its
/// value follows from the parameters: computed once per parameter set, in the order of
/// declaration, each derived parameter from the parameters and the derived parameters before it.
/// It has no value of its own to set: it always agrees with its definition.
struct DerivedParameter {
  std::string name;
  GiNaC::realsymbol symbol;
  GiNaC::ex definition;      // in numbers, parameters and earlier derived parameters
  double default_value = 0;  // at the parameters' defaults
  std::string unit;          // as written in the model, or empty
};

/// An external input u (a force, a torque, a motor command) known as a function of time.
struct Input {
  std::string name;
  GiNaC::realsymbol symbol;
  std::string unit;  // as the model wrote it, or empty
};

/// What kind of quantity a symbol of the model stands for.
enum class SymbolKind { time, coordinate, rate, acceleration, parameter, derived_parameter, input };

/// Whether a symbol of this kind has the same value at every state: a parameter, derived or not.
bool is_parameter_kind(SymbolKind kind);

/// LaTeX for a symbol name: Greek letters as commands, trailing digits and "_x" as subscripts,
/// "_dot"/"_ddot" as accents: "theta_dot" -> "\dot{\theta}", "l_fh" -> "l_{\mathrm{fh}}".
std::string tex_name(const std::string& name);

/// Every symbol in e, visiting shared subexpressions once (linear in the expression's graph).
GiNaC::exset symbols_of(const GiNaC::ex& e);

/// e in doubles with its symbols at the numbers `values` gives them, each shared node once
/// (GiNaC's subs() and evalf() walk the tree): inf or NaN where e has a pole there; nothing where
/// a symbol of e has no real number in `values` or e is complex.
std::optional<double> value_in_doubles(const GiNaC::ex& e, const GiNaC::exmap& values);

class Variables {
 public:
  Variables();

  /// Declares a symbol; returns it by value (symbols are cheap handles).
  /// \throws ModelError if the name is empty, not an identifier, or already used.
  Coordinate add_coordinate(const std::string& name, const std::string& unit = "");
  Parameter add_parameter(const std::string& name, double default_value,
                                 const std::string& unit = "");
  Input add_input(const std::string& name, const std::string& unit = "");
  /// Declares a parameter defined from `definition`, an expression in numbers, parameters and
  /// derived parameters declared before; its default is the definition's value at theirs.
  /// \throws ModelError for a name as add_parameter, a definition that names any other symbol,
  ///   or one whose value at the defaults is not a finite real number.
  DerivedParameter add_derived_parameter(const std::string& name, const GiNaC::ex& definition,
                                         const std::string& unit = "");

  const GiNaC::realsymbol& time() const { return time_; }
  const std::vector<Coordinate>& coordinates() const { return coordinates_; }
  const std::vector<Parameter>& parameters() const { return parameters_; }
  const std::vector<Input>& inputs() const { return inputs_; }
  /// In the order of declaration: each is defined from those before it.
  const std::vector<DerivedParameter>& derived_parameters() const { return derived_parameters_; }
  std::size_t coordinate_count() const { return coordinates_.size(); }

  /// The symbol of that name (coordinate, rate "name_dot", acceleration "name_ddot",
  /// parameter, derived parameter, input or "t"), if any.
  std::optional<GiNaC::realsymbol> find(const std::string& name) const;
  /// Kind of a symbol of this model, or nothing if the symbol is foreign to the model.
  std::optional<SymbolKind> kind_of(const GiNaC::ex& symbol) const;
  /// Index of the coordinate whose q, qd or qdd is this symbol.
  std::optional<std::size_t> coordinate_index(const GiNaC::ex& symbol) const;

  /// Indices (in parameters()) of the parameters e depends on, directly or through derived
  /// parameters, in increasing order.
  std::vector<std::size_t> parameters_in(const GiNaC::ex& e) const;

  /// Gives every derived parameter its value in `values`, which has one for every parameter:
  /// each computed from those before it, in doubles. \throws Error naming the first derived
  /// parameter whose value is not a finite real number at these values.
  void evaluate_derived_parameters(DoubleEvaluator& values) const;

  /// Whether e contains a symbol of that kind.
  bool contains(const GiNaC::ex& e, SymbolKind kind) const;

  /// \throws ModelError naming `what` if `e` contains a symbol that is not part of this model.
  void require_known_symbols(const GiNaC::ex& e, const std::string& what) const;

  /// Total time derivative d/dt e = de/dt + sum_k (de/dq_k qd_k + de/dqd_k qdd_k).
  /// \throws DerivationError if e contains an input or an acceleration (their rates are unknown).
  GiNaC::ex time_derivative(const GiNaC::ex& e) const;

  /// e with every rate qd_k set to zero.
  GiNaC::ex at_rest(const GiNaC::ex& e) const;
  /// e with every acceleration qdd_k set to zero.
  GiNaC::ex without_accelerations(const GiNaC::ex& e) const;

  /// All coordinate symbols q, in order.
  GiNaC::lst coordinate_list() const;
  GiNaC::lst rate_list() const;

 private:
  void check_name(const std::string& name) const;
  void claim_name(const std::string& name);

  GiNaC::realsymbol time_;
  std::vector<Coordinate> coordinates_;
  std::vector<Parameter> parameters_;
  std::vector<Input> inputs_;
  std::vector<DerivedParameter> derived_parameters_;
  std::set<std::string> names_;  // every declared name, for the duplicate check
  GiNaC::exmap kinds_;  // symbol -> numeric code of SymbolKind
  // parameter and derived parameter symbol -> its default value, so that a derived parameter's
  // default is computed from the symbols it names only (a chain of N definitions in O(N log N))
  GiNaC::exmap default_values_;
  GiNaC::exmap rate_to_zero_;
  GiNaC::exmap acceleration_to_zero_;
};

}  // namespace eomgen
