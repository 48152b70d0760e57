// How many sub-steps a tick of the gimbal plant takes (docs/gimbal-plant.md): the fewest, up to
// the bound n_max, whose error estimate stays within the tick's share of the error target.
//
// A tick first tries the count the previous tick chose; a try whose estimate is beyond the
// tolerance (or not finite) is redone once with the count the estimate asks for, and then at
// n_max: at most three tries, at most 3 n_max sub-steps. The counts come from the method's
// order (the error of n sub-steps falls as n^-8) with basic arithmetic and square roots only,
// correctly rounded in IEEE 754: the same counts on every machine.
#pragma once

#include <cmath>

namespace gyro {

// The counts aim at this fraction of the tolerance, so that a tick's try seldom fails.
template <typename T>
inline constexpr T kSubstepSafety = T(0.5);

namespace gimbal_detail {
// n (error / (safety tolerance))^(1/8), rounded up: the count the estimate asks for.
template <typename T>
[[nodiscard]] T substeps_for(int n, T error, T tolerance) noexcept {
  const T ratio = error / (kSubstepSafety<T> * tolerance);
  return std::ceil(static_cast<T>(n) * std::sqrt(std::sqrt(std::sqrt(ratio))));
}
}  // namespace gimbal_detail

// After a try of n sub-steps failed: more, at most n_max (n_max when the estimate is not
// finite).
template <typename T>
[[nodiscard]] int substeps_after_failure(int n, T error, T tolerance, int n_max) noexcept {
  const T m = gimbal_detail::substeps_for(n, error, tolerance);
  if (!(m < static_cast<T>(n_max))) return n_max;  // NaN too
  return m > static_cast<T>(n) ? static_cast<int>(m) : n + 1;
}

// After a try of n sub-steps passed: the count the next tick tries first, no more than n (a
// failed try costs its sub-steps), at least 1.
template <typename T>
[[nodiscard]] int substeps_after_success(int n, T error, T tolerance) noexcept {
  const T m = gimbal_detail::substeps_for(n, error, tolerance);
  if (!(m < static_cast<T>(n))) return n;
  return m < T(1) ? 1 : static_cast<int>(m);
}

}  // namespace gyro
