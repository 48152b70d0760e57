// Faults the processor-in-the-loop host injects on the gyro link (docs/pil.md, "Wire
// faults"): their command-line form, the ticks they hit, and what the electronics' frame of a
// tick becomes on the wire under them.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace gyro::sil {

// Faults injected by the host on the gyro link, for the ticks [start_tick, start_tick + ticks):
//   crc        the pickoff frame is sent with one payload bit flipped (its CRC no longer matches)
//   drop       the pickoff frame is not sent
//   duplicate  the pickoff frame is sent twice
//   stall      nothing crosses the link either way (the torque frames are lost too)
//   noise      16 bytes of noise precede the pickoff frame
enum class WireFaultKind : std::uint8_t { kCorruptCrc, kDrop, kDuplicate, kStall, kNoise };
inline constexpr int kWireFaultKindCount = 5;

[[nodiscard]] const char* wire_fault_name(WireFaultKind k) noexcept;

struct WireFault {
  WireFaultKind kind{WireFaultKind::kDrop};
  std::uint64_t start_tick{0};
  std::uint64_t ticks{1};
};

// "KIND@TICK" or "KIND@TICK+TICKS" (e.g. "crc@600+5"); nullopt with `error` set otherwise.
[[nodiscard]] std::optional<WireFault> parse_wire_fault(std::string_view text, std::string& error);

// Whether `kind` is among the active faults `faults` (bit 1 << kind).
[[nodiscard]] constexpr bool has_wire_fault(std::uint32_t faults, WireFaultKind kind) noexcept {
  return (faults & (1u << static_cast<unsigned>(kind))) != 0u;
}

// The wire faults active at `tick`: bit (1 << kind) for each.
[[nodiscard]] std::uint32_t active_wire_faults(const std::vector<WireFault>& faults, std::uint64_t tick) noexcept;

// What the electronics' encoded frame becomes on the wire at `tick` under the active faults
// (stall > drop > the others; noise first, then the frame, corrupted or twice).
[[nodiscard]] std::vector<std::uint8_t> faulted_downlink(std::span<const std::uint8_t> frame, std::uint32_t faults,
                                                         std::uint64_t tick);

}  // namespace gyro::sil
