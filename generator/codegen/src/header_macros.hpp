#pragma once
// The object- and function-like macros that the headers of generated code and of the
// simulation program define, or that the compiler predefines, with a name a model could
// give: data, so that generating a header never runs a compiler and gives the same bytes on
// every machine.
#include <string_view>

namespace eomgen {

/// True if `name` is one of the macros of header_macros.cpp.
bool is_header_macro(std::string_view name);

}  // namespace eomgen
