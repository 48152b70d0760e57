// atan2 in a fixed, small number of operations, the same on every target: the gimbal angles
// are read off the spin axis every tick, and libm's atan2 costs several times this (more
// again on a Cortex-M, and its last bit differs from one C library to the next).
//
// Cephes' method (S. L. Moshier): the ratio of the smaller to the larger magnitude, reduced
// to [0, tan(pi/8)] by atan(t) = pi/4 + atan((t - 1)/(t + 1)), then x + x^3 P(x^2)/Q(x^2)
// with Cephes' minimax coefficients (double), or an odd polynomial of degree 9 (float).
// Relative error against the exact arctangent: 2.8e-16 in double, 2.0e-7 in float (1.3 and
// 1.6 units in the last place; tests/arctangent_test.cpp). Unlike std::atan2, two infinite
// arguments give NaN (as does a NaN), and (+-0, +-0) gives +-0.
#pragma once

#include <cmath>

#include "gyro/rotor_parameters.hpp"

namespace gyro {

namespace detail {

// atan(t) for t in [0, 1].
[[nodiscard]] inline double arctangent_unit(double t) noexcept {
  constexpr double kTanPiOver8 = 0.41421356237309504880;
  constexpr double kMoreBits = 3.061616997868382943065e-17;  // pi/4 - double(pi/4)
  const bool reduced = t > kTanPiOver8;
  const double x = reduced ? (t - 1.0) / (t + 1.0) : t;
  const double z = x * x;
  const double p =
      ((((-8.750608600031904122785e-1 * z - 1.615753718733365076637e1) * z - 7.500855792314704667340e1) * z -
        1.228866684490136173410e2) * z - 6.485021904942025371773e1) * z;
  const double q = ((((z + 2.485846490142306297962e1) * z + 1.650270098316988542046e2) * z +
                     4.328810604912902668951e2) * z + 4.853903996359136964868e2) * z + 1.945506571482613964425e2;
  const double a = x + x * (p / q);
  return reduced ? kPi<double> / 4.0 + (a + kMoreBits) : a;
}

[[nodiscard]] inline float arctangent_unit(float t) noexcept {
  constexpr float kTanPiOver8 = 0.414213562373f;
  const bool reduced = t > kTanPiOver8;
  const float x = reduced ? (t - 1.0f) / (t + 1.0f) : t;
  const float z = x * x;
  const float a = (((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z - 3.33329491539e-1f) *
                      z * x + x;
  return reduced ? kPi<float> / 4.0f + a : a;
}

}  // namespace detail

// The angle of (x, y) from the x axis, in [-pi, pi].
template <typename T>
[[nodiscard]] T fixed_cost_atan2(T y, T x) noexcept {
  const T ax = std::abs(x), ay = std::abs(y);
  const bool steep = ay > ax;
  const T larger = steep ? ay : ax;
  const T ratio = (larger == T(0)) ? T(0) : (steep ? ax : ay) / larger;  // a NaN stays one
  T a = detail::arctangent_unit(ratio);
  if (steep) a = kPi<T> / T(2) - a;
  if (x < T(0)) a = kPi<T> - a;
  return std::copysign(a, y);
}

}  // namespace gyro
