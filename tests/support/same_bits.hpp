// Bit-for-bit equality of a value or a fixed-size Eigen matrix: what a refused call must leave.
#pragma once

#include <cstddef>
#include <cstring>

#include <Eigen/Core>

namespace gyro::testing {

template <typename A>
[[nodiscard]] bool same_bits(const A& a, const A& b) {
  return std::memcmp(&a, &b, sizeof(A)) == 0;
}
template <typename T, int R, int C>
[[nodiscard]] bool same_bits(const Eigen::Matrix<T, R, C>& a, const Eigen::Matrix<T, R, C>& b) {
  return std::memcmp(a.data(), b.data(), sizeof(T) * static_cast<std::size_t>(R * C)) == 0;
}

}  // namespace gyro::testing
