// What gyro_sil --pil needs to run the flight component on an emulated target (docs/pil.md):
// the serial socket, how to start QEMU, the timer period, the wire faults to inject; and what
// the run measured.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "gyro/link/frame_decoder.hpp"
#include "gyro/pil/harness.hpp"
#include "wire_faults.hpp"

namespace gyro::sil {

struct PilOptions {
  std::string socket;                    // UNIX socket of QEMU's serial chardev (server side)
  std::string firmware;                  // start QEMU with this image; empty: attach to a running one
  std::string machine{"mps2-an386"};     // QEMU machine (mps2-an500 for the Cortex-M7 image)
  std::string qemu{"qemu-system-arm"};
  std::optional<std::uint32_t> tick_clocks;  // timer period in target clocks (default: the tick)
  std::vector<WireFault> faults;
  double timeout_s{30};                  // silence from the target before the run is given up
  bool target_console{true};             // QEMU's console (the target's summary) to stderr
};

struct PilSummary {
  std::uint8_t target_real_bytes{};      // 4: float, 8: double
  std::uint32_t timer_hz{};              // the target's timer clock
  std::uint32_t tick_clocks{};           // timer period used
  std::uint64_t cycles{};                // ticks the target ran
  std::uint64_t skipped{};               // ticks it skipped after overruns
  std::uint32_t overruns{};
  std::uint64_t step_clocks_total{};
  std::uint64_t step_clocks_worst{};
  std::uint64_t worst_tick{};
  double exchange_wall_s{};              // wall time from the first tick to the stop
  pil::TickOut last_report{};            // the target's counters at its last report
  link::DecoderCounters uplink{};        // the host's decoder of the torque frames
  std::uint64_t torque_commands{};       // torque frames the host applied to the stub
  int qemu_exit{-1};                     // QEMU's exit status when gyro_sil started it

  // Target instructions per timer clock: QEMU's -icount shift=0 runs one instruction per
  // nanosecond of virtual time.
  [[nodiscard]] double instructions_per_clock() const noexcept {
    return timer_hz == 0u ? 0.0 : 1e9 / static_cast<double>(timer_hz);
  }
};

}  // namespace gyro::sil
