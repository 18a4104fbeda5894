#pragma once
// The unit check of a model that gives units: the elaborator states, as it builds each element,
// what dimension each of its expressions must have (an obligation), and finish() infers the
// coordinates' dimensions from the rotations and points they enter and checks every obligation.
// A model without units records nothing and pays nothing.
#include <ginac/ginac.h>

#include <optional>
#include <string>
#include <vector>

#include "eomgen/mechanics/dimension.hpp"
#include "eomgen/mechanics/variables.hpp"
#include "eomgen/mechanics/vector.hpp"
#include "model_syntax.hpp"

namespace eomgen::syntax {

class UnitChecks {
 public:
  /// What an obligation tells about the dimension of a coordinate without a unit: a rotation's
  /// angles and parameters are dimensionless, a point's offset a length.
  enum class Evidence { rotation, position, none };

  /// Before the declarations: whether the statement gives a unit, making the model one with units.
  void note(const Statement& s);
  bool active() const { return first_.has_value(); }

  /// The declarations, in file order. \throws SourceError for a parameter or input without a
  /// unit in a model with units.
  void parameter(const Parameter& p, const std::optional<Unit>& unit, const SourceLocation& at);
  void coordinate(const Coordinate& c, const std::optional<Unit>& unit);
  void input(const Input& u, const std::optional<Unit>& unit, const SourceLocation& at);
  /// A derived parameter, declared after the parameters its definition names: with a unit its
  /// definition must have that unit; without one it has its definition's. `at` is where the
  /// definition starts, `what` names the parameter. \throws SourceError where the parts of a
  /// definition without a unit disagree.
  void derived_parameter(const DerivedParameter& d, const std::optional<Unit>& unit, const SourceLocation& at,
                         const std::string& what);

  /// What an expression must measure: every term has dimension `expected` times
  /// dim(relative)^power. `what` names the statement ("moment 'drive'"), `role` the quantity
  /// ("a moment"), `preferred` the name of the expected unit where several fit ("J", "N m").
  struct Obligation {
    GiNaC::ex value;
    std::optional<Dimension> expected;  // none: its parts must only agree with each other
    GiNaC::ex relative = 1;
    Exponent power = 0;
    SourceLocation at;
    std::string what, role, preferred;
    Evidence evidence = Evidence::none;
    /// The expected dimension times dim(relative)^power.
    Obligation per(const GiNaC::ex& relative_to, Exponent k) const {
      Obligation o = *this;
      o.relative = relative_to;
      o.power = k;
      return o;
    }
  };
  static Obligation expect(const Dimension& expected, const SourceLocation& at, std::string what, std::string role,
                           std::string preferred = "", Evidence evidence = Evidence::none) {
    Obligation o;
    o.expected = expected;
    o.at = at;
    o.what = std::move(what);
    o.role = std::move(role);
    o.preferred = std::move(preferred);
    o.evidence = evidence;
    return o;
  }
  void require(const GiNaC::ex& value, const Obligation& obligation);
  /// Every term of every component of `v` in every frame.
  void require(const Vector& v, const Obligation& each);
  void require(const GiNaC::matrix& entries, const Obligation& each);
  /// The parts of `value` agree with each other.
  void require_consistent(const GiNaC::ex& value, const SourceLocation& at, const std::string& what);

  /// Infers the dimensions of coordinates without a unit and checks every obligation.
  /// \throws SourceError for a coordinate whose dimension nothing fixes and for the first
  /// obligation broken. Returns the dimension of every symbol of the model.
  DimensionMap finish(const Variables& vars, const std::vector<SourceLocation>& coordinate_locations);

 private:
  bool infer(const GiNaC::ex& value, const Dimension& expected, DimensionAnalysis& analysis);
  bool has_unknown(const GiNaC::ex& e) const;
  void fix(const Coordinate& c, const Dimension& d, DimensionAnalysis& analysis);
  void check(const Obligation& o, DimensionAnalysis& analysis) const;
  [[noreturn]] void missing(const std::string& kind, const std::string& name, const SourceLocation& at,
                            const std::string& where) const;

  std::optional<SourceLocation> first_;  // the first unit of the file
  DimensionMap known_;
  DimensionAnalysis parameters_{{}};  // the parameters declared so far, derived or not
  std::vector<Coordinate> unknown_;  // coordinates without a unit, not yet inferred
  std::vector<Obligation> obligations_;
};

}  // namespace eomgen::syntax
