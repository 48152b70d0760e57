// gyro.h's types for a scalar type, and its arrays to and from Eigen: matrices row by row
// (r[3*i + j] = R(i, j)), vectors in order.
#pragma once

#include "gyro/attitude.hpp"
#include "gyro/gyro.h"

namespace gyro::c_api {

// gyro.h's structs and handles in double and float.
template <typename T>
struct Types;
template <>
struct Types<double> {
  using Params = gyro_rotor_parameters_d;
  using Transition = gyro_transition_d;
  using Handle = gyro_model_d;
  using Input = gyro_step_input_d;
};
template <>
struct Types<float> {
  using Params = gyro_rotor_parameters_f;
  using Transition = gyro_transition_f;
  using Handle = gyro_model_f;
  using Input = gyro_step_input_f;
};

template <typename T>
[[nodiscard]] Matrix3<T> matrix_of(const T* r) noexcept {
  Matrix3<T> m;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m(i, j) = r[3 * i + j];
  }
  return m;
}

template <typename T>
void put(const Matrix3<T>& m, T* r) noexcept {
  if (r == nullptr) return;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r[3 * i + j] = m(i, j);
  }
}

template <typename T, int N>
void put(const Eigen::Matrix<T, N, 1>& v, T* out) noexcept {
  if (out == nullptr) return;
  for (int i = 0; i < N; ++i) out[i] = v(i);
}

template <typename T, int N>
[[nodiscard]] Eigen::Matrix<T, N, 1> vector_of(const T* v) noexcept {
  Eigen::Matrix<T, N, 1> r;
  for (int i = 0; i < N; ++i) r(i) = v[i];
  return r;
}

}  // namespace gyro::c_api
