#pragma once
// Which input of the generated functions each symbol of a model is.
#include "eomgen/codegen/cpp_printer.hpp"
#include "eomgen/codegen/lower.hpp"
#include "eomgen/mechanics/model.hpp"

namespace eomgen {

struct SymbolicLinearization;

/// t, every q, qd and u, every parameter and, with a linearization, every qdd and lambda.
/// Each is named by its spelling under `print`: the order of operands has always come from
/// those names, and with it the bytes of every generated header.
VariableNames bind_variables(const Model& model, const SymbolicLinearization* linearization,
                             const CppPrintOptions& print);

}  // namespace eomgen
