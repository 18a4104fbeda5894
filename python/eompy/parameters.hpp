#pragma once
/// \file
/// The Parameters and Constants classes of a model's module.
///
/// Parameters holds one value per model parameter, each an attribute, defaulted to the model's
/// values; setting one to anything but a finite real number is a ValueError or TypeError, and
/// a name the model does not have is an UnknownNameError (an AttributeError and a ValueError).
/// A Parameters object builds its Constants (the generated code's values that depend on the
/// parameters alone) at its first use in a call and keeps them until a value changes, so
/// passing Parameters costs what passing Constants does.
#include <pybind11/pybind11.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>

namespace eompy {

namespace py = pybind11;

/// The text the generator writes for a model besides its header: each parameter's Python
/// attribute name (the model's name, with a trailing _ where it is a Python keyword) and unit.
template <class Model>
struct ParameterText {
  std::array<const char*, Model::np> attributes;
  std::array<const char*, Model::np> units;
};

/// What the Python class Parameters holds.
template <class Model>
class ParameterSet {
 public:
  using Values = typename Model::template Parameters<double>;
  using Constants = typename Model::template Constants<double>;

  ParameterSet() = default;
  explicit ParameterSet(const Values& values) : values_(values) {}

  double get(std::size_t k) const { return *const_cast<Values&>(values_).fields()[k]; }
  void set(std::size_t k, double v) {
    *values_.fields()[k] = v;
    constants_.reset();
  }
  const Values& values() const { return values_; }
  const Constants& constants() const {
    if (!constants_) constants_.emplace(values_);
    return *constants_;
  }

