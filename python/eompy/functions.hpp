#pragma once
/// \file
/// A generated function as a Python function: its arguments read as arrays (arrays.hpp), the
/// function called once per state of a batch in C++, its outputs returned as new arrays.
///
/// The Python arguments are the C++ ones without the outputs, in their order and with their
/// names (lambda as lambda_); u may be left out (zeros), p may be left out (the defaults) or be
/// Parameters or Constants. When any state argument is a batch of N, the others are one value
/// each or N of them, the function runs N times and every result gains a first dimension N.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "eompy/arrays.hpp"
#include "eompy/parameters.hpp"

namespace eompy {

namespace py = pybind11;

/// An argument of a generated function.
enum class Arg { t, q, qd, qdd, u, lambda, p };

/// What a generated function returns besides its outputs.
enum class Returns {
  nothing,
  scalar,      ///< its one output, a scalar (T, V)
  status,      ///< why the result is not regular (nullptr: it is); a ValueError then
};

/// The outputs of a function: rows, columns, and whether NumPy sees a vector.
template <int R, int C, bool vector>
struct Out {
  static constexpr int rows = R, cols = C;
  static constexpr bool is_vector = vector;
};

template <Arg... args>
struct Reads {};

constexpr const char* python_name(Arg a) {
  switch (a) {
    case Arg::t: return "t";
    case Arg::q: return "q";
    case Arg::qd: return "qd";
    case Arg::qdd: return "qdd";
    case Arg::u: return "u";
    case Arg::lambda: return "lambda_";
    case Arg::p: return "p";
  }
  return "?";
}

/// The state a function is called at: views of the arguments' entries for one state.
template <class Model>
struct Point {
  using Constants = typename Model::template Constants<double>;
  template <int n>
  using View = Eigen::Map<const Eigen::Matrix<double, n, 1>, Eigen::Unaligned, Eigen::InnerStride<>>;

  double t = 0;
  View<Model::nq> q{nullptr, Model::nq, Eigen::InnerStride<>(1)};
  View<Model::nq> qd{nullptr, Model::nq, Eigen::InnerStride<>(1)};
  View<Model::nq> qdd{nullptr, Model::nq, Eigen::InnerStride<>(1)};
  View<Model::nu> u{nullptr, Model::nu, Eigen::InnerStride<>(1)};
  View<Model::nc> lambda{nullptr, Model::nc, Eigen::InnerStride<>(1)};
  const Constants* c = nullptr;
};

namespace detail {

template <class Model>
py::ssize_t size_of(Arg a) {
  switch (a) {
    case Arg::q:
    case Arg::qd:
    case Arg::qdd:
      return Model::nq;
    case Arg::u: return Model::nu;
    case Arg::lambda: return Model::nc;
    case Arg::t:
    case Arg::p:
      return 0;
  }
  return 0;
}

/// Zero inputs, for a call that leaves u out.
template <class Model>
const double* zero_inputs() {
  static const std::array<double, Model::nu + 1> zeros{};
  return zeros.data();
}

template <class T>
py::object result_object(T&& results) {
  if constexpr (std::tuple_size_v<std::decay_t<T>> == 1)
    return std::move(std::get<0>(results).array);
  else
    return std::apply([](auto&... r) { return py::make_tuple(std::move(r.array)...); }, results);
}

}  // namespace detail

/// Defines the Python function \p name calling \p call(point, outputs...) per state.
template <class Model, Returns returns, class Reads, class... Outs>
struct FunctionDefinition;

template <class Model, Returns returns, Arg... args, class... Outs>
struct FunctionDefinition<Model, returns, Reads<args...>, Outs...> {
  static constexpr std::size_t count = sizeof...(args);

  template <class Call>
  static void define(py::module_& m, const char* name, const std::string& doc, const ParameterSet<Model>& defaults,
                     Call call) {
    const std::string function = name;
    const ParameterTypes<Model> parameters(m, defaults);
    auto body = [function, parameters, call](const std::array<py::handle, count>& values) -> py::object {
      return evaluate(function, parameters, call, values, std::make_index_sequence<count>());
    };
    define_with(m, name, doc, body, std::make_index_sequence<count>());
    // the functions of states and their arguments, by name: for introspection and tests
    if (!py::hasattr(m, "functions")) m.attr("functions") = py::dict();
    m.attr("functions")[name] = py::make_tuple(python_name(args)...);
  }

