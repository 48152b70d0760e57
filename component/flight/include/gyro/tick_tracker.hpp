// The tick tracker: how many ticks passed since the last call, from the caller's tick count.
//
// The call itself is the clock (one per release of the rate group): a jump of 2..max_tick_gap
// after a trusted count is lost ticks, bridged (the held torque acted all along); anything
// else (a repeat, a step back, a longer jump, or any jump right after an untrusted count) is
// taken as one tick and the count resynchronised to it, to be trusted once the next call
// follows it by one.
#pragma once

#include <cstdint>

#include "gyro/component_types.hpp"

namespace gyro {

struct ElapsedTicks {
  std::uint64_t ticks{1};
  std::uint32_t flags{0};  // kTickSkipped (bridged) or kTickInvalid (taken as one)
};

class TickTracker {
 public:
  [[nodiscard]] ElapsedTicks advance(std::uint64_t tick, std::uint64_t max_tick_gap) noexcept {
    ElapsedTicks e;
    bool trusted = true;
    if (have_tick_ && tick != last_tick_ + 1u) {
      const bool bridgeable = tick_trusted_ && tick > last_tick_ && tick - last_tick_ <= max_tick_gap;
      if (bridgeable) {
        e.ticks = tick - last_tick_;
        e.flags |= kTickSkipped;
      } else {
        e.flags |= kTickInvalid;
        trusted = false;
      }
    }
    last_tick_ = tick;
    have_tick_ = true;
    tick_trusted_ = trusted;
    return e;
  }

 private:
  std::uint64_t last_tick_{0};
  bool have_tick_{false};
  bool tick_trusted_{false};
};

}  // namespace gyro
