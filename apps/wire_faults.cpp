#include "wire_faults.hpp"

#include <cstddef>

#include "gyro/link/frame.hpp"
#include "printable.hpp"

namespace gyro::sil {

namespace {

constexpr std::size_t kNoiseBytes = 16;

std::uint64_t splitmix64(std::uint64_t x) noexcept {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30u)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27u)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31u);
}

}  // namespace

const char* wire_fault_name(WireFaultKind k) noexcept {
  switch (k) {
    case WireFaultKind::kCorruptCrc: return "crc";
    case WireFaultKind::kDrop: return "drop";
    case WireFaultKind::kDuplicate: return "duplicate";
    case WireFaultKind::kStall: return "stall";
    case WireFaultKind::kNoise: return "noise";
  }
  return "unknown";
}

std::optional<WireFault> parse_wire_fault(std::string_view text, std::string& error) {
  const std::size_t at = text.find('@');
  if (at == std::string_view::npos) {
    error = "expected KIND@TICK[+TICKS], e.g. crc@600+5";
    return std::nullopt;
  }
  const std::string_view name = text.substr(0, at);
  std::optional<WireFaultKind> kind;
  for (int i = 0; i < kWireFaultKindCount; ++i) {
    if (name == wire_fault_name(static_cast<WireFaultKind>(i))) kind = static_cast<WireFaultKind>(i);
  }
  if (!kind) {
    error = "unknown wire fault \"" + printable(name) + "\" (crc, drop, duplicate, stall, noise)";
    return std::nullopt;
  }
  const auto number = [](std::string_view s, std::uint64_t& out) {
    if (s.empty() || s.size() > 18) return false;
    out = 0;
    for (char c : s) {
      if (c < '0' || c > '9') return false;
      out = out * 10u + static_cast<std::uint64_t>(c - '0');
    }
    return true;
  };
  const std::string_view rest = text.substr(at + 1);
  const std::size_t plus = rest.find('+');
  WireFault f;
  f.kind = *kind;
  if (!number(rest.substr(0, plus), f.start_tick) ||
      (plus != std::string_view::npos && (!number(rest.substr(plus + 1), f.ticks) || f.ticks == 0u))) {
    error = "bad tick or tick count in \"" + printable(text) + "\" (KIND@TICK[+TICKS], TICKS >= 1)";
    return std::nullopt;
  }
  return f;
}

std::uint32_t active_wire_faults(const std::vector<WireFault>& faults, std::uint64_t tick) noexcept {
  std::uint32_t bits = 0;
  for (const WireFault& f : faults) {
    if (tick >= f.start_tick && tick - f.start_tick < f.ticks) bits |= 1u << static_cast<unsigned>(f.kind);
  }
  return bits;
}

std::vector<std::uint8_t> faulted_downlink(std::span<const std::uint8_t> frame, std::uint32_t faults,
                                           std::uint64_t tick) {
  std::vector<std::uint8_t> out;
  if (has_wire_fault(faults, WireFaultKind::kStall) || has_wire_fault(faults, WireFaultKind::kDrop)) return out;
  if (has_wire_fault(faults, WireFaultKind::kNoise)) {
    std::uint64_t r = splitmix64(tick);
    for (std::size_t i = 0; i < kNoiseBytes; ++i) {
      if (i % 8u == 0u && i != 0u) r = splitmix64(r);
      out.push_back(static_cast<std::uint8_t>((r >> (8u * (i % 8u))) & 0xFFu));
    }
  }
  const std::size_t start = out.size();
  out.insert(out.end(), frame.begin(), frame.end());
  if (has_wire_fault(faults, WireFaultKind::kCorruptCrc) && frame.size() > link::kFrameOverhead) {
    out[start + link::kHeaderBytes] ^= 0x01u;  // the first payload byte: the CRC no longer matches
  }
  if (has_wire_fault(faults, WireFaultKind::kDuplicate)) {
    const std::vector<std::uint8_t> copy(out.begin() + static_cast<std::ptrdiff_t>(start), out.end());
    out.insert(out.end(), copy.begin(), copy.end());
  }
  return out;
}

}  // namespace gyro::sil
