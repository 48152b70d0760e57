// The wire encoding of gyro::link payloads: little-endian integers, and reals as IEEE 754
// binary32 (float) or binary64 (double) bit patterns, little-endian, whatever the host's own
// byte order. WireWriter and WireReader work on a fixed array: a write or read past its end
// does nothing (a read gives 0) and turns ok() false, so a layout error shows up as a refused
// frame, never as a stray memory access.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <limits>

namespace gyro::link {

static_assert(std::numeric_limits<float>::is_iec559 && sizeof(float) == 4, "binary32 floats");
static_assert(std::numeric_limits<double>::is_iec559 && sizeof(double) == 8, "binary64 doubles");

template <std::size_t N>
class WireWriter {
 public:
  WireWriter(std::array<std::uint8_t, N>& buffer, std::size_t position) noexcept : buf_(buffer), pos_(position) {}

  void u8(std::uint8_t v) noexcept {
    if (pos_ >= N) {
      ok_ = false;
      return;
    }
    buf_[pos_++] = v;
  }
  void u16(std::uint16_t v) noexcept { unsigned_le(v, 2); }
  void u32(std::uint32_t v) noexcept { unsigned_le(v, 4); }
  void real(float v) noexcept {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    unsigned_le(bits, 4);
  }
  void real(double v) noexcept {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    unsigned_le(bits, 8);
  }

  [[nodiscard]] std::size_t position() const noexcept { return pos_; }
  [[nodiscard]] bool ok() const noexcept { return ok_; }

 private:
  void unsigned_le(std::uint64_t v, int bytes) noexcept {
    for (int i = 0; i < bytes; ++i) u8(static_cast<std::uint8_t>((v >> (8u * static_cast<unsigned>(i))) & 0xFFu));
  }

  std::array<std::uint8_t, N>& buf_;
  std::size_t pos_;
  bool ok_{true};
};

template <std::size_t N>
class WireReader {
 public:
  WireReader(const std::array<std::uint8_t, N>& buffer, std::size_t position) noexcept
      : buf_(buffer), pos_(position) {}

  [[nodiscard]] std::uint8_t u8() noexcept {
    if (pos_ >= N) {
      ok_ = false;
      return 0;
    }
    return buf_[pos_++];
  }
  [[nodiscard]] std::uint16_t u16() noexcept { return static_cast<std::uint16_t>(unsigned_le(2)); }
  [[nodiscard]] std::uint32_t u32() noexcept { return static_cast<std::uint32_t>(unsigned_le(4)); }
  // A real of the type asked for (float: binary32, double: binary64).
  template <typename T>
  [[nodiscard]] T real() noexcept {
    static_assert(sizeof(T) == 4 || sizeof(T) == 8, "binary32 or binary64");
    if constexpr (sizeof(T) == 4) {
      const auto bits = static_cast<std::uint32_t>(unsigned_le(4));
      T v{};
      std::memcpy(&v, &bits, sizeof v);
      return v;
    } else {
      const std::uint64_t bits = unsigned_le(8);
      T v{};
      std::memcpy(&v, &bits, sizeof v);
      return v;
    }
  }

  [[nodiscard]] std::size_t position() const noexcept { return pos_; }
  [[nodiscard]] bool ok() const noexcept { return ok_; }

 private:
  [[nodiscard]] std::uint64_t unsigned_le(int bytes) noexcept {
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= std::uint64_t{u8()} << (8u * static_cast<unsigned>(i));
    return v;
  }

  const std::array<std::uint8_t, N>& buf_;
  std::size_t pos_;
  bool ok_{true};
};

}  // namespace gyro::link
