// gyro.h's GyroModel (gyro/gyro_model.hpp) in double and float, in the caller's storage, and the
// report's sample. Flight part: no heap, no exceptions.
#include <cstdint>
#include <new>

#include "c_arrays.hpp"
#include "c_fields.hpp"
#include "c_handles.hpp"
#include "gyro/report_sample.hpp"

namespace gyro::c_api {
namespace {

// Bytes a handle needs in storage of any alignment.
template <typename T>
constexpr std::size_t kNeeded = sizeof(typename Types<T>::Handle) + alignof(typename Types<T>::Handle) - 1;
static_assert(kNeeded<double> <= GYRO_MODEL_D_STORAGE_BYTES, "GYRO_MODEL_D_STORAGE_BYTES too small for this target");
static_assert(kNeeded<float> <= GYRO_MODEL_F_STORAGE_BYTES, "GYRO_MODEL_F_STORAGE_BYTES too small for this target");

template <typename T>
typename Types<T>::Handle* init(void* storage, std::size_t bytes) noexcept {
  using H = typename Types<T>::Handle;
  if (storage == nullptr || bytes < kNeeded<T>) return nullptr;
  const std::uintptr_t a = reinterpret_cast<std::uintptr_t>(storage);
  const std::uintptr_t aligned = (a + alignof(H) - 1) & ~static_cast<std::uintptr_t>(alignof(H) - 1);
  return ::new (reinterpret_cast<void*>(aligned)) H{};
}

template <typename T>
int configure(typename Types<T>::Handle* h, const gyro_model_config* config, gyro_refusal* refusal) noexcept {
  if (h == nullptr || config == nullptr) return GYRO_NULL_ARGUMENT;
  GyroModelConfig<double> d{};
  ConfigCheck c = read_config(kModelConfig, config, d);
  if (c.ok()) c = check(d);  // in double first: a value beyond float's range is named as given
  if (c.ok()) {
    if constexpr (std::is_same_v<T, double>) {
      c = h->model.configure(d);
    } else {
      GyroModelConfig<float> f{};
      cast_fields(d, f);
      c = h->model.configure(f);
    }
  }
  to_c(c, refusal);
  return static_cast<int>(c.status);
}

template <typename T>
int uncage(typename Types<T>::Handle* h, const T* r, const T* rate, const T* offset) noexcept {
  if (h == nullptr || r == nullptr || rate == nullptr) return GYRO_NULL_ARGUMENT;
  const Vector2<T> off = offset != nullptr ? Vector2<T>(offset[0], offset[1]) : Vector2<T>(Vector2<T>::Zero());
  return static_cast<int>(h->model.uncage(matrix_of(r), Vector2<T>(rate[0], rate[1]), off));
}

template <typename T>
GyroStepInput<T> input_of(const typename Types<T>::Input& c) noexcept {
  GyroStepInput<T> in;
  in.dt_s = c.dt_s;
  in.R_earth_to_body = matrix_of(c.R_earth_to_body);
  in.body_accel = Vector2<T>(c.body_accel[0], c.body_accel[1]);
  in.spin_hz = c.spin_hz;
  in.body_rate_rad_s = Vector3<T>(c.body_rate_rad_s[0], c.body_rate_rad_s[1], c.body_rate_rad_s[2]);
  return in;
}

template <typename T>
int step_slew(typename Types<T>::Handle* h, const typename Types<T>::Input* in, const T* slew) noexcept {
  if (h == nullptr || in == nullptr || slew == nullptr) return GYRO_NULL_ARGUMENT;
  return static_cast<int>(h->model.step_slew(input_of<T>(*in), Vector2<T>(slew[0], slew[1])));
}
template <typename T>
int step_torque(typename Types<T>::Handle* h, const typename Types<T>::Input* in, const T* torque) noexcept {
  if (h == nullptr || in == nullptr || torque == nullptr) return GYRO_NULL_ARGUMENT;
  return static_cast<int>(h->model.step_torque(input_of<T>(*in), Vector2<T>(torque[0], torque[1])));
}

}  // namespace
}  // namespace gyro::c_api

namespace c = gyro::c_api;
using gyro::Vector2;

