// The link's event counters: one more, stopping at the largest uint32 instead of wrapping to 0
// (a wrapped count would read as no events at all).
#pragma once

#include <cstdint>
#include <limits>

namespace gyro::link {

[[nodiscard]] constexpr std::uint32_t saturating_increment(std::uint32_t count) noexcept {
  return count == std::numeric_limits<std::uint32_t>::max() ? count : count + 1u;
}

}  // namespace gyro::link
