#pragma once
// Turns the syntax tree of a model file into a Model, through the C++ API: loops expanded,
// names resolved, frames and points built in dependency order whatever the file order.
#include <ginac/ginac.h>

#include <array>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "eomgen/mechanics/model.hpp"
#include "model_syntax.hpp"
#include "model_units.hpp"

namespace eomgen::syntax {

/// The value of an expression: the language has scalars, physical vectors, columns (rotation
/// parameters) and matrices (inertia, DCMs, and the algebra of model_matrices.hpp).
struct Value {
  enum class Kind { scalar, vector, column, matrix };
  Kind kind = Kind::scalar;
  GiNaC::ex scalar;
  eomgen::Vector vector;
  GiNaC::matrix matrix;  // column: n x 1
  static Value of(GiNaC::ex e) { Value v; v.kind = Kind::scalar; v.scalar = std::move(e); return v; }
  static Value of(eomgen::Vector u) { Value v; v.kind = Kind::vector; v.vector = std::move(u); return v; }
  /// A column when m has one column, else a matrix.
  static Value of_matrix(GiNaC::matrix m) {
    Value v;
    v.kind = m.cols() == 1 ? Kind::column : Kind::matrix;
    v.matrix = std::move(m);
    return v;
  }
};

std::string kind_name(Value::Kind kind);

/// e at a state that gives every symbol in it a number, or nothing where e is not a real number
/// there (a pole, a root of a negative number, a symbol the state leaves free).
std::optional<double> value_at(const GiNaC::ex& e, const GiNaC::exmap& state);

/// Loop variables of the current iteration.
using Environment = std::map<std::string, GiNaC::numeric>;

/// The keyword of a statement ("spring", "for"), which messages about it start with.
const char* statement_word(Statement::Kind kind);

/// The pass of Elaborator::run that elaborates a kind of statement. pass_of and
/// Elaborator::add_element list every kind, so that a kind the parser produces and no pass
/// handles does not compile.
enum class Pass { flatten, declarations, frames_and_points, elements, independent_speeds };
Pass pass_of(Statement::Kind kind);

/// The unit tangents t1, t2 of a plane of unit normal n (docs/model-language.md, roll), inertial.
std::array<GiNaC::matrix, 2> plane_tangents(const GiNaC::matrix& n);

/// The three entries of a 3x1 column.
inline std::array<GiNaC::ex, 3> column_entries(const GiNaC::matrix& c) { return {c(0, 0), c(1, 0), c(2, 0)}; }

struct ConstraintRows;  // model_constraint_rows.hpp

/// One statement to elaborate, with the loop variables it was expanded under.
struct Instance {
  const Statement* statement;
  Environment environment;
};

class Elaborator {
 public:
  Elaborator(std::string file, const std::map<std::string, double>& overrides);
  Model run(const std::vector<Statement>& statements);

  // expression evaluation (model_expression.cpp)
  Value evaluate(const ExprPtr& e, const Environment& env);
  GiNaC::ex scalar(const ExprPtr& e, const Environment& env, const std::string& what);
  eomgen::Vector vector(const ExprPtr& e, const Environment& env, const std::string& what);
  GiNaC::numeric constant(const ExprPtr& e, const Environment& env, const std::string& what);
  int integer(const ExprPtr& e, const Environment& env, const std::string& what);
  std::string resolve(const Name& name, const Environment& env);
  FrameId frame_named(const Name& name, const Environment& env);
  PointId point_named(const Name& name, const Environment& env);

 private:
  friend class ExpressionEvaluator;
  Value call(const Expr& e, const Environment& env);
  Value sum(const Expr& e, const Environment& env);
  Value product(const Expr& e, const Environment& env);
  Value name_value(const Expr& e, const Environment& env);
  [[noreturn]] void unknown_name(const std::string& name, const SourceLocation& at,
                                 const std::vector<std::string>& candidates, const std::string& what);

  // statements (model_elaborator.cpp)
  void constants(const std::vector<Statement>& statements);
  void flatten(const std::vector<Statement>& statements, const Environment& env);
  void declare(const std::string& name, const std::string& kind, const SourceLocation& at);
  void expand(std::size_t tokens, const SourceLocation& at);
  void reject_hiding_loop_variables() const;
  void declarations();
  // parameters, derived ones built on demand (model_declarations.cpp)
  GiNaC::ex parameter_value(const std::string& name);
  [[noreturn]] void reject_in_parameter(const std::string& kind, const std::string& name, const SourceLocation& at) const;
  void collect_frames_and_points();
  FrameId build_frame(const std::string& name);
  PointId build_point(const std::string& name);
  void reject_non_unit(const GiNaC::matrix& part, const GiNaC::matrix& rest, const SourceLocation& at,
                       const std::string& what, const std::string& expected) const;
  void reject_non_rotation(const GiNaC::matrix& dcm, const SourceLocation& at) const;

