// NumPy helpers shared by the bindings: fixed-size vectors in and out, and the shape checks
// of the vectorised calls (one state per row).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <string>

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

// The number of rows of `a`, which must be (width,) (returns 0: one row, no batch axis) or
// (n, width); ValueError naming `name` otherwise.
template <typename T>
py::ssize_t batch_rows(const CArray<T>& a, py::ssize_t width, const char* name) {
  if (a.ndim() == 1 && a.shape(0) == width) return 0;
  if (a.ndim() == 2 && a.shape(1) == width) return a.shape(0);
  throw py::value_error(std::string(name) + " must have shape (" + std::to_string(width) + ",) or (n, " +
                        std::to_string(width) + ")");
}

}  // namespace gyro::python
