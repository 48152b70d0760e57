// A value limited to a range, the one clamp of the flight code and the SIL stub.
//
// Not std::clamp: written as min(hi, max(lo, v)) it sends a NaN to lo (std::clamp passes it
// through), and every limit in gyro has always been applied this way, so the outputs stay
// bit-for-bit what they were.
#pragma once

#include <algorithm>

namespace gyro {

// v limited to [lo, hi] (lo <= hi); a NaN gives lo.
template <typename T>
[[nodiscard]] constexpr T saturate(T v, T lo, T hi) noexcept {
  return std::min(hi, std::max(lo, v));
}
// v limited to [-limit, limit] (limit >= 0); a NaN gives -limit.
template <typename T>
[[nodiscard]] constexpr T saturate(T v, T limit) noexcept {
  return saturate(v, -limit, limit);
}

}  // namespace gyro
