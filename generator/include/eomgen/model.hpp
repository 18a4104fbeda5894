#pragma once
// A model read from a model file (.eom): the mechanical system built through the C++ API,
// plus what the file says beyond it (name, description, named outputs) and where each
// declaration sits in the file, so later checks can point at it.
#include <map>
#include <string>
#include <vector>

#include "eomgen/equations_of_motion.hpp"
#include "eomgen/mechanical_system.hpp"
#include "eomgen/source_location.hpp"

namespace eomgen {

/// A named quantity for post-processing: a scalar, or the components of a vector resolved in
/// a frame (`labels` then holds "name_1", "name_2", "name_3").
struct Output {
  std::string name;
  std::vector<GiNaC::ex> components;  // expressions in q, qd, t, parameters, inputs
  std::vector<std::string> labels;    // one per component
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
  /// Coordinate indices whose rates are the independent speeds of the null-space method, in the
  /// order of the `independent` statement (nq - nc of them); empty when the model declares none
  /// and the runtime takes the null space of Xi from a QR decomposition instead.
  std::vector<std::size_t> independent_speeds;
  /// Integer/real constants of the file after overrides (e.g. n of a chain).
  std::map<std::string, double> constants;
};

/// Parses model text. `overrides` replace `const` values (e.g. {"n", 8}).
/// \throws SourceError (file:line:col: error: ...) for every syntax or model error.
Model parse_model(const std::string& text, const std::string& file_name,
                  const std::map<std::string, double>& overrides = {});

/// Derives the model's equations, with its outputs bound to shared intermediates too
/// (EquationsOfMotion::outputs, in the order of the outputs' labels).
EquationsOfMotion derive_equations(const Model& model);

/// Output component k (counting the components of all outputs in order) as derived.
/// \throws Error if `equations` were derived from model.system alone (without outputs).
const GiNaC::ex& output_component(const Model& model, const EquationsOfMotion& equations, std::size_t k);

/// Reads and parses a model file. \throws SourceError, or Error if the file cannot be read.
Model load_model(const std::string& path, const std::map<std::string, double>& overrides = {});

}  // namespace eomgen
