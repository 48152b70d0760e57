// gyro.h's exact step (gyro/rotor_transition.hpp), modes, and rotations. Flight part: no heap,
// no exceptions; the transition is the caller's plain struct, copied in and out.
#include <cmath>
#include <cstring>

#include "c_arrays.hpp"
#include "gyro/gyro.h"
#include "gyro/report_sample.hpp"  // initg_step
#include "gyro/rotor_transition.hpp"

namespace gyro::c_api {
namespace {

static_assert(sizeof(gyro_transition_d::coefficients) == 4 * sizeof(Matrix2<double>) + sizeof(double),
              "E0, E1, E1 J^-1, E2 J^-1 and dt");
static_assert(sizeof(gyro_transition_f::coefficients) == 4 * sizeof(Matrix2<float>) + sizeof(float),
              "E0, E1, E1 J^-1, E2 J^-1 and dt");

template <typename T>
RotorParameters<T> params_of(const typename Types<T>::Params& p) noexcept {
  return {p.pitch_inertia, p.yaw_inertia, p.friction, p.angular_momentum};
}

// The four 2x2 matrices column by column (Eigen's layout), then dt.
template <typename T>
void store_transition(const RotorTransition<T>& tr, typename Types<T>::Transition& out) noexcept {
  T* c = out.coefficients;
  std::memcpy(c, tr.rate_from_rate.data(), 4 * sizeof(T));
  std::memcpy(c + 4, tr.angle_from_rate.data(), 4 * sizeof(T));
  std::memcpy(c + 8, tr.rate_from_torque.data(), 4 * sizeof(T));
  std::memcpy(c + 12, tr.angle_from_torque.data(), 4 * sizeof(T));
  c[16] = tr.dt_s;
}
// Inlined into the step (out of line it costs a call and a default-initialised copy).
template <typename T>
[[gnu::always_inline]] inline RotorTransition<T> transition_of(const typename Types<T>::Transition& in) noexcept {
  RotorTransition<T> tr;
  const T* c = in.coefficients;
  std::memcpy(tr.rate_from_rate.data(), c, 4 * sizeof(T));
  std::memcpy(tr.angle_from_rate.data(), c + 4, 4 * sizeof(T));
  std::memcpy(tr.rate_from_torque.data(), c + 8, 4 * sizeof(T));
  std::memcpy(tr.angle_from_torque.data(), c + 12, 4 * sizeof(T));
  tr.dt_s = c[16];
  return tr;
}

template <typename T>
int make(const typename Types<T>::Params* p, T dt_s, typename Types<T>::Transition* out) noexcept {
  if (p == nullptr || out == nullptr) return GYRO_NULL_ARGUMENT;
  RotorTransition<T> tr;
  const Status st = make_transition(params_of<T>(*p), dt_s, tr);
  if (st == Status::kOk) store_transition(tr, *out);
  return static_cast<int>(st);
}

template <typename T>
RotorState<T> state_of(const T* s) noexcept {
  RotorState<T> r;
  r.angle_rad = Vector2<T>(s[0], s[1]);
  r.rate_rad_s = Vector2<T>(s[2], s[3]);
  return r;
}
template <typename T>
void store(const RotorState<T>& r, T* s) noexcept {
  s[0] = r.angle_rad(0);
  s[1] = r.angle_rad(1);
  s[2] = r.rate_rad_s(0);
  s[3] = r.rate_rad_s(1);
}

template <typename T>
int advance_one(const typename Types<T>::Transition* c_tr, const T* torque, T* state) noexcept {
  if (c_tr == nullptr || torque == nullptr || state == nullptr) return GYRO_NULL_ARGUMENT;
  const RotorTransition<T> tr = transition_of<T>(*c_tr);
  RotorState<T> s = state_of(state);
  const Status st = advance(tr, Vector2<T>(torque[0], torque[1]), s);
  if (st == Status::kOk) store(s, state);
  return static_cast<int>(st);
}

template <typename T>
int advance_many(const typename Types<T>::Transition* c_tr, T* states, std::size_t n, const T* torques,
                 std::size_t torque_stride, std::uint8_t* statuses) noexcept {
  if (c_tr == nullptr || (n > 0 && (states == nullptr || torques == nullptr))) return GYRO_NULL_ARGUMENT;
  if (torque_stride != 0 && torque_stride != 2) return GYRO_OUT_OF_RANGE;
  const RotorTransition<T> tr = transition_of<T>(*c_tr);
  int first = GYRO_OK;
  for (std::size_t i = 0; i < n; ++i) {
    T* s = states + 4 * i;
    const T* t = torques + torque_stride * i;
    RotorState<T> r = state_of(s);
    const Status st = advance(tr, Vector2<T>(t[0], t[1]), r);
    if (st == Status::kOk) {
      store(r, s);
    } else if (first == GYRO_OK) {
      first = static_cast<int>(st);
    }
    if (statuses != nullptr) statuses[i] = static_cast<std::uint8_t>(st);
  }
  return first;
}

// The orthogonal polar factor of a matrix near a rotation, by Bjorck and Bowie's iteration
// X <- X (3 I - X^T X) / 2: its error e goes to about 3 e^2 / 4 a pass, so four passes take
// GYRO_ROTATION_REPAIR_LIMIT's 1e-3 below double's rounding.
template <typename T>
int nearest(const T* r, T* out) noexcept {
  if (r == nullptr || out == nullptr) return GYRO_NULL_ARGUMENT;
  Matrix3<T> x = matrix_of(r);
  if (!x.allFinite()) return GYRO_NON_FINITE_INPUT;
  if (!(orthonormality_error(x) <= static_cast<T>(GYRO_ROTATION_REPAIR_LIMIT)) || !(x.determinant() > T(0))) {
    return GYRO_INVALID_ROTATION;
  }
  for (int pass = 0; pass < 4; ++pass) {
    Matrix3<T> g = -(x.transpose() * x);
    g.diagonal().array() += T(3);
    const Matrix3<T> next = T(0.5) * (x * g);
    x = next;
  }
  if (!is_rotation(x)) return GYRO_INVALID_ROTATION;
  put(x, out);
  return GYRO_OK;
}

}  // namespace
}  // namespace gyro::c_api

