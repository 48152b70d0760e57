// The frame of gyro::link (docs/pil-protocol.md): fixed size for each message type,
//
//   offset  0     1     2     3    4    5 .. 4+L    5+L  6+L
//           0xA5  0x5A  type  seq  L    payload     CRC (little-endian)
//
// type: bits 0-6 the message id, bit 7 the real format of the payload (1: binary64, 0:
// binary32); seq: +1 per frame sent on a channel (wraps); L: the payload length, which must be
// the one the message id and real format define; CRC: CRC-16/CCITT-FALSE of type, seq, L and
// the payload. 7 bytes of overhead, at most 255 of payload.
#pragma once

#include <array>
#include <cstdint>

#include "gyro/link/crc16.hpp"

namespace gyro::link {

inline constexpr std::uint8_t kSync1 = 0xA5u;
inline constexpr std::uint8_t kSync2 = 0x5Au;
inline constexpr std::size_t kHeaderBytes = 5;  // sync, sync, type, seq, length
inline constexpr std::size_t kCrcBytes = 2;
inline constexpr std::size_t kFrameOverhead = kHeaderBytes + kCrcBytes;
inline constexpr std::size_t kMaxPayloadBytes = 255;
inline constexpr std::uint8_t kBinary64Bit = 0x80u;
inline constexpr std::uint8_t kMessageIdMask = 0x7Fu;

// The type byte of message `id` with reals of type T.
template <typename T>
[[nodiscard]] constexpr std::uint8_t frame_type(std::uint8_t id) noexcept {
  static_assert(sizeof(T) == 4 || sizeof(T) == 8, "binary32 or binary64 reals");
  const auto base = static_cast<std::uint8_t>(id & kMessageIdMask);
  return sizeof(T) == 8 ? static_cast<std::uint8_t>(base | kBinary64Bit) : base;
}
[[nodiscard]] constexpr std::uint8_t message_id(std::uint8_t type) noexcept {
  return static_cast<std::uint8_t>(type & kMessageIdMask);
}
// Bytes per real of the type byte's format.
[[nodiscard]] constexpr std::size_t real_bytes(std::uint8_t type) noexcept {
  return (type & kBinary64Bit) != 0u ? 8u : 4u;
}

template <std::size_t kMaxPayload>
struct Frame {
  static_assert(kMaxPayload <= kMaxPayloadBytes, "the length field is one byte");
  std::uint8_t type{};
  std::uint8_t seq{};
  std::uint8_t length{};
  std::array<std::uint8_t, kMaxPayload> payload{};
};

// Writes the frame to out[0, kFrameOverhead + length) and returns that size; 0 (nothing
// written) if the length exceeds the payload array or `out`.
template <std::size_t kMaxPayload, std::size_t N>
[[nodiscard]] constexpr std::size_t encode_frame(const Frame<kMaxPayload>& f, std::array<std::uint8_t, N>& out) noexcept {
  const std::size_t total = kFrameOverhead + f.length;
  if (f.length > kMaxPayload || total > N) return 0;
  out[0] = kSync1;
  out[1] = kSync2;
  out[2] = f.type;
  out[3] = f.seq;
  out[4] = f.length;
  for (std::size_t i = 0; i < f.length; ++i) out[kHeaderBytes + i] = f.payload[i];
  const std::uint16_t crc = crc16(out, 2, 3u + f.length);
  out[kHeaderBytes + f.length] = static_cast<std::uint8_t>(crc & 0xFFu);
  out[kHeaderBytes + f.length + 1] = static_cast<std::uint8_t>(crc >> 8u);
  return total;
}

}  // namespace gyro::link
