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

/// Points the view of \p a in \p point at state \p k of \p arg.
template <class Model>
void bind(Point<Model>& point, Arg a, const Argument& arg, py::ssize_t k) {
  const double* data = arg.at(k);
  const Eigen::InnerStride<> stride(arg.inner);
  using P = Point<Model>;
  // a Map is re-pointed by constructing it anew in place (Eigen's documented way)
  switch (a) {
    case Arg::t: point.t = *data; return;
    case Arg::q: new (&point.q) typename P::template View<Model::nq>(data, Model::nq, stride); return;
    case Arg::qd: new (&point.qd) typename P::template View<Model::nq>(data, Model::nq, stride); return;
    case Arg::qdd: new (&point.qdd) typename P::template View<Model::nq>(data, Model::nq, stride); return;
    case Arg::u: new (&point.u) typename P::template View<Model::nu>(data, Model::nu, stride); return;
    case Arg::lambda: new (&point.lambda) typename P::template View<Model::nc>(data, Model::nc, stride); return;
    case Arg::p: return;
  }
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
    const ParameterSet<Model>* parameters = &defaults;  // owned by the module (define_model)
    auto body = [function, parameters, call](const std::array<py::handle, count>& values) -> py::object {
      constexpr std::array<Arg, count> kinds{args...};
      constexpr std::array<const char*, count> names{python_name(args)...};
      std::array<Argument, count> read{};
      Point<Model> point;
      for (std::size_t i = 0; i < count; ++i) {
        const Arg a = kinds[i];
        const ArgumentName what{function, names[i]};
        if (a == Arg::p) {
          point.c = &constants_of<Model>(values[i], *parameters, function.c_str());
        } else if (a == Arg::u && values[i].is_none()) {
          read[i].data = detail::zero_inputs<Model>();
        } else if (a == Arg::t) {
          read_scalar(values[i], what, read[i]);
        } else {
          read_vector(values[i], detail::size_of<Model>(a), what, read[i]);
        }
      }
      const py::ssize_t batch = batch_size(function, names, read);
      std::tuple<Result<Outs::rows, Outs::cols, Outs::is_vector>...> results{
          Result<Outs::rows, Outs::cols, Outs::is_vector>(batch)...};
      py::array_t<double> scalars;
      if constexpr (returns == Returns::scalar) scalars = py::array_t<double>(std::vector<py::ssize_t>{batch < 0 ? 1 : batch});
      const py::ssize_t n = batch < 0 ? 1 : batch;
      py::ssize_t irregular = -1;
      const char* reason = nullptr;
      {
        // a large batch runs without the GIL: other Python threads go on meanwhile
        std::optional<py::gil_scoped_release> release;
        if (n >= 64) release.emplace();
        for (py::ssize_t k = 0; k < n; ++k) {
          for (std::size_t i = 0; i < count; ++i)
            if (kinds[i] != Arg::p) detail::bind(point, kinds[i], read[i], k);
          auto outputs = std::apply([k](auto&... r) { return std::make_tuple(r.at(k)...); }, results);
          if constexpr (returns == Returns::nothing) {
            std::apply([&](auto&... o) { call(point, o...); }, outputs);
          } else if constexpr (returns == Returns::scalar) {
            scalars.mutable_data()[k] = call(point);
          } else {
            const char* why = std::apply([&](auto&... o) { return call(point, o...); }, outputs);
            if (why != nullptr && irregular < 0) irregular = k, reason = why;
          }
        }
      }
      if constexpr (returns == Returns::scalar) {
        if (batch < 0) return py::float_(scalars.data()[0]);
        return std::move(scalars);
      } else {
        if (irregular >= 0)
          throw py::value_error(function + "(): " +
                                (batch < 0 ? std::string() : "at state " + std::to_string(irregular) + ": ") + reason);
        return detail::result_object(std::move(results));
      }
    };
    define_with(m, name, doc, body, std::make_index_sequence<count>());
    // the functions of states and their arguments, by name: for introspection and tests
    if (!py::hasattr(m, "functions")) m.attr("functions") = py::dict();
    m.attr("functions")[name] = py::make_tuple(python_name(args)...);
  }

 private:
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