namespace c = gyro::c_api;

extern "C" {

double gyro_angular_momentum_d(double spin_hz, double spin_inertia) { return gyro::angular_momentum(spin_hz, spin_inertia); }
float gyro_angular_momentum_f(float spin_hz, float spin_inertia) { return gyro::angular_momentum(spin_hz, spin_inertia); }

int gyro_make_transition_d(const gyro_rotor_parameters_d* p, double dt_s, gyro_transition_d* out) {
  return c::make<double>(p, dt_s, out);
}
int gyro_make_transition_f(const gyro_rotor_parameters_f* p, float dt_s, gyro_transition_f* out) {
  return c::make<float>(p, dt_s, out);
}
int gyro_advance_d(const gyro_transition_d* tr, const double torque[2], double state[4]) {
  return c::advance_one<double>(tr, torque, state);
}
int gyro_advance_f(const gyro_transition_f* tr, const float torque[2], float state[4]) {
  return c::advance_one<float>(tr, torque, state);
}
int gyro_advance_batch_d(const gyro_transition_d* tr, double* states, size_t n, const double* torques,
                         size_t torque_stride, uint8_t* statuses) {
  return c::advance_many<double>(tr, states, n, torques, torque_stride, statuses);
}
int gyro_advance_batch_f(const gyro_transition_f* tr, float* states, size_t n, const float* torques,
                         size_t torque_stride, uint8_t* statuses) {
  return c::advance_many<float>(tr, states, n, torques, torque_stride, statuses);
}

int gyro_compute_modes_d(const gyro_rotor_parameters_d* p, gyro_rotor_modes_d* out) {
  if (p == nullptr || out == nullptr) return GYRO_NULL_ARGUMENT;
  gyro::RotorModes<double> m;
  const gyro::Status st = gyro::compute_modes(c::params_of<double>(*p), m);
  if (st != gyro::Status::kOk) return static_cast<int>(st);
  *out = gyro_rotor_modes_d{m.alpha_1_s,           m.beta_squared_1_s2,   m.beta_rad_s,  m.natural_rate_rad_s,
                            m.slow_decay_rate_1_s, m.fast_decay_rate_1_s, m.nutation_hz, static_cast<int>(m.regime)};
  return GYRO_OK;
}

int gyro_initg_step_d(const gyro_rotor_parameters_d* p, double* step_s) {
  if (p == nullptr || step_s == nullptr) return GYRO_NULL_ARGUMENT;
  const gyro::Status st = gyro::validate(c::params_of<double>(*p));
  if (st != gyro::Status::kOk) return static_cast<int>(st);
  const double step = gyro::initg_step(c::params_of<double>(*p));
  if (!(step > 0.0)) return GYRO_OUT_OF_RANGE;
  *step_s = step;
  return GYRO_OK;
}

int gyro_frame_rotation_d(int axis, double angle_rad, double R[9]) {
  if (R == nullptr) return GYRO_NULL_ARGUMENT;
  if (!std::isfinite(angle_rad)) return GYRO_NON_FINITE_INPUT;
  if (axis != 1 && axis != 2) return GYRO_OUT_OF_RANGE;
  c::put(axis == 1 ? gyro::frame_rotation_y(angle_rad) : gyro::frame_rotation_z(angle_rad), R);
  return GYRO_OK;
}

int gyro_nearest_rotation_d(const double R[9], double out[9]) { return c::nearest<double>(R, out); }
int gyro_nearest_rotation_f(const float R[9], float out[9]) { return c::nearest<float>(R, out); }

}  // extern "C"
