// Where the report's linear model meets the device: a yaw-outer, pitch-inner gimbal whose
// torquers act about the gimbal axes and whose bearings rub on the gimbal rates relative to
// the body (docs/gimbal-geometry.md derives each line).
//
// Frames (docs/conventions.md): the spin axis x (gyro x), the gyro's own transverse axes
// y_g, z_g (the report's, carried by the exact step: they never roll), and the inner gimbal
// frame y_I (the pitch gimbal axis, normal to the spin axis and to body z) and z_I = x × y_I.
// With the gimbal angles theta (pitch) and psi (yaw), in body axes:
//   x   = ( cos th cos ps,  cos th sin ps, -sin th)
//   y_I = (-sin ps,         cos ps,         0     )
//   z_I = ( sin th cos ps,  sin th sin ps,  cos th)
// The inner torquer acts about y_I; the outer one about body z, which is tilted from the
// plane normal to the spin axis by theta, so its moment reaches the rotor as T_out / cos th
// about z_I (the outer bearing carries the rest). Both axes turn with the gimbal frame, which
// twists about the spin axis against the gyro's axes as the body rolls: the 2x2 rotation
// `gimbal_to_gyro` carries components on (y_I, z_I) to components on (y_g, z_g).
#pragma once

#include <algorithm>
#include <cmath>

#include "gyro/attitude.hpp"
#include "gyro/saturate.hpp"

