// SysTick as the clock of the rate group: an interrupt every `period` core clocks, and the
// running time in core clocks. pause() stops the counter where it is and resume() continues
// from there: the processor-in-the-loop exchange with the host happens while the timer is
// paused, so the target's time, its tick releases and its overruns depend only on the
// instructions it executes (under QEMU's -icount shift=0 one core clock of the MPS2's 25 MHz is
// 40 instructions), never on how long the host took.
#pragma once

#include <cstdint>

#include "cortex_m.hpp"

namespace gyro_fw {

class TickTimer {
 public:
  static constexpr std::uint32_t kEnable = 1u << 0;
  static constexpr std::uint32_t kInterrupt = 1u << 1;
  static constexpr std::uint32_t kCoreClock = 1u << 2;
  static constexpr std::uint32_t kMaxPeriod = 1u << 24;

  // Starts releasing a tick every `period` core clocks (2 .. 2^24); false: out of range.
  [[nodiscard]] bool start(std::uint32_t period) noexcept {
    if (period < 2u || period > kMaxPeriod) return false;
    period_ = period;
    volatile SysTickRegisters& r = systick();
    r.ctrl = 0;
    r.load = period - 1u;
    r.val = 0;  // any write clears: the counter reloads on enable
    r.ctrl = kEnable | kInterrupt | kCoreClock;
    return true;
  }
  void pause() noexcept { systick().ctrl = kInterrupt | kCoreClock; }
  void resume() noexcept { systick().ctrl = kEnable | kInterrupt | kCoreClock; }

  // From the SysTick handler: one period has passed.
  void on_interrupt() noexcept { wraps_ = wraps_ + 1u; }

  // Core clocks of running time since start() (paused time excluded).
  [[nodiscard]] std::uint64_t now() const noexcept {
    const std::uint32_t primask = save_and_disable_interrupts();
    std::uint32_t wraps = wraps_;
    std::uint32_t val = systick().val;
    if ((icsr() & kIcsrPendStSet) != 0u) {  // wrapped, handler not yet run: count it, re-read
      ++wraps;
      val = systick().val;
    }
    restore_interrupts(primask);
    // The counter runs period-1 .. 0 and raises its interrupt on reaching 0 (one clock before
    // it reloads): `wraps` periods are complete one clock after that.
    const std::uint64_t base = std::uint64_t{wraps} * period_;
    if (val == 0u) return base == 0u ? 0u : base - 1u;
    return base + (period_ - 1u - val);
  }

  [[nodiscard]] std::uint32_t period() const noexcept { return period_; }

 private:
  volatile std::uint32_t wraps_{0};
  std::uint32_t period_{1};
};

}  // namespace gyro_fw
