// The floors of a call from Python (bench/python/python_bench.py compiles it; not part of the
// build): where the time of a module's one-state forward_dynamics(t, q, qd, u, c) goes. Built
// as a Python module with the flags eomgen compiles models' modules with, on the header of the
// model whose call it takes apart, the model's namespace renamed so that its Parameters and
// Constants are other C++ types than those of the model's own module (pybind11 registers a C++
// type once per process, and both modules are timed in one):
//
//   c++ -O2 -DNDEBUG -std=c++17 -shared -fPIC -fvisibility=hidden -I<dir of model.hpp> \
//       -I<repo>/python -I<repo>/runtime/include -I/usr/include/eigen3 -I<Python's headers> \
//       -Dcart_pole=cart_pole_bench_floor -DMODEL_NS=eomgen_models::cart_pole_bench_floor \
//       floor_module.cpp -o eomgen_bench_floor$(python3-config --extension-suffix)
//
// Each function takes the module function's five arguments, by the same names:
//   bare(t, q, qd, u=None, p=None)          pybind11's dispatch alone: nothing read, None returned
//   bare_result(...)                        and a new (nq,) float64 array returned
//   eompy_noop(...)                         eompy's whole call path (functions.hpp: reading the
//                                           arguments, the Constants, the result array, the status)
//                                           around a model function that does nothing; its result
//                                           is not written (its entries are whatever memory held)
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>

#include "eompy/functions.hpp"
#include "eompy/parameters.hpp"
#include "model.hpp"

#ifndef MODEL_NS
#error "define MODEL_NS, the namespace of the generated model (eomgen_models::NAME)"
#endif

namespace {

namespace py = pybind11;
using Model = MODEL_NS::Model;

// the arguments as eompy declares them: each with the default None (t, q and qd then refuse it)
template <class F>
void define_bare(py::module_& m, const char* name, F f) {
  m.def(name, f, py::arg_v("t", py::none(), "required"), py::arg_v("q", py::none(), "required"),
        py::arg_v("qd", py::none(), "required"), py::arg("u") = py::none(), py::arg("p") = py::none());
}

}  // namespace

PYBIND11_MODULE(eomgen_bench_floor, m) {
  define_bare(m, "bare", [](py::handle, py::handle, py::handle, py::handle, py::handle) {});
  define_bare(m, "bare_result", [](py::handle, py::handle, py::handle, py::handle, py::handle) {
    return py::array_t<double>(Model::nq);
  });

  std::array<const char*, Model::np> units{};
  units.fill("");
  const eompy::ParameterText<Model> text{Model::parameter_names, units};
  eompy::define_parameters<Model>(m, text);
  static const eompy::ParameterSet<Model> defaults;
  using eompy::Arg;
  using Noop = eompy::FunctionDefinition<Model, eompy::Returns::status,
                                         eompy::Reads<Arg::t, Arg::q, Arg::qd, Arg::u, Arg::p>,
                                         eompy::Out<Model::nq, 1, true>>;
  Noop::define(m, "eompy_noop", "eompy's call path around nothing", defaults,
               [](const eompy::Point<Model>&, auto&&) -> const char* { return nullptr; });
}