 private:
  /// Reads the arguments, runs \p call per state, returns the results (see the file comment).
  template <class Call, std::size_t... I>
  static py::object evaluate(const std::string& function, const ParameterTypes<Model>& parameters, const Call& call,
                             const std::array<py::handle, count>& values, std::index_sequence<I...>) {
    constexpr std::array<const char*, count> names{python_name(args)...};
    std::array<Argument, count> read{};
    Point<Model> point;
    (read_argument<args>(values[I], ArgumentName{function, names[I]}, parameters, read[I], point), ...);
    const py::ssize_t batch = batch_size(function, names, read);
    const py::ssize_t n = batch < 0 ? 1 : batch;
    std::tuple<Result<Outs::rows, Outs::cols, Outs::is_vector>...> results{
        Result<Outs::rows, Outs::cols, Outs::is_vector>(batch)...};
    double scalar = 0;
    py::object scalars;  // a scalar function's batch of results (not py::array: that would make an empty one)
    double* scalar_out = &scalar;
    if constexpr (returns == Returns::scalar) {
      if (batch >= 0) {
        const Py_intptr_t dimensions[1] = {batch};
        scalars = new_doubles(1, dimensions);
        scalar_out = reinterpret_cast<double*>(py::detail::array_proxy(scalars.ptr())->data);
      }
    }
    py::ssize_t irregular = -1;
    const char* reason = nullptr;
    {
      // a large batch runs without the GIL: other Python threads go on meanwhile
      std::optional<py::gil_scoped_release> release;
      if (n >= 64) release.emplace();
      for (py::ssize_t k = 0; k < n; ++k) {
        (bind<args>(point, read[I], k), ...);
        if constexpr (returns == Returns::nothing) {
          std::apply([&](auto&... r) { call(point, r.at(k)...); }, results);
        } else if constexpr (returns == Returns::scalar) {
          scalar_out[k] = call(point);
        } else {
          const char* why = std::apply([&](auto&... r) { return call(point, r.at(k)...); }, results);
          if (why != nullptr && irregular < 0) irregular = k, reason = why;
        }
      }
    }
    if constexpr (returns == Returns::scalar) {
      if (batch < 0) return py::float_(scalar);
      return scalars;
    } else {
      if (irregular >= 0)
        throw py::value_error(function + "(): " +
                              (batch < 0 ? std::string() : "at state " + std::to_string(irregular) + ": ") + reason);
      return detail::result_object(std::move(results));
    }
  }

  /// Reads the argument \p a of a call into \p out (a state argument) or \p point (p).
  template <Arg a>
  static void read_argument(py::handle value, const ArgumentName& name, const ParameterTypes<Model>& parameters,
                            Argument& out, Point<Model>& point) {
    if constexpr (a == Arg::p)
      point.c = &parameters.constants(value, name.function.c_str());
    else if constexpr (a == Arg::t)
      read_scalar(value, name, out);
    else if (a == Arg::u && value.is_none())
      out.data = detail::zero_inputs<Model>();
    else
      read_vector(value, detail::size_of<Model>(a), name, out);
  }

  /// Points the view of \p a in \p point at state \p k of \p arg (a Map is re-pointed by
  /// constructing it anew in place, Eigen's documented way).
  template <Arg a>
  static void bind(Point<Model>& point, const Argument& arg, py::ssize_t k) {
    using P = Point<Model>;
    const double* data = arg.at(k);
    const Eigen::InnerStride<> stride(arg.inner);
    if constexpr (a == Arg::t) point.t = *data;
    if constexpr (a == Arg::q) new (&point.q) typename P::template View<Model::nq>(data, Model::nq, stride);
    if constexpr (a == Arg::qd) new (&point.qd) typename P::template View<Model::nq>(data, Model::nq, stride);
    if constexpr (a == Arg::qdd) new (&point.qdd) typename P::template View<Model::nq>(data, Model::nq, stride);
    if constexpr (a == Arg::u) new (&point.u) typename P::template View<Model::nu>(data, Model::nu, stride);
    if constexpr (a == Arg::lambda) new (&point.lambda) typename P::template View<Model::nc>(data, Model::nc, stride);
  }

  template <class Body, std::size_t... I>
  static void define_with(py::module_& m, const char* name, const std::string& doc, Body body,
                          std::index_sequence<I...>) {
    constexpr std::array<Arg, count> kinds{args...};
    m.def(
        name,
        [body](std::conditional_t<(I < count), py::handle, void>... values) {
          return body(std::array<py::handle, count>{values...});
        },
        argument(kinds[I])..., doc.c_str());
  }

  static py::arg_v argument(Arg a) {
    if (a == Arg::u || a == Arg::p) return py::arg(python_name(a)) = py::none();
    return py::arg_v(python_name(a), py::none(), "required");
  }
};

}  // namespace eompy
