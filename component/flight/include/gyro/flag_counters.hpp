// The flag counters: one saturating count per flag bit (telemetry.counters, index = bit number), so
// that the ground sees every flag a tick raised even when it reads telemetry seldom.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>

#include "gyro/component_types.hpp"

namespace gyro {

// The bit number of a single raised flag: its counter's index. Five halvings: a fixed cost, without
// compiler builtins.
[[nodiscard]] constexpr std::size_t flag_bit(std::uint32_t single_flag) noexcept {
  std::size_t i = 0;
  if ((single_flag & 0xFFFF0000u) != 0u) i += 16u;
  if ((single_flag & 0xFF00FF00u) != 0u) i += 8u;
  if ((single_flag & 0xF0F0F0F0u) != 0u) i += 4u;
  if ((single_flag & 0xCCCCCCCCu) != 0u) i += 2u;
  if ((single_flag & 0xAAAAAAAAu) != 0u) i += 1u;
  return i;
}

// Counts a tick that raised `flags`: one more per raised flag, none past the counter's range. In
// place: the counts are the telemetry's, and a copy in and out costs a clean tick a fifth of its
// flag handling. A loop over the raised flags only (at most kComponentFlagCount passes; none on a
// clean tick).
inline void count_flags(FlagCounts& counts, std::uint32_t flags) noexcept {
  std::uint32_t left = flags & ((1u << static_cast<unsigned>(kComponentFlagCount)) - 1u);
  for (int pass = 0; pass < kComponentFlagCount && left != 0u; ++pass) {
    const std::uint32_t lowest = left & (~left + 1u);  // the lowest raised flag
    std::uint32_t& n = counts[flag_bit(lowest)];
    if (n != std::numeric_limits<std::uint32_t>::max()) ++n;
    left ^= lowest;
  }
}

}  // namespace gyro
