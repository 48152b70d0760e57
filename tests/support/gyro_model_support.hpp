// What the GyroModel tests share (gyro_model_test.cpp, gyro_model_error_sources_test.cpp,
// gyro_model_bad_input_test.cpp): the test gyro, tolerances, step inputs, and the model's
// observable state for bit-for-bit comparisons.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "gyro/gyro_model.hpp"

namespace gyro::model_test {

using Scalars = ::testing::Types<float, double>;

template <typename T>
constexpr bool kIsFloat = std::is_same_v<T, float>;

template <typename T>
constexpr double D(T x) noexcept {
  return static_cast<double>(x);
}

// Tolerances on quantities of order 0.01-1 (rad, rad/s).
template <typename T>
struct Tol;
template <>
struct Tol<double> {
  static constexpr double kRate = 1e-12;
  static constexpr double kAngle = 1e-12;
  static constexpr double kRel = 1e-9;
};
template <>
struct Tol<float> {
  static constexpr double kRate = 2e-5;
  static constexpr double kAngle = 2e-5;
  static constexpr double kRel = 2e-4;
};

// The report's gyro without friction (J1 != J2, so the nutation is elliptical), no error
// sources, rate limits and gimbal cone out of the way unless a test sets them.
template <typename T>
GyroModelConfig<T> test_config() {
  GyroModelConfig<T> c;
  c.pitch_inertia = T(2.25);
  c.yaw_inertia = T(2.0);
  c.spin_inertia = T(3.0);
  c.friction = T(0);
  c.gimbal_cone_limit_rad = T(1.5);
  c.max_pitch_rate_rad_s = T(1);
  c.max_yaw_rate_rad_s = T(1);
  return c;  // small-angle limit 0.01 rad and gravity 9.80665 by default
}

template <typename T>
constexpr T kSpinHz = T(100);

template <typename T>
T momentum(const GyroModelConfig<T>& c, T spin_hz) {
  return T(2) * kPi<T> * spin_hz * c.spin_inertia;
}

// Nutation rate of a frictionless gyro: the eigenvalues of eqs 1a/1b with f = 0 are
// +-i H/sqrt(J1 J2).
template <typename T>
T frictionless_nutation_rate(const GyroModelConfig<T>& c, T spin_hz) {
  return momentum(c, spin_hz) / std::sqrt(c.pitch_inertia * c.yaw_inertia);
}

template <typename T>
Matrix3<T> some_body_attitude() {
  // R_earth_to_body of a body turned by 0.7 rad about (1, 2, 3)/|.|.
  const Vector3<T> axis = Vector3<T>(T(1), T(2), T(3)).normalized();
  return Eigen::AngleAxis<T>(T(0.7), axis).toRotationMatrix().transpose();
}

template <typename T>
GyroModel<T> uncaged_model(const GyroModelConfig<T>& c, const Vector2<T>& rate0,
                           const Vector2<T>& offset = Vector2<T>::Zero(),
                           const Matrix3<T>& r_eb = Matrix3<T>::Identity()) {
  GyroModel<T> g;
  const ConfigCheck cc = g.configure(c);
  EXPECT_TRUE(cc.ok()) << (cc.field ? cc.field : "");
  EXPECT_EQ(g.uncage(r_eb, rate0, offset), Status::kOk);
  return g;
}

template <typename T>
GyroStepInput<T> step_input(T dt, T spin_hz = kSpinHz<T>, const Matrix3<T>& r_eb = Matrix3<T>::Identity()) {
  GyroStepInput<T> in;
  in.dt_s = dt;
  in.spin_hz = spin_hz;
  in.R_earth_to_body = r_eb;
  return in;
}

// The mean of the rates over `periods` whole nutation periods of a frictionless gyro,
// sampled 20 times a period: the nutation sums to zero, what is left is the precession.
template <typename T>
Vector2<double> mean_rate_over_nutation_periods(GyroModel<T>& g, GyroStepInput<T> in, int periods,
                                                const std::function<Status(GyroModel<T>&, const GyroStepInput<T>&)>& step) {
  const T beta = frictionless_nutation_rate(g.config(), in.spin_hz);
  in.dt_s = T(2) * kPi<T> / (T(20) * beta);
  Vector2<double> sum = Vector2<double>::Zero();
  const int n = 20 * periods;
  for (int k = 0; k < n; ++k) {
    const Status st = step(g, in);
    EXPECT_EQ(st, Status::kOk);
    if (st != Status::kOk) break;
    sum += g.rate_rad_s().template cast<double>();
  }
  return sum / static_cast<double>(n);
}

template <typename T>
std::function<Status(GyroModel<T>&, const GyroStepInput<T>&)> slewing(const Vector2<T>& cmd) {
  return [cmd](GyroModel<T>& g, const GyroStepInput<T>& in) { return g.step_slew(in, cmd); };
}
template <typename T>
std::function<Status(GyroModel<T>&, const GyroStepInput<T>&)> torquing(const Vector2<T>& torque) {
  return [torque](GyroModel<T>& g, const GyroStepInput<T>& in) { return g.step_torque(in, torque); };
}

// Spin axis (gyro x) after a rotation by `angle` about the unit axis (0, uy, uz) of a frame
// whose x it started on (Rodrigues): (cos a, uz sin a, -uy sin a).
inline Vector3<double> spin_after_rotation(double uy, double uz, double angle) {
  return Vector3<double>(std::cos(angle), uz * std::sin(angle), -uy * std::sin(angle));
}
// Gimbal angles read off a spin axis in body axes, by their definition: pitch = elevation
// above the body x-y plane (z down), yaw = azimuth to the right.
inline Vector2<double> gimbal_of(const Vector3<double>& s) {
  return Vector2<double>(std::asin(-s(2) / s.norm()), std::atan2(s(1), s(0)));
}

// Everything a caller can observe of the model.
template <typename T>
struct Observed {
  static constexpr std::size_t kN = 24;
  std::array<T, kN> v{};
  std::uint32_t flags{};
  bool uncaged{};
};
template <typename T>
Observed<T> observe(const GyroModel<T>& g) {
  Observed<T> o;
  std::size_t i = 0;
  const auto put = [&](T x) { o.v[i++] = x; };
  const Quaternion<T>& q = g.attitude_gyro_to_earth();
  put(q.w());
  put(q.x());
  put(q.y());
  put(q.z());
  const Matrix3<T> r = g.R_earth_to_gyro();
  for (int k = 0; k < 9; ++k) put(r.data()[k]);
  put(g.rate_rad_s()(0));
  put(g.rate_rad_s()(1));
  put(g.isaf_angle_rad()(0));
  put(g.isaf_angle_rad()(1));
  put(g.nutation_amplitude_rad()(0));
  put(g.nutation_amplitude_rad()(1));
  put(g.applied_torque()(0));
  put(g.applied_torque()(1));
  put(g.gimbal_pitch_rad());
  put(g.gimbal_yaw_rad());
  put(g.gimbal_cone_rad());
  o.flags = g.flags();
  o.uncaged = g.uncaged();
  return o;
}
template <typename T>
bool bit_identical(const Observed<T>& a, const Observed<T>& b) {
  return std::memcmp(a.v.data(), b.v.data(), sizeof(T) * Observed<T>::kN) == 0 && a.flags == b.flags &&
         a.uncaged == b.uncaged;
}
template <typename T>
bool same_config(const GyroModelConfig<T>& a, const GyroModelConfig<T>& b) {
  static_assert(std::is_trivially_copyable_v<GyroModelConfig<T>>);
  return std::memcmp(&a, &b, sizeof(a)) == 0;
}

}  // namespace gyro::model_test
