#pragma once
// A generated model as a Python module: the C++ source that binds every function of the
// model's header with pybind11, through the binding library python/eompy/ (docs/python.md).
#include <string>

#include "eomgen/derivation/header_functions.hpp"
#include "eomgen/mechanics/model.hpp"

namespace eomgen {

/// The module's name: the model's name as the header spells it (cpp_identifier), with a '_'
/// after a Python keyword (lambda -> lambda_), which no other name maps to.
std::string python_module_name(const Model& model);

/// `name` (a C++ identifier) as a Python attribute: itself, or with a '_' after a Python keyword.
std::string python_identifier(const std::string& name);

/// The source of the module of `model`, whose header `functions` describes (it must have been
/// derived with a linearization: the module's linearization() needs linearization_terms). It
/// includes the header as "model.hpp" and the library as "eompy/module.hpp", and defines one
/// Python function per function of the header; every text of the model in it is a string
/// literal written by cpp_string_contents. `module_name` (a Python identifier) is the name
/// `import` takes, which the compiled file's name must match.
std::string python_module_source(const Model& model, const HeaderFunctions& functions, const std::string& module_name);

}  // namespace eomgen
