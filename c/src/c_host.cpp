// gyro.h's host parts without exceptions: models on the heap (for callers that cannot keep
// storage) and the nonlinear gimbal plant (gyro/gimbal_plant.hpp).
#include <new>

#include "c_arrays.hpp"
#include "c_fields.hpp"
#include "c_handles.hpp"
#include "gyro/gimbal_plant.hpp"

// The plant and the body's motion at its last tick (the start of the next).
struct gyro_plant_d {
  gyro::GimbalPlant<double> plant;
  gyro::BodyState<double> body;
};

namespace gyro::c_api {
namespace {

template <class H>
H* create() noexcept {
  void* p = ::operator new(sizeof(H), std::align_val_t{alignof(H)}, std::nothrow);
  return p != nullptr ? ::new (p) H{} : nullptr;
}
template <class H>
void destroy(H* h) noexcept {
  if (h == nullptr) return;
  h->~H();
  ::operator delete(h, std::align_val_t{alignof(H)});
}

Vector3<double> vector3_or_zero(const double* v) noexcept {
  return v != nullptr ? vector_of<double, 3>(v) : Vector3<double>(Vector3<double>::Zero());
}
Vector2<double> vector2_or_zero(const double* v) noexcept {
  return v != nullptr ? vector_of<double, 2>(v) : Vector2<double>(Vector2<double>::Zero());
}

}  // namespace
}  // namespace gyro::c_api

namespace c = gyro::c_api;

extern "C" {

gyro_model_d* gyro_model_d_create(void) { return c::create<gyro_model_d>(); }
gyro_model_f* gyro_model_f_create(void) { return c::create<gyro_model_f>(); }
void gyro_model_d_destroy(gyro_model_d* m) { c::destroy(m); }
void gyro_model_f_destroy(gyro_model_f* m) { c::destroy(m); }

gyro_plant_d* gyro_plant_d_create(void) { return c::create<gyro_plant_d>(); }
void gyro_plant_d_destroy(gyro_plant_d* p) { c::destroy(p); }

int gyro_plant_d_configure(gyro_plant_d* p, const gyro_plant_config* config, double tick_s, gyro_refusal* refusal) {
  if (p == nullptr || config == nullptr) return GYRO_NULL_ARGUMENT;
  gyro::GimbalPlantConfig<double> cpp{};
  gyro::ConfigCheck check = c::read_config(c::kPlantConfig, config, cpp);
  if (check.ok()) check = p->plant.configure(cpp, tick_s);
  c::to_c(check, refusal);
  return static_cast<int>(check.status);
}

int gyro_plant_d_start(gyro_plant_d* p, const double gimbal_angle_rad[2], const double gimbal_rate_rad_s[2],
                       double spin_hz, const double body_rate_rad_s[3], const double specific_force[3]) {
  if (p == nullptr) return GYRO_NULL_ARGUMENT;
  gyro::BodyState<double> body;
  body.rate_rad_s = c::vector3_or_zero(body_rate_rad_s);
  body.specific_force = c::vector3_or_zero(specific_force);
  const gyro::GimbalStart<double> start{c::vector2_or_zero(gimbal_angle_rad), c::vector2_or_zero(gimbal_rate_rad_s),
                                        spin_hz};
  const gyro::Status st = p->plant.start(start, body);
  if (st == gyro::Status::kOk) p->body = body;
  return static_cast<int>(st);
}

int gyro_plant_d_step(gyro_plant_d* p, const double torque[2], const double body_rate_rad_s[3],
                      const double specific_force[3]) {
  if (p == nullptr || torque == nullptr) return GYRO_NULL_ARGUMENT;
  gyro::BodyState<double> end = p->body;
  if (body_rate_rad_s != nullptr) end.rate_rad_s = c::vector_of<double, 3>(body_rate_rad_s);
  if (specific_force != nullptr) end.specific_force = c::vector_of<double, 3>(specific_force);
  const gyro::Status st = p->plant.step(c::vector_of<double, 2>(torque), p->body, end);
  if (st == gyro::Status::kOk) p->body = end;
  return static_cast<int>(st);
}

void gyro_plant_d_gimbal(const gyro_plant_d* p, double angle_rad[2], double rate_rad_s[2]) {
  if (p == nullptr) return;
  c::put(gyro::Vector2<double>(p->plant.gimbal_angle_rad()), angle_rad);
  c::put(gyro::Vector2<double>(p->plant.gimbal_rate_rad_s()), rate_rad_s);
}
void gyro_plant_d_spin_axis_body(const gyro_plant_d* p, double axis[3]) {
  if (p != nullptr) c::put(gyro::Vector3<double>(p->plant.spin_axis_body()), axis);
}
double gyro_plant_d_cone(const gyro_plant_d* p) { return p != nullptr ? p->plant.cone_rad() : 0.0; }
double gyro_plant_d_spin_rate(const gyro_plant_d* p) { return p != nullptr ? p->plant.spin_rate_rad_s() : 0.0; }
int gyro_plant_d_in_contact(const gyro_plant_d* p) { return p != nullptr && p->plant.in_contact() ? 1 : 0; }

}  // extern "C"
