// Persistence of a fault condition that an intermittent fault cannot dodge: a leaky counter.
//
// Each tick the condition holds the counter fills by 2; each tick it does not, it drains by
// 1 (never below 0). The monitor trips when the counter reaches 2 N (N = the configured
// persistence), and the counter never rises above 2 N. So:
//   - N consecutive bad ticks trip it, exactly as a consecutive-tick counter would;
//   - a condition present in a fraction p > 1/3 of the ticks trips it too, after about
//     2 N / (3 p - 1) ticks (19 bad ticks in 20: 1.1 N; one in two: 4 N);
//   - below one bad tick in three it never trips (isolated glitches are only counted);
//   - one good tick after any run of bad ones un-trips it (the counter is capped at 2 N), so a
//     latched fault can be left as soon as the condition is gone.
// Constant cost, no data-dependent loop, integer arithmetic only.
#pragma once

#include <cstdint>

namespace gyro {

class PersistenceMonitor {
 public:
  // Feeds one tick; returns whether the monitor is tripped after it. `persistence` >= 1.
  [[nodiscard]] bool update(bool condition, std::uint32_t persistence) noexcept {
    const std::uint64_t cap = 2u * static_cast<std::uint64_t>(persistence);
    if (condition) {
      fill_ = fill_ + 2u > cap ? cap : fill_ + 2u;
    } else if (fill_ > 0u) {
      --fill_;
    }
    return tripped(persistence);
  }
  [[nodiscard]] bool tripped(std::uint32_t persistence) const noexcept {
    return fill_ >= 2u * static_cast<std::uint64_t>(persistence);
  }
  void reset() noexcept { fill_ = 0; }
  [[nodiscard]] std::uint64_t fill() const noexcept { return fill_; }

 private:
  std::uint64_t fill_{0};
};

}  // namespace gyro
