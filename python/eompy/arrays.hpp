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
inline std::string shape_text(const py::detail::PyArray_Proxy* a) {
  std::string s = "(";
  for (int k = 0; k < a->nd; ++k) s += (k ? ", " : "") + std::to_string(a->dimensions[k]);
  return s + (a->nd == 1 ? ",)" : ")");
}

namespace detail {

/// \p value as a NumPy array of float64 in the machine's byte order, which the functions read
/// as it is; nullptr for anything else (another dtype, a swapped byte order, not an array).
/// Through NumPy's structures directly: this is every call's path, and a dtype object per
/// argument would cost more than the call of a small model's function.
inline const py::detail::PyArray_Proxy* native_doubles(py::handle value) {
  const py::detail::npy_api& api = py::detail::npy_api::get();
  if (!api.PyArray_Check_(value.ptr())) return nullptr;
  const py::detail::PyArray_Proxy* a = py::detail::array_proxy(value.ptr());
  const py::detail::PyArrayDescr_Proxy* d = py::detail::array_descriptor_proxy(a->descr);
#if PY_LITTLE_ENDIAN
  constexpr char native = '<';
#else
  constexpr char native = '>';
#endif
  if (d->type_num != py::detail::npy_api::NPY_DOUBLE_ || (d->byteorder != '=' && d->byteorder != native)) return nullptr;
  return a;
}

}  // namespace detail

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
  if (detail::native_doubles(a)) return a;
  const char kind = a.dtype().kind();
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
inline bool stride_in_doubles(const py::detail::PyArray_Proxy* a, int d, py::ssize_t& stride) {
  const py::ssize_t bytes = a->strides[d];
  if (bytes < 0 || bytes % static_cast<py::ssize_t>(sizeof(double)) != 0) return false;
  stride = bytes / static_cast<py::ssize_t>(sizeof(double));
  return true;
}

/// The entries of a float64 array as \p read takes them (it throws for a wrong shape), in place
/// where its strides allow, else from a C-ordered copy held by \p out.keep.
template <class Read>
void read_doubles(py::handle value, const ArgumentName& name, Argument& out, Read read) {
  const py::detail::PyArray_Proxy* a = native_doubles(value);
  py::object converted;  // not a py::array: its default constructor makes an empty array
  if (a == nullptr) {
    converted = real_array(value, name);
    a = py::detail::array_proxy(converted.ptr());
  }
  read(a, out);
  if (out.data == nullptr) {  // strides that are not whole doubles
    converted = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(
        py::reinterpret_borrow<py::object>(reinterpret_cast<PyObject*>(const_cast<py::detail::PyArray_Proxy*>(a))));
    a = py::detail::array_proxy(converted.ptr());
    read(a, out);
  }
  if (converted) out.keep = std::move(converted);
}

}  // namespace detail

/// Reads a scalar argument (t): a number, or an array of shape (N,) for a batch.
inline void read_scalar(py::handle value, const ArgumentName& name, Argument& out) {
  if (PyFloat_CheckExact(value.ptr())) {  // the common case, without an array
    out.scalar = PyFloat_AS_DOUBLE(value.ptr());
    out.data = &out.scalar;
    return;
  }
  detail::read_doubles(value, name, out, [&name](const py::detail::PyArray_Proxy* a, Argument& o) {
    if (a->nd == 0) {
      o.scalar = *reinterpret_cast<const double*>(a->data);
      o.data = &o.scalar;
      return;
    }
    if (a->nd != 1)
      throw py::value_error(name.text() + ": expected a number, or an array of shape (N,) for N states, got shape " +
                            shape_text(a));
    o.batch = a->dimensions[0];
    o.data = detail::stride_in_doubles(a, 0, o.outer) ? reinterpret_cast<const double*>(a->data) : nullptr;
  });
}

/// Reads a vector argument of \p n entries: shape (n,), or (N, n) for a batch.
inline void read_vector(py::handle value, py::ssize_t n, const ArgumentName& name, Argument& out) {
  detail::read_doubles(value, name, out, [n, &name](const py::detail::PyArray_Proxy* a, Argument& o) {
    const bool one = a->nd == 1 && a->dimensions[0] == n;
    const bool batch = a->nd == 2 && a->dimensions[1] == n;
    if (!one && !batch)
      throw py::value_error(name.text() + ": expected shape (" + std::to_string(n) + ",), or (N, " +
                            std::to_string(n) + ") for N states, got " + shape_text(a));
    bool strided = detail::stride_in_doubles(a, a->nd - 1, o.inner);
    if (batch) strided = strided && detail::stride_in_doubles(a, 0, o.outer);
    o.batch = batch ? a->dimensions[0] : -1;
    o.data = strided ? reinterpret_cast<const double*>(a->data) : nullptr;
  });
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

/// A new C-ordered float64 array of the given dimensions, made by NumPy's own constructor:
/// every call makes its results, and this is the cheapest way there is.
inline py::array new_doubles(int nd, const Py_intptr_t* dimensions) {
  const py::detail::npy_api& api = py::detail::npy_api::get();
  PyObject* descr = api.PyArray_DescrFromType_(py::detail::npy_api::NPY_DOUBLE_);
  PyObject* a = api.PyArray_NewFromDescr_(api.PyArray_Type_, descr, nd, dimensions, nullptr, nullptr, 0, nullptr);
  if (a == nullptr) throw py::error_already_set();
  return py::reinterpret_steal<py::array>(a);
}

/// A result of R x C entries (a vector when \p vector), for one value or a batch of N.
/// Eigen's storage order is row-major, as NumPy's C order is, except for a column vector
/// (Eigen has no row-major column).
template <int R, int C, bool vector>
struct Result {
  static constexpr int options = (C == 1 && R != 1) ? Eigen::ColMajor : Eigen::RowMajor;
  using Matrix = Eigen::Matrix<double, R, C, options>;
  using Map = Eigen::Map<Matrix>;

  py::array array;
  double* data;

  explicit Result(py::ssize_t batch)
      : array(make(batch)), data(reinterpret_cast<double*>(py::detail::array_proxy(array.ptr())->data)) {}
  Map at(py::ssize_t k) { return Map(data + k * R * C); }

 private:
  // made in the initializer list: a default-constructed py::array would be an empty NumPy
  // array, made and freed at every call for nothing
  static py::array make(py::ssize_t batch) {
    Py_intptr_t dimensions[3];
    int nd = 0;
    if (batch >= 0) dimensions[nd++] = batch;
    dimensions[nd++] = R;
    if (!vector) dimensions[nd++] = C;
    return new_doubles(nd, dimensions);
  }
};

}  // namespace eompy
