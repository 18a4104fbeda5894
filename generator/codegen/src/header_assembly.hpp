#pragma once
// The assembly of a generated header around its functions, and the hash that identifies it.
#include <cstdint>
#include <string>
#include <vector>

#include "eomgen/codegen/emit_model.hpp"
#include "function_table.hpp"

namespace eomgen {

/// The model's hash: of every target and the functions' source (the equations as printed),
/// and of the declared independent speeds, which change how the runtime solves the model.
std::uint64_t model_fingerprint(const Model& model, const std::vector<FunctionSpec>& table,
                                const std::string& functions);

/// The header: banner, includes, namespaces, and the Model struct with its metadata, type
/// aliases, Parameters and `source` (the member functions' text) of `functions`.
std::string assemble_header(const Model& model, const HeaderFunctions& functions, const std::string& source,
                            std::uint64_t model_hash, const EmitOptions& options);

}  // namespace eomgen
