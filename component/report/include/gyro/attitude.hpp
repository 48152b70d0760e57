// Attitude pieces of the gyro model: the exact rotation of one step, the gimbal angles
// read off the spin axis in body axes, and checks on rotations handed in by callers.
//
// Frames: earth, body (x forward, y right, z down) and gyro (x = spin axis). The gyro's
// attitude is the unit quaternion q_gyro_to_earth (it rotates gyro-axis vectors into earth
// axes); R_earth_to_gyro is the transpose of its matrix, the report's ROTEG.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "gyro/arctangent.hpp"
#include "gyro/rotor_parameters.hpp"

namespace gyro {

template <typename T>
using Vector3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using Matrix3 = Eigen::Matrix<T, 3, 3>;
template <typename T>
using Quaternion = Eigen::Quaternion<T>;

namespace detail {
// The rotation of rotation vector (roll, th, ps) in the gyro axes, as a unit quaternion.
template <typename T>
[[nodiscard]] Quaternion<T> rotation_from_vector(T roll, T th, T ps) noexcept {
  const T h2 = (roll * roll + th * th + ps * ps) / T(4);  // (half the rotation angle)^2
  constexpr T kSmall = ScalarTraits<T>::kSmallRotation / T(2);
  T c, s;  // cos(h) and sin(h)/(2h)
  if (h2 <= kSmall * kSmall) {
    // Truncation below h^8/8! = 1e-17 for h <= 0.025: exact to rounding.
    c = T(1) - h2 * (T(1) / T(2) - h2 * (T(1) / T(24) - h2 * (T(1) / T(720))));
    s = (T(1) - h2 * (T(1) / T(6) - h2 * (T(1) / T(120) - h2 * (T(1) / T(5040))))) / T(2);
  } else if (std::isfinite(h2)) {
    const T h = std::sqrt(h2);
    c = std::cos(h);
    s = std::sin(h) / (T(2) * h);
  } else {
    // The squares overflowed (angles beyond 1e154 rad in double, 1e19 in float): the same
    // from the half angles without squaring, so the result is still a unit quaternion.
    const T h = std::hypot(std::hypot(roll / T(2), th / T(2)), ps / T(2));
    c = std::cos(h);
    s = (std::sin(h) / h) / T(2);
  }
  return Quaternion<T>(c, s * roll, s * th, s * ps);
}
}  // namespace detail

// The rotation of a step whose ISAF angles are (theta, psi): rotation vector (0, theta, psi)
// in the gyro axes at the step's start. To first order this is the report's ROT matrix; here
// it is exact, so the attitude stays a rotation however large the angles.
template <typename T>
[[nodiscard]] Quaternion<T> step_rotation(const Vector2<T>& isaf_angle_rad) noexcept {
  return detail::rotation_from_vector(T(0), isaf_angle_rad(0), isaf_angle_rad(1));
}

// A correction c turned just before a step a (both (pitch, yaw) rotation vectors on the same
// gyro axes), as one rotation: R(c) R(a) has the rotation vector c + a + (c x a)/2 (the
// Baker-Campbell-Hausdorff series), whose x part (c_th a_ps - c_ps a_th)/2 is the roll that
// two turns about different transverse axes leave. The terms left out are third order, below
// |a| |c| (|a| + |c|) / 12; with c = 0 this is step_rotation(a) exactly.
template <typename T>
[[nodiscard]] Quaternion<T> step_rotation(const Vector2<T>& isaf_angle_rad, const Vector2<T>& correction_rad) noexcept {
  const Vector2<T>& a = isaf_angle_rad;
  const Vector2<T>& c = correction_rad;
  return detail::rotation_from_vector(T(0.5) * (c(0) * a(1) - c(1) * a(0)), c(0) + a(0), c(1) + a(1));
}

// Brings |q| back to 1 to first order without a square root: (3 - |q|^2)/2 ~ 1/|q| when
// |q| ~ 1 (the error left is 1.5 (|q|^2 - 1)^2, far below rounding for a unit step).
template <typename T>
void renormalize(Quaternion<T>& q) noexcept {
  q.coeffs() *= (T(3) - q.coeffs().squaredNorm()) / T(2);
}

// The spin axis (gyro x) expressed in earth axes.
template <typename T>
[[nodiscard]] Vector3<T> spin_axis_in_earth(const Quaternion<T>& q_gyro_to_earth) noexcept {
  const T w = q_gyro_to_earth.w(), x = q_gyro_to_earth.x(), y = q_gyro_to_earth.y(),
          z = q_gyro_to_earth.z();
  return Vector3<T>(T(1) - T(2) * (y * y + z * z), T(2) * (x * y + w * z), T(2) * (x * z - w * y));
}

template <typename T>
struct GimbalAngles {
  T pitch_rad{};  // spin axis above the body x-y plane is positive (nose-up, like theta)
  T yaw_rad{};    // spin axis to the right of the body x-z plane is positive (like psi)
  T cosine_of_cone{1};  // cos of the total angle between spin axis and body x
};

// Gimbal angles from the spin axis in body axes (the report's GP vector), or from the spin
// axis in earth axes and the body's attitude. The listing's GIMBY and GIMBZ are the
// negatives of these (see docs/seed-errata.md).
template <typename T>
[[nodiscard]] GimbalAngles<T> gimbal_angles(const Vector3<T>& spin_axis_body) noexcept {
  const Vector3<T>& gp = spin_axis_body;
  GimbalAngles<T> g;
  g.pitch_rad = fixed_cost_atan2(-gp(2), std::sqrt(gp(0) * gp(0) + gp(1) * gp(1)));  // |gp| = 1
  g.yaw_rad = fixed_cost_atan2(gp(1), gp(0));
  g.cosine_of_cone = gp(0);
  return g;
}
template <typename T>
[[nodiscard]] GimbalAngles<T> gimbal_angles(const Matrix3<T>& R_earth_to_body,
                                            const Vector3<T>& spin_axis_earth) noexcept {
  Vector3<T> gp;
  gp.noalias() = R_earth_to_body * spin_axis_earth;
  return gimbal_angles(gp);
}

// True when R is finite and a rotation within the scalar type's tolerance: its first two rows
// unit and orthogonal, its last their cross product (so R R^T - I is within a few times the
// tolerance and det R = +1: a reflection's last row is minus the cross product). Every test is
// false on a NaN, and an infinite entry makes a norm or a difference infinite or NaN, so
// non-finite entries fail without a test of their own; no branch per test.
template <typename T>
[[nodiscard]] bool is_rotation(const Matrix3<T>& r) noexcept {
  const T a0 = r(0, 0), a1 = r(0, 1), a2 = r(0, 2);
  const T b0 = r(1, 0), b1 = r(1, 1), b2 = r(1, 2);
  const T tol = ScalarTraits<T>::kRotationTolerance;
  const auto within = [tol](T e) noexcept { return static_cast<unsigned>(std::abs(e) <= tol); };
  const unsigned orthonormal = within(a0 * a0 + a1 * a1 + a2 * a2 - T(1)) &
                               within(b0 * b0 + b1 * b1 + b2 * b2 - T(1)) & within(a0 * b0 + a1 * b1 + a2 * b2);
  const unsigned last_row = within(r(2, 0) - (a1 * b2 - a2 * b1)) & within(r(2, 1) - (a2 * b0 - a0 * b2)) &
                            within(r(2, 2) - (a0 * b1 - a1 * b0));
  return (orthonormal & last_row) != 0u;
}

// Largest entry of R R^T - I: how far a matrix has drifted from a rotation.
template <typename T>
[[nodiscard]] T orthonormality_error(const Matrix3<T>& r) noexcept {
  Matrix3<T> e;
  e.noalias() = r * r.transpose();
  e -= Matrix3<T>::Identity();
  return e.cwiseAbs().maxCoeff();
}

// The passive (frame) rotation matrices the report's driver uses: a body that turns by
// `angle` about its own y (pitch) or z (yaw) axis has R_new = R_axis(angle) * R_old.
template <typename T>
[[nodiscard]] Matrix3<T> frame_rotation_y(T angle) noexcept {
  const T c = std::cos(angle), s = std::sin(angle);
  Matrix3<T> r;
  r << c, T(0), -s, T(0), T(1), T(0), s, T(0), c;
  return r;
}
template <typename T>
[[nodiscard]] Matrix3<T> frame_rotation_z(T angle) noexcept {
  const T c = std::cos(angle), s = std::sin(angle);
  Matrix3<T> r;
  r << c, s, T(0), -s, c, T(0), T(0), T(0), T(1);
  return r;
}

}  // namespace gyro
