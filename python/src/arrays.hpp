// NumPy helpers shared by the bindings: every numeric argument (an array, a fixed-size vector
// or matrix, a scalar) converted here, and the shape checks of the vectorised calls (one state
// per row).
//
// Kinds: only real numbers are taken, a float or an integer (Python's int and float, NumPy's
// integer and floating dtypes). A bool, a complex number, a string (or bytes), an object array
// and anything else NumPy would coerce is refused with a TypeError naming the argument, what
// it got and what it needs: no imaginary part is dropped, no string parsed as a number.
// Shapes are checked with a ValueError naming the argument, the shape given and the shape
// needed; a value too large for float32 in a float32 call is a ValueError too (it would
// silently become infinite). Non-finite values are the C++ calls' to refuse (a Status).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Python.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>

namespace gyro::python {

namespace py = pybind11;

template <typename T>
using CArray = py::array_t<T, py::array::c_style | py::array::forcecast>;

// A fresh 1-D array holding `v`.
template <typename T, int N>
py::array_t<T> to_array(const Eigen::Matrix<T, N, 1>& v) {
  py::array_t<T> a(N);
  for (int i = 0; i < N; ++i) a.mutable_at(i) = v(i);
  return a;
}
// A fresh 2-D array holding `m` (row-major as NumPy shows it).
template <typename T, int R, int C>
py::array_t<T> to_array(const Eigen::Matrix<T, R, C>& m) {
  py::array_t<T> a({R, C});
  for (int r = 0; r < R; ++r) {
    for (int c = 0; c < C; ++c) a.mutable_at(r, c) = m(r, c);
  }
  return a;
}

namespace array_detail {

inline std::string type_name(py::handle v) {
  return py::str(py::type::handle_of(v).attr("__name__")).cast<std::string>();
}

inline std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i > 0 ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// "an array of complex128 (complex numbers)", ... for the message of a refused kind.
inline std::string kind_text(const py::array& a) {
  const char* what = "";
  switch (a.dtype().kind()) {
    case 'c': what = " (complex numbers)"; break;
    case 'U': what = " (strings)"; break;
    case 'S': what = " (bytes)"; break;
    case 'b': what = " (booleans)"; break;
    case 'O': what = " (Python objects)"; break;
    case 'M': what = " (dates)"; break;
    case 'm': what = " (time differences)"; break;
    default: break;
  }
  return "an array of " + py::str(a.dtype()).cast<std::string>() + what;
}

[[noreturn]] inline void refuse_kind(const char* name, const std::string& got) {
  throw py::type_error(std::string(name) + ": expected real numbers (float or integer), got " + got);
}

// Whether `v`, a list or tuple, holds a bool, at any depth of lists and tuples.
inline bool holds_bool(py::handle v) {
  if (!PyList_Check(v.ptr()) && !PyTuple_Check(v.ptr())) return false;
  for (const py::handle e : py::reinterpret_borrow<py::sequence>(v)) {
    if (PyBool_Check(e.ptr()) || holds_bool(e)) return true;
  }
  return false;
}

inline bool real_kind(char k) { return k == 'f' || k == 'i' || k == 'u'; }

// The largest finite value of T, as a double.
template <typename T>
constexpr double max_of() {
  return static_cast<double>(std::numeric_limits<T>::max());
}

template <typename T>
void check_representable(double d, const char* name) {
  if constexpr (!std::is_same_v<T, double>) {
    if (std::isfinite(d) && std::fabs(d) > max_of<T>()) {
      throw py::value_error(std::string(name) + ": " + py::repr(py::float_(d)).cast<std::string>() +
                            " is beyond float32's range (largest " +
                            py::repr(py::float_(max_of<T>())).cast<std::string>() + ")");
    }
  }
}

}  // namespace array_detail

// `v` as a NumPy array of real numbers (any shape), without converting its kind: a NumPy
// array as it is, anything else through numpy.asarray. TypeError naming `name` otherwise.
inline py::array real_array(py::handle v, const char* name) {
  using namespace array_detail;
  if (py::isinstance<py::str>(v) || py::isinstance<py::bytes>(v)) {
    refuse_kind(name, type_name(v) + " " + py::repr(v).cast<std::string>());
  }
  // NumPy reads [True, 2.0] as numbers: a bool among a (nested) list's or tuple's items is
  // refused here.
  if (holds_bool(v)) refuse_kind(name, "a " + type_name(v) + " holding a bool");
  py::array a;
  if (py::isinstance<py::array>(v)) {
    a = py::reinterpret_borrow<py::array>(v);
  } else {
    try {
      a = py::module_::import("numpy").attr("asarray")(v);
    } catch (py::error_already_set& e) {
      refuse_kind(name, type_name(v) + " (" + std::string(e.what()) + ")");
    }
  }
  if (!real_kind(a.dtype().kind())) {
    refuse_kind(name, py::isinstance<py::array>(v) ? kind_text(a) : "a " + type_name(v) + " read as " + kind_text(a));
  }
  return a;
}

// `v` as a C-contiguous array of T (real numbers only, as real_array), values checked to be
// representable in T.
template <typename T>
CArray<T> real_array_of(py::handle v, const char* name) {
  const py::array a = real_array(v, name);
  if constexpr (!std::is_same_v<T, double>) {
    if (a.dtype().kind() != 'f' || a.dtype().itemsize() > static_cast<py::ssize_t>(sizeof(T))) {
      const CArray<double> wide = CArray<double>::ensure(a);
      if (!wide) throw py::error_already_set();
      const double* d = wide.data();
      for (py::ssize_t i = 0; i < wide.size(); ++i) array_detail::check_representable<T>(d[i], name);
    }
  }
  CArray<T> out = CArray<T>::ensure(a);
  if (!out) throw py::error_already_set();
  return out;
}

// One real number: a Python int or float, a NumPy integer or floating scalar or a 0-d array
// of one. TypeError naming `name` for anything else (bool, complex, str, a sequence).
template <typename T = double>
T real_scalar(py::handle v, const char* name) {
  using namespace array_detail;
  double d = 0;
  if (PyFloat_Check(v.ptr())) {
    d = PyFloat_AS_DOUBLE(v.ptr());
  } else if (PyLong_Check(v.ptr()) && !PyBool_Check(v.ptr())) {
    d = PyLong_AsDouble(v.ptr());
    if (d == -1.0 && PyErr_Occurred() != nullptr) {
      PyErr_Clear();
      throw py::value_error(std::string(name) + ": " + py::repr(v).cast<std::string>() + " is too large for a float");
    }
  } else if (py::isinstance<py::array>(v) || py::isinstance(v, py::module_::import("numpy").attr("generic"))) {
    const py::array a = py::module_::import("numpy").attr("asarray")(v);
    if (!real_kind(a.dtype().kind())) refuse_kind(name, type_name(v) + " " + py::repr(v).cast<std::string>());
    if (a.ndim() != 0) {
      throw py::value_error(std::string(name) + ": expected a number, got an array of shape " + shape_text(a));
    }
    d = py::float_(a.attr("item")()).cast<double>();
  } else {
    refuse_kind(name, type_name(v) + " " + py::repr(v).cast<std::string>());
  }
  check_representable<T>(d, name);
  return static_cast<T>(d);
}

// A whole number from `lo` to `hi`: a Python int or a NumPy integer (operator.index), not a bool
// or a float. TypeError for another kind, ValueError out of range, both naming `name`, the
// value and the range.
inline std::uint64_t whole_number(py::handle v, const char* name, std::uint64_t lo, std::uint64_t hi) {
  using namespace array_detail;
  const std::string range = "a whole number from " + std::to_string(lo) + " to " + std::to_string(hi);
  if (PyBool_Check(v.ptr()) || PyIndex_Check(v.ptr()) == 0 ||
      (py::isinstance<py::array>(v) && py::reinterpret_borrow<py::array>(v).dtype().kind() == 'b')) {
    throw py::type_error(std::string(name) + ": expected " + range + ", got " + type_name(v) + " " +
                         py::repr(v).cast<std::string>());
  }
  const py::int_ n = py::reinterpret_steal<py::int_>(PyNumber_Index(v.ptr()));
  if (!n) throw py::error_already_set();
  const bool below = py::int_(lo) > n;
  const bool above = n > py::int_(hi);
  if (below || above) {
    throw py::value_error(std::string(name) + ": expected " + range + ", got " + py::repr(n).cast<std::string>());
  }
  return n.cast<std::uint64_t>();
}

// A fixed-size vector (shape (N,)) or matrix (shape (R, C)) of real numbers.
template <typename M>
M real_matrix(py::handle v, const char* name) {
  using T = typename M::Scalar;
  constexpr int R = M::RowsAtCompileTime;
  constexpr int C = M::ColsAtCompileTime;
  M m;
  // Fast path for a list or tuple of Python floats and ints (the common call).
  if constexpr (C == 1) {
    if ((PyList_Check(v.ptr()) || PyTuple_Check(v.ptr())) && PySequence_Fast_GET_SIZE(v.ptr()) == R) {
      bool plain = true;
      for (int i = 0; i < R && plain; ++i) {
        PyObject* e = PySequence_Fast_GET_ITEM(v.ptr(), i);
        plain = PyFloat_Check(e) || (PyLong_Check(e) && !PyBool_Check(e));
      }
      if (plain) {
        for (int i = 0; i < R; ++i) m(i) = real_scalar<T>(PySequence_Fast_GET_ITEM(v.ptr(), i), name);
        return m;
      }
    }
  }
  const CArray<T> a = real_array_of<T>(v, name);
  const bool ok = C == 1 ? (a.ndim() == 1 && a.shape(0) == R) : (a.ndim() == 2 && a.shape(0) == R && a.shape(1) == C);
  if (!ok) {
    const std::string need =
        C == 1 ? "(" + std::to_string(R) + ",)" : "(" + std::to_string(R) + ", " + std::to_string(C) + ")";
    throw py::value_error(std::string(name) + ": expected shape " + need + ", got shape " +
                          array_detail::shape_text(a));
  }
  const T* d = a.data();
  for (int r = 0; r < R; ++r) {
    for (int c = 0; c < C; ++c) m(r, c) = d[r * C + c];
  }
  return m;
}

// real_matrix, or nullopt for None.
template <typename M>
std::optional<M> optional_matrix(py::handle v, const char* name) {
  if (v.is_none()) return std::nullopt;
  return real_matrix<M>(v, name);
}

// real_matrix, or zeros for None.
template <typename M>
M matrix_or_zero(py::handle v, const char* name) {
  return v.is_none() ? M(M::Zero()) : real_matrix<M>(v, name);
}

// The number of rows of `a`, which must be (width,) (returns nullopt: one row, no batch axis)
// or (n, width), n >= 0; ValueError naming `name`, the shape given and the shapes taken otherwise.
template <typename T>
std::optional<py::ssize_t> batch_rows(const CArray<T>& a, py::ssize_t width, const char* name) {
  if (a.ndim() == 1 && a.shape(0) == width) return std::nullopt;
  if (a.ndim() == 2 && a.shape(1) == width) return a.shape(0);
  throw py::value_error(std::string(name) + ": expected shape (" + std::to_string(width) + ",) or (n, " +
                        std::to_string(width) + "), got shape " + array_detail::shape_text(a));
}

}  // namespace gyro::python