namespace gyro {

template <typename T>
struct GimbalFrame {
  T cos_pitch{T(1)};  // cos th (never below kMinCosPitch: the gimbal-lock guard)
  T sin_pitch{};
  Vector3<T> spin_axis_body{T(1), T(0), T(0)};  // x in body axes
  Vector3<T> y_inner_body{T(0), T(1), T(0)};  // y_I in body axes
  Vector3<T> z_inner_body{T(0), T(0), T(1)};  // z_I in body axes
  Matrix2<T> gimbal_to_gyro{Matrix2<T>::Identity()};  // (y_I, z_I) components -> (y_g, z_g)
};

// Below this cos th the outer torquer has no authority left (th beyond 87 deg): the geometry
// is evaluated at this bound instead of dividing by nothing.
template <typename T>
inline constexpr T kMinCosPitch = T(0.05);

namespace detail {
// The gimbal frame from the spin axis x in body axes and the first two body components of the
// gyro's y_g and z_g. (y_I, z_I) and (y_g, z_g) are right-handed bases of the same plane, so
// gimbal_to_gyro is the 2x2 rotation [c s; -s c] with c = y_I . y_g and s = -y_I . z_g, and y_I
// has no body z component: the last row of y_g and z_g is not needed.
// Every field of `f` is written (a frame is filled in place, without a copy).
template <typename T>
void gimbal_frame_from(const Vector3<T>& x, T yg0, T yg1, T zg0, T zg1, GimbalFrame<T>& f) noexcept {
  const T horizontal = std::sqrt(x(0) * x(0) + x(1) * x(1));  // cos th
  T cos_yaw = T(1), sin_yaw = T(0);
  if (horizontal > T(0)) {
    cos_yaw = x(0) / horizontal;
    sin_yaw = x(1) / horizontal;
  }
  f.sin_pitch = -x(2);
  f.cos_pitch = std::max(horizontal, kMinCosPitch<T>);
  f.spin_axis_body = x;
  f.y_inner_body = Vector3<T>(-sin_yaw, cos_yaw, T(0));
  f.z_inner_body = Vector3<T>(f.sin_pitch * cos_yaw, f.sin_pitch * sin_yaw, horizontal);
  const T c = cos_yaw * yg1 - sin_yaw * yg0, s = sin_yaw * zg0 - cos_yaw * zg1;
  f.gimbal_to_gyro << c, s, -s, c;
}
}  // namespace detail

// The gimbal frame of a gyro whose axes, in body axes, are the columns of R_gyro_to_body
// (column 0 the spin axis).
template <typename T>
[[nodiscard]] GimbalFrame<T> gimbal_frame(const Matrix3<T>& R_gyro_to_body) noexcept {
  const Matrix3<T>& r = R_gyro_to_body;
  GimbalFrame<T> f;
  detail::gimbal_frame_from<T>(r.col(0), r(0, 1), r(1, 1), r(0, 2), r(1, 2), f);
  return f;
}

// The same for a gyro at attitude q_gyro_to_earth on a body at R_earth_to_body, written into
// `out`, without the whole product R_earth_to_body R(q): the spin axis and four entries of
// the other two columns.
template <typename T>
void gimbal_frame(const Matrix3<T>& R_earth_to_body, const Quaternion<T>& q_gyro_to_earth,
                  GimbalFrame<T>& out) noexcept {
  const T w = q_gyro_to_earth.w(), qx = q_gyro_to_earth.x(), qy = q_gyro_to_earth.y(), qz = q_gyro_to_earth.z();
  const Vector3<T> x_earth = spin_axis_in_earth(q_gyro_to_earth);
  const Vector3<T> y_earth(T(2) * (qx * qy - w * qz), T(1) - T(2) * (qx * qx + qz * qz), T(2) * (qy * qz + w * qx));
  const Vector3<T> z_earth(T(2) * (qx * qz + w * qy), T(2) * (qy * qz - w * qx), T(1) - T(2) * (qx * qx + qy * qy));
  const Matrix3<T>& r = R_earth_to_body;
  const auto row_dot = [&r](int i, const Vector3<T>& v) noexcept {
    return r(i, 0) * v(0) + r(i, 1) * v(1) + r(i, 2) * v(2);
  };
  const Vector3<T> x(row_dot(0, x_earth), row_dot(1, x_earth), row_dot(2, x_earth));
  detail::gimbal_frame_from<T>(x, row_dot(0, y_earth), row_dot(1, y_earth), row_dot(0, z_earth), row_dot(1, z_earth),
                               out);
}

// The gimbal frame at the gimbal angles (pitch, yaw), for a gyro whose own axes are the
// gimbal's (no twist).
template <typename T>
[[nodiscard]] GimbalFrame<T> gimbal_frame_at(const Vector2<T>& gimbal_rad) noexcept {
  const T cp = std::cos(gimbal_rad(0)), sp = std::sin(gimbal_rad(0));
  const T cy = std::cos(gimbal_rad(1)), sy = std::sin(gimbal_rad(1));
  GimbalFrame<T> f;
  f.sin_pitch = sp;
  f.cos_pitch = std::max(cp, kMinCosPitch<T>);
  f.spin_axis_body = Vector3<T>(cp * cy, cp * sy, -sp);
  f.y_inner_body = Vector3<T>(-sy, cy, T(0));
  f.z_inner_body = Vector3<T>(sp * cy, sp * sy, cp);
  return f;
}

// The torque the torquers put on the rotor across the spin axis, on (y_I, z_I): the inner
// torque as it is, the outer one divided by cos th.
template <typename T>
[[nodiscard]] Vector2<T> rotor_torque_from_torquers(const GimbalFrame<T>& f, const Vector2<T>& torquer) noexcept {
  return Vector2<T>(torquer(0), torquer(1) / f.cos_pitch);
}

// The same on the gyro's axes, with the frame moved from `f` by a gimbal pitch change `dth`
// and a roll `roll` of the inner gimbal about the spin axis against the gyro's axes (which
// never roll): second order in both, for the middle of a step. With gimbal_to_gyro
// [c s; -s c] = [cos tau, -sin tau; sin tau, cos tau], tau the roll of y_I from y_g, the roll
// adds to tau. A move beyond half a radian (a step too coarse to follow its torquer axes) is
// taken as half a radian, where the expansion's rotation is still within 1 % of unit length:
// unbounded, it would scale the torque up with the move.
template <typename T>
[[nodiscard]] Vector2<T> rotor_torque_on_gyro_axes_moved(const GimbalFrame<T>& f, const Vector2<T>& torquer, T dth,
                                                         T roll) noexcept {
  constexpr T kMaxMove = T(0.5);
  if (!(std::abs(dth) <= kMaxMove && std::abs(roll) <= kMaxMove)) {  // rare: tested once
    dth = saturate(dth, kMaxMove);
    roll = saturate(roll, kMaxMove);
  }
  const T half_dth_sq = T(0.5) * dth * dth, half_roll_sq = T(0.5) * roll * roll;
  const T cos_pitch = f.cos_pitch - half_dth_sq * f.cos_pitch - dth * f.sin_pitch;
  const Vector2<T> t(torquer(0), torquer(1) / std::max(cos_pitch, kMinCosPitch<T>));
  const T c0 = f.gimbal_to_gyro(0, 0), s0 = f.gimbal_to_gyro(0, 1);
  const T c = c0 - half_roll_sq * c0 + roll * s0, s = s0 - half_roll_sq * s0 - roll * c0;
  return Vector2<T>(c * t(0) + s * t(1), c * t(1) - s * t(0));
}

// The body's angular velocity across the spin axis, on (y_I, z_I) (y_I has no body z part).
template <typename T>
[[nodiscard]] Vector2<T> body_rate_on_gimbal(const GimbalFrame<T>& f, const Vector3<T>& body_rate_rad_s) noexcept {
  const Vector3<T>& w = body_rate_rad_s;
  const Vector3<T>& y = f.y_inner_body;
  const Vector3<T>& z = f.z_inner_body;
  return Vector2<T>(y(0) * w(0) + y(1) * w(1), z(0) * w(0) + z(1) * w(1) + z(2) * w(2));
}

// The inner gimbal's angular velocity about the spin axis (what a spin motor holding the
// spin relative to the inner gimbal adds to the rotor's inertial spin): the body's along x
// plus the outer gimbal's rate ps' = (w_z - wb_z) / cos th about body z, whose share along x
// is -sin th. w and wb are the spin axis's and the body's rates on (y_I, z_I).
template <typename T>
[[nodiscard]] T inner_gimbal_roll(const GimbalFrame<T>& f, const Vector3<T>& body_rate_rad_s,
                                  const Vector2<T>& rate_on_gimbal,
                                  const Vector2<T>& body_rate_on_gimbal_rad_s) noexcept {
  return f.spin_axis_body.dot(body_rate_rad_s) -
         f.sin_pitch * (rate_on_gimbal(1) - body_rate_on_gimbal_rad_s(1)) / f.cos_pitch;
}

// Torquer commands (inner, outer) that hold the spin axis at the inertial rate `rate` (on
// y_I, z_I: pitch, yaw) against the bearings' friction f on the gimbal rates, in steady
// precession with angular momentum h:
//   T_inner = h w_z + f (w_y - wb_y)
//   T_outer = (-h w_y + f (w_z - wb_z) / cos^2 th) cos th
// where wb is the body rate on (y_I, z_I): the gimbal rates are th' = w_y - wb_y and
// ps' = (w_z - wb_z) / cos th. With th = 0 and the body at rest this is the report's exact
// inverse of the friction-coupled precession, T1 = f w1 + H w2, T2 = f w2 - H w1.
template <typename T>
[[nodiscard]] Vector2<T> torquers_for_rate(const GimbalFrame<T>& f, T h, T friction, const Vector2<T>& rate,
                                           const Vector2<T>& body_rate_on_gimbal_rad_s) noexcept {
  const Vector2<T> relative = rate - body_rate_on_gimbal_rad_s;
  const T c = f.cos_pitch;
  return Vector2<T>(h * rate(1) + friction * relative(0), -h * rate(0) * c + friction * relative(1) / c);
}

// The inverse of torquers_for_rate: the steady inertial rate of the spin axis that torquer
// commands `torquer` hold, solving
//   [f, h; -h c, f / c] w = (T_inner + f wb_y, T_outer + f wb_z / c),   det = f^2 / c + h^2 c.
// Zero when the torquers hold no rate (h = f = 0).
template <typename T>
[[nodiscard]] Vector2<T> rate_for_torquers(const GimbalFrame<T>& f, T h, T friction, const Vector2<T>& torquer,
                                           const Vector2<T>& body_rate_on_gimbal_rad_s) noexcept {
  const T c = f.cos_pitch;
  const T det = friction * friction / c + h * h * c;
  if (!(det > T(0))) return Vector2<T>::Zero();
  const T a = torquer(0) + friction * body_rate_on_gimbal_rad_s(0);
  const T b = torquer(1) + friction * body_rate_on_gimbal_rad_s(1) / c;
  return Vector2<T>((friction / c * a - h * b) / det, (h * c * a + friction * b) / det);
}

// What the report's model (friction f on the inertial rates w, in its own axes) must be
// given on top of the torquers' torque so that its friction is the bearings' on (y_I, z_I):
//   f (wb_y, (wb_z - w_z sin^2 th) / cos^2 th)
// with w the spin axis's inertial rate on (y_I, z_I).
template <typename T>
[[nodiscard]] Vector2<T> friction_correction(const GimbalFrame<T>& f, T friction, const Vector2<T>& rate_on_gimbal,
                                             const Vector2<T>& body_rate_on_gimbal_rad_s) noexcept {
  const T c2 = f.cos_pitch * f.cos_pitch;
  return Vector2<T>(friction * body_rate_on_gimbal_rad_s(0),
                    friction * (body_rate_on_gimbal_rad_s(1) - rate_on_gimbal(1) * f.sin_pitch * f.sin_pitch) / c2);
}

}  // namespace gyro
