// CRC-16/CCITT-FALSE (also catalogued as CRC-16/IBM-3740): polynomial 0x1021, initial value
// 0xFFFF, no reflection, no final XOR; check value 0x29B1 for the ASCII bytes "123456789".
// It detects every error of up to 3 bits, every odd number of bit errors and every burst of up
// to 16 bits in the frames of gyro::link (at most 262 bytes; Hamming distance 4 holds up to
// 32,751 bits). Table-driven: 512 bytes of constant table, one lookup per byte.
#pragma once

#include <array>
#include <cstdint>

namespace gyro::link {

inline constexpr std::uint16_t kCrc16Initial = 0xFFFFu;

namespace crc_detail {

[[nodiscard]] constexpr std::array<std::uint16_t, 256> make_crc16_table() noexcept {
  std::array<std::uint16_t, 256> table{};
  for (std::uint32_t byte = 0; byte < 256u; ++byte) {
    std::uint32_t crc = byte << 8u;
    for (int bit = 0; bit < 8; ++bit) {
      crc = ((crc & 0x8000u) != 0u) ? ((crc << 1u) ^ 0x1021u) : (crc << 1u);
    }
    table[byte] = static_cast<std::uint16_t>(crc & 0xFFFFu);
  }
  return table;
}

inline constexpr std::array<std::uint16_t, 256> kCrc16Table = make_crc16_table();

}  // namespace crc_detail

// The CRC after one more byte.
[[nodiscard]] constexpr std::uint16_t crc16_update(std::uint16_t crc, std::uint8_t byte) noexcept {
  const auto index = static_cast<std::uint8_t>((crc >> 8u) ^ byte);
  return static_cast<std::uint16_t>((crc << 8u) ^ crc_detail::kCrc16Table[index]);
}

// The CRC of bytes[first, first + count) of an array.
template <std::size_t N>
[[nodiscard]] constexpr std::uint16_t crc16(const std::array<std::uint8_t, N>& bytes, std::size_t first,
                                            std::size_t count) noexcept {
  std::uint16_t crc = kCrc16Initial;
  for (std::size_t i = first; i < first + count && i < N; ++i) crc = crc16_update(crc, bytes[i]);
  return crc;
}

}  // namespace gyro::link