 private:
  Values values_;
  mutable std::optional<Constants> constants_;
};

/// The exception for a name the model does not have: an AttributeError (so that hasattr and
/// getattr's default work) and a ValueError.
inline py::object unknown_name_error(py::module_& m) {
  if (py::hasattr(m, "UnknownNameError")) return m.attr("UnknownNameError");
  py::dict body;
  body["__doc__"] = "A parameter, coordinate or input name the model does not have.";
  body["__module__"] = m.attr("__name__");
  py::object error = py::reinterpret_borrow<py::object>(reinterpret_cast<PyObject*>(&PyType_Type))(
      "UnknownNameError",
      py::make_tuple(py::reinterpret_borrow<py::object>(PyExc_AttributeError),
                     py::reinterpret_borrow<py::object>(PyExc_ValueError)),
      body);
  m.attr("UnknownNameError") = error;
  return error;
}

namespace detail {

/// A parameter's new value: a finite real number.
inline double parameter_value(py::handle value, const std::string& name) {
  const auto refuse = [&] {
    throw py::type_error("parameter " + name + ": expected a real number, got an object of type " +
                         std::string(py::str(py::type::handle_of(value).attr("__name__"))));
  };
  if (PyBool_Check(value.ptr()) || PyComplex_Check(value.ptr())) refuse();
  const double v = PyFloat_AsDouble(value.ptr());  // a float, an int, or what has __float__ or __index__
  if (v == -1.0 && PyErr_Occurred()) {
    PyErr_Clear();
    refuse();
  }
  if (!std::isfinite(v)) throw py::value_error("parameter " + name + ": expected a finite number, got " + std::to_string(v));
  return v;
}

template <class Model>
std::string parameter_list(const ParameterText<Model>& text) {
  std::string s;
  for (std::size_t k = 0; k < Model::np; ++k) s += (k ? ", " : "") + std::string(text.attributes[k]);
  return s.empty() ? "none" : s;
}

template <class Model>
std::optional<std::size_t> parameter_index(const ParameterText<Model>& text, const std::string& name) {
  for (std::size_t k = 0; k < Model::np; ++k)
    if (name == text.attributes[k]) return k;
  return std::nullopt;
}

template <class Model>
[[noreturn]] void unknown_parameter(py::object error, const ParameterText<Model>& text, const std::string& name) {
  PyErr_SetString(error.ptr(), (std::string(Model::name) + " has no parameter '" + name + "'; its parameters: " +
                                parameter_list(text))
                                   .c_str());
  throw py::error_already_set();
}

template <class Model>
std::string parameters_repr(const std::string& module, const ParameterSet<Model>& s, const ParameterText<Model>& text) {
  std::string r = module + ".Parameters(";
  for (std::size_t k = 0; k < Model::np; ++k)
    r += (k ? ", " : "") + std::string(text.attributes[k]) + "=" + std::string(py::repr(py::float_(s.get(k))));
  return r + ")";
}

}  // namespace detail

/// Defines the classes Parameters and Constants in \p m.
template <class Model>
void define_parameters(py::module_& m, const ParameterText<Model>& text) {
  using Set = ParameterSet<Model>;
  using Constants = typename Set::Constants;
  const py::object error = unknown_name_error(m);

  py::class_<Set> parameters(m, "Parameters",
                             "The model's parameters, each an attribute, defaulted to the model's values; "
                             "Parameters(name=value, ...) overrides some.");
  parameters.def(py::init([text, error](const py::kwargs& values) {
                   Set s;
                   for (const auto& [key, value] : values) {
                     const std::string name = py::str(key);
                     const std::optional<std::size_t> k = detail::parameter_index(text, name);
                     if (!k) detail::unknown_parameter(error, text, name);
                     s.set(*k, detail::parameter_value(value, name));
                   }
                   return s;
                 }));
  // attributes are the parameters only: a misspelt name is an error, not a new attribute
  parameters.def("__setattr__", [text, error](Set& s, const std::string& name, py::handle v) {
    const std::optional<std::size_t> k = detail::parameter_index(text, name);
    if (!k) detail::unknown_parameter(error, text, name);
    s.set(*k, detail::parameter_value(v, name));
  });
  parameters.def("__getattr__", [text, error](const Set&, const std::string& name) -> py::object {
    detail::unknown_parameter(error, text, name);
  });
  // the module's name, which eval() of the repr finds (a model named NULL is the module NULL_)
  const std::string module = py::str(m.attr("__name__"));
  parameters.def("__repr__", [text, module](const Set& s) { return detail::parameters_repr(module, s, text); });
  parameters.def("__eq__", [](const Set& a, const Set& b) {
    for (std::size_t k = 0; k < Model::np; ++k)
      if (a.get(k) != b.get(k)) return false;
    return true;
  });
  parameters.def("__copy__", [](const Set& s) { return Set(s.values()); });
  parameters.def("__deepcopy__", [](const Set& s, py::handle) { return Set(s.values()); });
  parameters.def(py::pickle([](const Set& s) {
                              py::tuple state(Model::np);
                              for (std::size_t k = 0; k < Model::np; ++k) state[k] = s.get(k);
                              return state;
                            },
                            [](const py::tuple& state) {
                              if (state.size() != Model::np) throw py::value_error("Parameters: a pickle of another model");
                              Set s;
                              for (std::size_t k = 0; k < Model::np; ++k)
                                s.set(k, detail::parameter_value(state[k], Model::parameter_names[k]));
                              return s;
                            }));
  parameters.def(
      "to_dict",
      [text](const Set& s) {
        py::dict d;
        for (std::size_t k = 0; k < Model::np; ++k) d[text.attributes[k]] = s.get(k);
        return d;
      },
      "The values by name, in the model's order.");
  parameters.attr("__hash__") = py::none();  // mutable, compared by value
  // the parameters last: one named like a method (to_dict) is the parameter
  for (std::size_t k = 0; k < Model::np; ++k) {
    const std::string name = text.attributes[k];
    parameters.def_property(
        text.attributes[k], [k](const Set& s) { return s.get(k); },
        [k, name](Set& s, py::handle v) { s.set(k, detail::parameter_value(v, name)); },
        (std::string("[") + text.units[k] + "]").c_str());
  }

  py::class_<Constants>(m, "Constants",
                        "The values of the generated functions that depend on the parameters alone, computed once: "
                        "Constants(parameters). Immutable: for other parameters, build other Constants.")
      .def(py::init([](const Set& s) { return s.constants(); }), py::arg("parameters"))
      .def_property_readonly(
          "parameters", [](const Constants& c) { return Set(c.parameters()); },
          "A copy of the parameters these were computed from.")
      .def("__repr__", [text, module](const Constants& c) {
        return module + ".Constants(" + detail::parameters_repr(module, Set(c.parameters()), text) + ")";
      })
      .def(py::pickle([](const Constants& c) {
                        py::tuple state(Model::np);
                        const Set s(c.parameters());
                        for (std::size_t k = 0; k < Model::np; ++k) state[k] = s.get(k);
                        return state;
                      },
                      [](const py::tuple& state) {
                        if (state.size() != Model::np) throw py::value_error("Constants: a pickle of another model");
                        Set s;
                        for (std::size_t k = 0; k < Model::np; ++k)
                          s.set(k, detail::parameter_value(state[k], Model::parameter_names[k]));
                        return Constants(s.values());
                      }));
}

/// The Constants a call evaluates with: those of \p p (Parameters or Constants), or of the
/// defaults when \p p is None; \p defaults holds the latter.
template <class Model>
const typename Model::template Constants<double>& constants_of(py::handle p, const ParameterSet<Model>& defaults,
                                                               const char* function) {
  using Set = ParameterSet<Model>;
  using Constants = typename Set::Constants;
  if (p.is_none()) return defaults.constants();
  if (py::isinstance<Set>(p)) return p.cast<const Set&>().constants();
  if (py::isinstance<Constants>(p)) return p.cast<const Constants&>();
  throw py::type_error(std::string(function) + "(): p: expected " + Model::name + ".Parameters or " + Model::name +
                       ".Constants (or None for the defaults), got an object of type " +
                       std::string(py::str(py::type::handle_of(p).attr("__name__"))));
}

/// How a call finds the Constants of its p, fast: the classes' Python types are looked up once,
/// when a function is defined, and an argument of exactly one of them is read in place (a
/// general pybind11 cast per call would cost more than a small model's function).
template <class Model>
class ParameterTypes {
 public:
  using Set = ParameterSet<Model>;
  using Constants = typename Set::Constants;

  /// The classes must be defined in \p m (define_parameters); \p defaults outlives every call.
  ParameterTypes(const py::module_& m, const Set& defaults)
      : set_(reinterpret_cast<PyTypeObject*>(m.attr("Parameters").ptr())),
        constants_(reinterpret_cast<PyTypeObject*>(m.attr("Constants").ptr())),
        defaults_(&defaults) {}

  /// The Constants of \p p: Parameters, Constants or None (the defaults).
  /// \throws py::type_error for anything else
  const Constants& constants(py::handle p, const char* function) const {
    if (Py_TYPE(p.ptr()) == set_) return static_cast<const Set*>(value(p))->constants();
    if (Py_TYPE(p.ptr()) == constants_) return *static_cast<const Constants*>(value(p));
    return constants_of<Model>(p, *defaults_, function);  // None, a subclass, or an error
  }

 private:
  static const void* value(py::handle p) {
    return reinterpret_cast<py::detail::instance*>(p.ptr())->get_value_and_holder().value_ptr();
  }

  PyTypeObject* set_;
  PyTypeObject* constants_;
  const Set* defaults_;
};

}  // namespace eompy
