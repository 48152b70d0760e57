// RateGroup: the schedule of a fixed-rate task released by a timer interrupt, after F Prime's
// rate groups: it counts its own ticks and reports overruns as telemetry.
//
//   timer interrupt:  group.release();                 once per period
//   main loop:        if (group.begin(tick)) {          the latest released tick
//                       component.step(tick, ...);      (its members, once)
//                       group.end();                    overrun if a tick came meanwhile
//                     }
//
// The first release is tick 0. A cycle runs the latest released tick: ticks released while
// the previous cycle still ran are skipped (counted), and the component sees the gap in its
// tick count (it flags and bridges it). A tick released before the cycle ended is an overrun
// (F Prime's cycle slip): counted, and flagged for that cycle.
//
// release() is the only writer of the release count, a 32-bit atomic (lock-free and a single
// store on 32-bit cores); everything else belongs to the main loop. No heap, no exceptions.
#pragma once

#include <atomic>
#include <cstdint>
#include <limits>

namespace gyro {

struct RateGroupTelemetry {
  std::uint64_t released{};   // ticks released by the timer so far
  std::uint64_t cycles{};     // cycles run
  std::uint64_t last_tick{};  // the tick of the last cycle
  std::uint64_t skipped{};    // released ticks that never ran (a later one ran instead)
  std::uint32_t overruns{};   // cycles during which another tick was released
  bool overrun{false};        // the last cycle overran
};

class RateGroup {
 public:
  // Interrupt context: releases the next tick.
  void release() noexcept { releases_.store(releases_.load(std::memory_order_relaxed) + 1u, std::memory_order_release); }

  // A released tick awaits its cycle.
  [[nodiscard]] bool pending() const noexcept { return releases_.load(std::memory_order_acquire) != seen_; }

  // Starts the cycle of the latest released tick (its number in `tick`); false, and nothing
  // changed, when no tick was released since the last cycle began or a cycle is still open.
  [[nodiscard]] bool begin(std::uint64_t& tick) noexcept {
    const std::uint32_t now = releases_.load(std::memory_order_acquire);
    if (now == seen_ || in_cycle_) return false;
    telemetry_.released += static_cast<std::uint32_t>(now - seen_);  // modulo 2^32: wraps cleanly
    seen_ = now;
    const std::uint64_t latest = telemetry_.released - 1u;
    telemetry_.skipped += telemetry_.cycles == 0u ? latest : latest - telemetry_.last_tick - 1u;
    telemetry_.last_tick = latest;
    in_cycle_ = true;
    tick = latest;
    return true;
  }

  // Ends the cycle begun last; true when another tick was released while it ran (overrun).
  bool end() noexcept {
    if (!in_cycle_) return false;
    in_cycle_ = false;
    ++telemetry_.cycles;
    telemetry_.overrun = releases_.load(std::memory_order_acquire) != seen_;
    if (telemetry_.overrun && telemetry_.overruns != std::numeric_limits<std::uint32_t>::max()) ++telemetry_.overruns;
    return telemetry_.overrun;
  }

  [[nodiscard]] const RateGroupTelemetry& telemetry() const noexcept { return telemetry_; }

 private:
  std::atomic<std::uint32_t> releases_{0};
  std::uint32_t seen_{0};
  bool in_cycle_{false};
  RateGroupTelemetry telemetry_{};
};

}  // namespace gyro
