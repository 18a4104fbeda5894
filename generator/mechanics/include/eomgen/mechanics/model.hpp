#pragma once
// A model: the mechanical system built through the C++ API, plus what a model file says beyond
// it (name, description, named outputs) and where each declaration sits in the file, so later
// checks can point at it. The language layer builds it (eomgen/language/model_file.hpp); the
// derivation turns it into equations (eomgen/derivation/model_equations.hpp).
#include <map>
#include <string>
#include <vector>

#include "eomgen/mechanics/dimension.hpp"
#include "eomgen/mechanics/mechanical_system.hpp"
#include "eomgen/mechanics/visual_shape.hpp"
#include "eomgen/base/note.hpp"
#include "eomgen/base/source_location.hpp"

namespace eomgen {

/// A named quantity for post-processing: a scalar, or the components of a vector resolved in
/// a frame (`labels` then holds "name_1", "name_2", "name_3").
struct Output {
  std::string name;
  std::vector<GiNaC::ex> components;  // expressions in q, qd, t, parameters, inputs
  std::vector<std::string> labels;    // one per component
  SourceLocation location;
};

/// A constraint row left out of the system as redundant: at a generic state its row of Xi is a
/// combination of the rows of earlier constraints, and so is its Xi_t, so every motion that
/// satisfies those satisfies it too (docs/model-language.md, constraint). A holonomic one holds
/// along such a motion where it holds at the start: kept so that a state can be checked
/// against it.
struct RedundantConstraint {
  Constraint constraint;                // name, kind and expression, as it would have been added
  std::vector<std::string> depends_on;  // the kept constraints its row is a combination of, in system order
  SourceLocation location;
};

struct Model {
  std::string name;
  std::string description;
  MechanicalSystem system;
  std::vector<Output> outputs;
  /// Where each coordinate and each constraint was declared (same order as in `system`).
  std::vector<SourceLocation> coordinate_locations;
  std::vector<SourceLocation> constraint_locations;
  /// The constraints of `system` that are redundant (their rows combinations of earlier ones at a
  /// generic state), in the order of the file; they stay in the system, and the solves take an
  /// independent set of rows at each state.
  std::vector<RedundantConstraint> redundant_constraints;
  /// What the reader of the file should know that is no error (one per redundant constraint),
  /// in the order found; the commands print them on standard error.
  std::vector<Note> notes;
  /// Coordinate indices whose rates are the independent speeds of the null-space method, in the
  /// order of the `independent` statement (nq - nc of them); empty when the model declares none
  /// and the runtime takes the null space of Xi from a QR decomposition instead.
  std::vector<std::size_t> independent_speeds;
  /// Where each derived parameter was declared (same order as system.variables().derived_parameters()).
  std::vector<SourceLocation> derived_parameter_locations;
  /// The dimension of every symbol (time, coordinates, rates, accelerations, parameters, inputs)
  /// where the model gives units; empty where it gives none, and nothing is checked.
  DimensionMap dimensions;
  /// How the bodies look in an animation (`shape` statements), in the order of the file; a body
  /// or particle without one is drawn as its default (docs/animation.md).
  std::vector<VisualShape> shapes;
  /// The contacts of `roll` and `wheel`, whose multipliers are forces at a point.
  std::vector<ContactForce> contacts;
  /// Integer/real constants of the file after overrides (e.g. n of a chain).
  std::map<std::string, double> constants;
};

}  // namespace eomgen
