// gyro.h's functions for one scalar type, for the C API's typed tests: C<double> calls the _d
// functions, C<float> the _f ones.
#pragma once

#include <cstddef>
#include <cstdint>

#include "gyro/gyro.h"

namespace gyro::c_api_test {

template <typename T>
struct C;
template <>
struct C<double> {
  using Params = gyro_rotor_parameters_d;
  using Transition = gyro_transition_d;
  static int make(const Params* p, double dt, Transition* t) { return gyro_make_transition_d(p, dt, t); }
  static int advance(const Transition* t, const double* q, double* s) { return gyro_advance_d(t, q, s); }
  static int batch(const Transition* t, double* s, std::size_t n, const double* q, std::size_t stride, std::uint8_t* st) {
    return gyro_advance_batch_d(t, s, n, q, stride, st);
  }

  using Model = gyro_model_d;
  using Input = gyro_step_input_d;
  static Model* init(void* s, std::size_t n) { return gyro_model_d_init(s, n); }
  static std::size_t size() { return gyro_model_d_storage_size(); }
  static int configure(Model* m, const gyro_model_config* c) { return gyro_model_d_configure(m, c, nullptr); }
  static int uncage(Model* m, const double* r, const double* w) { return gyro_model_d_uncage(m, r, w, nullptr); }
  static int slew(Model* m, const Input* in, const double* w) { return gyro_model_d_step_slew(m, in, w); }
  static int torque(Model* m, const Input* in, const double* t) { return gyro_model_d_step_torque(m, in, t); }
  static void gimbal(const Model* m, double* g) { gyro_model_d_gimbal(m, g); }
  static void rate(const Model* m, double* g) { gyro_model_d_rate(m, g); }
  static void isaf(const Model* m, double* g) { gyro_model_d_isaf_angle(m, g); }
  static void nutation(const Model* m, double* g) { gyro_model_d_nutation_amplitude(m, g); }
  static void applied(const Model* m, double* g) { gyro_model_d_applied_torque(m, g); }
  static void roteg(const Model* m, double* r) { gyro_model_d_R_earth_to_gyro(m, r); }
  static void attitude(const Model* m, double* q) { gyro_model_d_attitude(m, q); }
  static double cone(const Model* m) { return gyro_model_d_cone(m); }
  static std::uint32_t flags(const Model* m) { return gyro_model_d_flags(m); }
};
template <>
struct C<float> {
  using Params = gyro_rotor_parameters_f;
  using Transition = gyro_transition_f;
  static int make(const Params* p, float dt, Transition* t) { return gyro_make_transition_f(p, dt, t); }
  static int advance(const Transition* t, const float* q, float* s) { return gyro_advance_f(t, q, s); }
  static int batch(const Transition* t, float* s, std::size_t n, const float* q, std::size_t stride, std::uint8_t* st) {
    return gyro_advance_batch_f(t, s, n, q, stride, st);
  }

  using Model = gyro_model_f;
  using Input = gyro_step_input_f;
  static Model* init(void* s, std::size_t n) { return gyro_model_f_init(s, n); }
  static std::size_t size() { return gyro_model_f_storage_size(); }
  static int configure(Model* m, const gyro_model_config* c) { return gyro_model_f_configure(m, c, nullptr); }
  static int uncage(Model* m, const float* r, const float* w) { return gyro_model_f_uncage(m, r, w, nullptr); }
  static int slew(Model* m, const Input* in, const float* w) { return gyro_model_f_step_slew(m, in, w); }
  static int torque(Model* m, const Input* in, const float* t) { return gyro_model_f_step_torque(m, in, t); }
  static void gimbal(const Model* m, float* g) { gyro_model_f_gimbal(m, g); }
  static void rate(const Model* m, float* g) { gyro_model_f_rate(m, g); }
  static void isaf(const Model* m, float* g) { gyro_model_f_isaf_angle(m, g); }
  static void nutation(const Model* m, float* g) { gyro_model_f_nutation_amplitude(m, g); }
  static void applied(const Model* m, float* g) { gyro_model_f_applied_torque(m, g); }
  static void roteg(const Model* m, float* r) { gyro_model_f_R_earth_to_gyro(m, r); }
  static void attitude(const Model* m, float* q) { gyro_model_f_attitude(m, q); }
  static float cone(const Model* m) { return gyro_model_f_cone(m); }
  static std::uint32_t flags(const Model* m) { return gyro_model_f_flags(m); }
};

}  // namespace gyro::c_api_test