extern "C" {

size_t gyro_model_d_storage_size(void) { return c::kNeeded<double>; }
size_t gyro_model_f_storage_size(void) { return c::kNeeded<float>; }
gyro_model_d* gyro_model_d_init(void* storage, size_t bytes) { return c::init<double>(storage, bytes); }
gyro_model_f* gyro_model_f_init(void* storage, size_t bytes) { return c::init<float>(storage, bytes); }

int gyro_model_d_configure(gyro_model_d* m, const gyro_model_config* config, gyro_refusal* refusal) {
  return c::configure<double>(m, config, refusal);
}
int gyro_model_f_configure(gyro_model_f* m, const gyro_model_config* config, gyro_refusal* refusal) {
  return c::configure<float>(m, config, refusal);
}
int gyro_model_d_uncage(gyro_model_d* m, const double R_earth_to_body[9], const double body_rate_rad_s[2],
                        const double offset_rad[2]) {
  return c::uncage<double>(m, R_earth_to_body, body_rate_rad_s, offset_rad);
}
int gyro_model_f_uncage(gyro_model_f* m, const float R_earth_to_body[9], const float body_rate_rad_s[2],
                        const float offset_rad[2]) {
  return c::uncage<float>(m, R_earth_to_body, body_rate_rad_s, offset_rad);
}
int gyro_model_d_step_slew(gyro_model_d* m, const gyro_step_input_d* in, const double slew_rate_rad_s[2]) {
  return c::step_slew<double>(m, in, slew_rate_rad_s);
}
int gyro_model_f_step_slew(gyro_model_f* m, const gyro_step_input_f* in, const float slew_rate_rad_s[2]) {
  return c::step_slew<float>(m, in, slew_rate_rad_s);
}
int gyro_model_d_step_torque(gyro_model_d* m, const gyro_step_input_d* in, const double torque[2]) {
  return c::step_torque<double>(m, in, torque);
}
int gyro_model_f_step_torque(gyro_model_f* m, const gyro_step_input_f* in, const float torque[2]) {
  return c::step_torque<float>(m, in, torque);
}

void gyro_model_d_gimbal(const gyro_model_d* m, double g[2]) {
  if (m != nullptr) c::put(Vector2<double>(m->model.gimbal_pitch_rad(), m->model.gimbal_yaw_rad()), g);
}
void gyro_model_f_gimbal(const gyro_model_f* m, float g[2]) {
  if (m != nullptr) c::put(Vector2<float>(m->model.gimbal_pitch_rad(), m->model.gimbal_yaw_rad()), g);
}
void gyro_model_d_rate(const gyro_model_d* m, double r[2]) { if (m != nullptr) c::put(m->model.rate_rad_s(), r); }
void gyro_model_f_rate(const gyro_model_f* m, float r[2]) { if (m != nullptr) c::put(m->model.rate_rad_s(), r); }
void gyro_model_d_isaf_angle(const gyro_model_d* m, double a[2]) { if (m != nullptr) c::put(m->model.isaf_angle_rad(), a); }
void gyro_model_f_isaf_angle(const gyro_model_f* m, float a[2]) { if (m != nullptr) c::put(m->model.isaf_angle_rad(), a); }
void gyro_model_d_nutation_amplitude(const gyro_model_d* m, double a[2]) {
  if (m != nullptr) c::put(m->model.nutation_amplitude_rad(), a);
}
void gyro_model_f_nutation_amplitude(const gyro_model_f* m, float a[2]) {
  if (m != nullptr) c::put(m->model.nutation_amplitude_rad(), a);
}
void gyro_model_d_applied_torque(const gyro_model_d* m, double t[2]) { if (m != nullptr) c::put(m->model.applied_torque(), t); }
void gyro_model_f_applied_torque(const gyro_model_f* m, float t[2]) { if (m != nullptr) c::put(m->model.applied_torque(), t); }

void gyro_model_d_R_earth_to_gyro(const gyro_model_d* m, double R[9]) {
  if (m == nullptr) return;
  c::put(gyro::Matrix3<double>(m->model.R_earth_to_gyro()), R);
}
void gyro_model_f_R_earth_to_gyro(const gyro_model_f* m, float R[9]) {
  if (m == nullptr) return;
  c::put(gyro::Matrix3<float>(m->model.R_earth_to_gyro()), R);
}
void gyro_model_d_attitude(const gyro_model_d* m, double q[4]) {
  if (m == nullptr || q == nullptr) return;
  const gyro::Quaternion<double>& a = m->model.attitude_gyro_to_earth();
  q[0] = a.w(), q[1] = a.x(), q[2] = a.y(), q[3] = a.z();
}
void gyro_model_f_attitude(const gyro_model_f* m, float q[4]) {
  if (m == nullptr || q == nullptr) return;
  const gyro::Quaternion<float>& a = m->model.attitude_gyro_to_earth();
  q[0] = a.w(), q[1] = a.x(), q[2] = a.y(), q[3] = a.z();
}
double gyro_model_d_cone(const gyro_model_d* m) { return m != nullptr ? m->model.gimbal_cone_rad() : 0.0; }
float gyro_model_f_cone(const gyro_model_f* m) { return m != nullptr ? m->model.gimbal_cone_rad() : 0.0f; }
uint32_t gyro_model_d_flags(const gyro_model_d* m) { return m != nullptr ? m->model.flags() : 0u; }
uint32_t gyro_model_f_flags(const gyro_model_f* m) { return m != nullptr ? m->model.flags() : 0u; }
int gyro_model_d_uncaged(const gyro_model_d* m) { return m != nullptr && m->model.uncaged() ? 1 : 0; }
int gyro_model_f_uncaged(const gyro_model_f* m) { return m != nullptr && m->model.uncaged() ? 1 : 0; }

int gyro_report_sample_get(gyro_report_sample* out, gyro_model_config* config) {
  using S = gyro::ReportSample<double>;
  if (out == nullptr || config == nullptr) return GYRO_NULL_ARGUMENT;
  if (!c::write_config(c::kModelConfig, S::config(), config)) return GYRO_INTERNAL_ERROR;
  out->spin_hz = S::kSpinHz;
  out->body_rate_rad_s[0] = S::kBodyPitchRate;
  out->body_rate_rad_s[1] = S::kBodyYawRate;
  const Vector2<double> slew = S::slew_command();
  out->slew_rate_rad_s[0] = slew(0);
  out->slew_rate_rad_s[1] = slew(1);
  out->initg_step_s = S::initg_step();
  out->steps = S::kSteps;
  return GYRO_OK;
}

}  // extern "C"
