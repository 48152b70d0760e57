// Per-scalar-type constants: the named tolerances and series lengths of the numerics.
#pragma once

#include <type_traits>

namespace gyro {

template <typename T>
struct ScalarTraits;

template <>
struct ScalarTraits<double> {
  // Terms of the Taylor series used for |eigenvalue * dt| <= 1: the first dropped term,
  // 1/(kSeriesTerms + 1)!, is below the unit roundoff (1/20! = 4.1e-19).
  static constexpr int kSeriesTerms = 20;
  // Below this rotation angle (rad) the step quaternion's series is exact to rounding.
  static constexpr double kSmallRotation = 0.05;
  // Orthonormality tolerated in a rotation matrix handed in by a caller.
  static constexpr double kRotationTolerance = 1e-9;
};

template <>
struct ScalarTraits<float> {
  static constexpr int kSeriesTerms = 12;  // 1/13! = 1.6e-10
  static constexpr float kSmallRotation = 0.05f;
  static constexpr float kRotationTolerance = 1e-4f;
};

template <typename T>
inline constexpr bool kIsSupportedScalar = std::is_same_v<T, float> || std::is_same_v<T, double>;

}  // namespace gyro
