#pragma once
/// \file
/// How a module's functions read NumPy arguments and write NumPy results.
///
/// An argument is one value (a scalar t, a vector q of n entries) or a batch of N of them (t of
/// shape (N,), q of shape (N, n)). A float64 array of any strides is read in place, through an
/// Eigen::Map with its strides (a column block of a state array, q = x[:, :nq], is not copied);
/// other real dtypes (integers, float32, lists of numbers) are converted once. Anything that is
/// not real numbers (complex, strings, objects, booleans) is a TypeError, a wrong shape a
/// ValueError, both naming the function, the argument and what was expected.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace eompy {

namespace py = pybind11;

/// "(3,)", "(5, 2)": a shape as NumPy prints it.
inline std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t k = 0; k < a.ndim(); ++k) s += (k ? ", " : "") + std::to_string(a.shape(k));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

/// An argument as messages name it: "mass_matrix(): q".
struct ArgumentName {
  const std::string& function;
  const char* argument;
  std::string text() const { return function + "(): " + argument; }
};

/// The array of real numbers \p value is, as float64; a TypeError for anything else.
inline py::array real_array(py::handle value, const ArgumentName& name) {
  const auto what = [&name] { return name.text(); };
  if (value.is_none()) throw py::type_error(what() + " is required, got None");
  py::array a = py::array::ensure(value);
  if (!a) {
    PyErr_Clear();
    throw py::type_error(what() + ": expected real numbers, got an object of type " +
                         std::string(py::str(py::type::handle_of(value).attr("__name__"))));
  }
  const char kind = a.dtype().kind();
  if (kind == 'f' && a.itemsize() == sizeof(double)) return a;
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw py::type_error(what() + ": expected real numbers (float64, or a dtype that converts to it), got " +
                         std::string(py::str(a.dtype())));
  return py::array_t<double, py::array::forcecast>::ensure(a);
}

/// One argument of a call, read: where its entries are, and whether it is one value or a
/// batch. Strides are in doubles.
struct Argument {
  const double* data = nullptr;
  py::ssize_t inner = 1;   ///< between the entries of one vector
  py::ssize_t outer = 0;   ///< between consecutive values of a batch
  py::ssize_t batch = -1;  ///< N, or -1 for one value
  double scalar = 0;       ///< a Python number given for a scalar (data points here)
  py::object keep;         ///< the array read, alive for the call

  const double* at(py::ssize_t k) const { return batch < 0 ? data : data + k * outer; }
};

namespace detail {

/// The stride of dimension \p d of a float64 array in doubles, or false if it is not a whole,
/// non-negative number of them (then the array is copied).
inline bool stride_in_doubles(const py::array& a, py::ssize_t d, py::ssize_t& stride) {
  const py::ssize_t bytes = a.strides(d);
  if (bytes < 0 || bytes % static_cast<py::ssize_t>(sizeof(double)) != 0) return false;
  stride = bytes / static_cast<py::ssize_t>(sizeof(double));
  return true;
}

}  // namespace detail

/// Reads a scalar argument (t): a number, or an array of shape (N,) for a batch.
inline void read_scalar(py::handle value, const ArgumentName& name, Argument& out) {
  const auto what = [&name] { return name.text(); };
  if (PyFloat_CheckExact(value.ptr())) {  // the common case, without an array
    out.scalar = PyFloat_AS_DOUBLE(value.ptr());
    out.data = &out.scalar;
    return;
  }
  py::array a = real_array(value, name);
  if (a.ndim() == 0) {
    out.scalar = *static_cast<const double*>(a.data());
    out.data = &out.scalar;
    return;
  }
  if (a.ndim() != 1)
    throw py::value_error(what() + ": expected a number, or an array of shape (N,) for N states, got shape " +
                          shape_text(a));
  if (!detail::stride_in_doubles(a, 0, out.outer)) {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    out.outer = 1;
  }
  out.data = static_cast<const double*>(a.data());
  out.batch = a.shape(0);
  out.keep = std::move(a);
}

/// Reads a vector argument of \p n entries: shape (n,), or (N, n) for a batch.
inline void read_vector(py::handle value, py::ssize_t n, const ArgumentName& name, Argument& out) {
  const auto what = [&name] { return name.text(); };
  py::array a = real_array(value, name);
  const bool one = a.ndim() == 1 && a.shape(0) == n;
  const bool batch = a.ndim() == 2 && a.shape(1) == n;
  if (!one && !batch)
    throw py::value_error(what() + ": expected shape (" + std::to_string(n) + ",), or (N, " + std::to_string(n) +
                          ") for N states, got " + shape_text(a));
  bool strided = detail::stride_in_doubles(a, a.ndim() - 1, out.inner);
  if (batch) strided = strided && detail::stride_in_doubles(a, 0, out.outer);
  if (!strided) {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    out.inner = 1;
    out.outer = n;
  }
  out.data = static_cast<const double*>(a.data());
  out.batch = batch ? a.shape(0) : -1;
  out.keep = std::move(a);
}

/// The batch size of a call: -1 if every argument is one value, else the N they share.
/// \p names[i] names \p args[i].
template <std::size_t count>
py::ssize_t batch_size(const std::string& function, const std::array<const char*, count>& names,
                       const std::array<Argument, count>& args) {
  py::ssize_t n = -1;
  const char* first = nullptr;
  for (std::size_t i = 0; i < count; ++i) {
    if (args[i].batch < 0) continue;
    if (n >= 0 && args[i].batch != n)
      throw py::value_error(function + "(): " + first + " holds " + std::to_string(n) + " states but " + names[i] +
                            " holds " + std::to_string(args[i].batch) + "; a batch's arguments share N");
    if (n < 0) n = args[i].batch, first = names[i];
  }
  return n;
}

/// A result of R x C entries (a vector when \p vector), for one value or a batch of N.
/// Eigen's storage order is row-major, as NumPy's C order is, except for a column vector
/// (Eigen has no row-major column).
template <int R, int C, bool vector>
struct Result {
  static constexpr int options = (C == 1 && R != 1) ? Eigen::ColMajor : Eigen::RowMajor;
  using Matrix = Eigen::Matrix<double, R, C, options>;
  using Map = Eigen::Map<Matrix>;

  py::array_t<double> array;

  explicit Result(py::ssize_t batch) {
    std::vector<py::ssize_t> shape;
    if (batch >= 0) shape.push_back(batch);
    shape.push_back(R);
    if (!vector) shape.push_back(C);
    array = py::array_t<double>(shape);
  }
  Map at(py::ssize_t k) { return Map(array.mutable_data() + k * R * C); }
};

}  // namespace eompy