  // generic states and the checks made at them (model_generic_states.cpp)
  std::vector<GiNaC::exmap> generic_states() const;
  void reject_zero_vector(const eomgen::Vector& v, const GiNaC::ex& length, const SourceLocation& at,
                          const std::string& what) const;

  // whole-model checks (model_file.cpp)
  void independent_speeds();
  void checks();
  // constraints whose rows are combinations of earlier ones, noted (they stay in the system); an
  // independent set of the rows (model_redundant_constraints.cpp)
  ConstraintRows note_redundant_constraints();

  // element statements (model_elements.cpp)
  class Arguments;  // an element statement's key = value arguments
  void element(const Instance& instance);
  void add_element(const Instance& instance, const std::string& name, const std::string& what);
  void body(const Instance& instance, const std::string& name, const std::string& what);
  void damper(const Instance& instance, const std::string& name, const std::string& what);
  void generalized_force(const Instance& instance, const std::string& what);
  // the constraint statement, scalar or vector (model_constraints.cpp)
  void constraint(const Instance& instance, const std::string& name, const std::string& what);
  void vector_constraint(const Instance& instance, const std::string& name, const std::string& what,
                         const eomgen::Vector& difference);
  void add_constraint_row(const std::string& name, const GiNaC::ex& expression, const SourceLocation& at);
  void output(const Instance& instance);
  void roll(const Instance& instance);
  // what roll and wheel share
  const RigidBody& rigid_body(const Arguments& args, const Environment& env);
  GiNaC::matrix plane_normal(const Argument& normal, const Environment& env, const std::string& what);
  eomgen::Vector material_velocity(const RigidBody& body, PointId at) const;
  std::vector<GiNaC::ex> no_slip_rows(const RigidBody& body, PointId contact, const GiNaC::matrix& unit_normal);
  std::vector<ContactForce::Row> add_rolling_rows(const std::string& name, const std::vector<GiNaC::ex>& rows,
                                                  const std::vector<GiNaC::matrix>& directions,
                                                  const SourceLocation& at);

  // the shape statement (model_shapes.cpp)
  void shape(const Instance& instance, const std::string& name, const std::string& what);
  void mesh_file_and_scale(VisualShape& shape, const Arguments& args, const std::string& what, const Environment& env);
  GiNaC::ex shape_length(const ExprPtr& value, const std::string& what, const std::string& role,
                         const Environment& env);

  // the wheel statement (model_wheel.cpp)
  static std::string wheel_contact_name(const std::string& wheel) { return wheel + "_contact"; }
  PointId wheel_contact(const Instance& instance, const std::string& contact_name);
  void wheel(const Instance& instance, const std::string& name, const std::string& what);

  std::string file_;
  std::map<std::string, double> overrides_;
  Model model_;
  std::map<std::string, GiNaC::ex> constants_;
  struct Declared {
    std::string kind;
    SourceLocation location;
  };
  std::map<std::string, Declared> declared_;
  std::vector<Instance> instances_;
  std::map<std::string, std::size_t> frame_instances_, point_instances_;  // name -> index in instances_
  std::map<std::string, FrameId> frames_;
  std::map<std::string, PointId> points_;
  std::vector<std::string> in_progress_;  // frames and points being built, innermost last
  std::set<std::string> used_coordinates_;
  std::map<std::string, std::size_t> parameter_instances_;  // name -> index in instances_
  std::map<std::string, GiNaC::ex> parameter_values_;  // the symbol of each, derived or not
  std::vector<std::string> parameters_in_progress_;  // innermost last
  SourceLocation independent_location_;  // of the `independent` keyword, when there is one
  bool kinematics_ready_ = false;
  bool saw_statement_ = false;
  std::size_t expanded_tokens_ = 0;  // expand()
  std::map<std::string, SourceLocation> loop_variables_;  // each name at its first loop
  UnitChecks units_;  // model_units.cpp: what the model's expressions must measure
};

}  // namespace eomgen::syntax
