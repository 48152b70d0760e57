// Shared pieces of the fuzz targets: a reader that turns the fuzz bytes into values, the
// invariant check, and bitwise comparison of Eigen coefficients.
//
// Each target defines LLVMFuzzerTestOneInput. Built with -fsanitize=fuzzer (clang) it is a
// libFuzzer executable; built with replay_main.cpp (any compiler, the host test build) it
// replays every file of the corpus and regression directories (see fuzz/README.md).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <type_traits>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace gyro::fuzz {

// An invariant of the code under test does not hold: report it and abort (libFuzzer saves
// the input as a crash; the replay test fails).
[[noreturn]] inline void violated(const char* what, const char* file, int line) noexcept {
  std::fprintf(stderr, "%s:%d: fuzz invariant violated: %s\n", file, line, what);
  std::fflush(stderr);
  std::abort();
}

#define GYRO_FUZZ_CHECK(cond)                                         \
  do {                                                                \
    if (!(cond)) ::gyro::fuzz::violated(#cond, __FILE__, __LINE__);  \
  } while (false)
#define GYRO_FUZZ_FAIL(what) ::gyro::fuzz::violated(what, __FILE__, __LINE__)

// Reads the fuzz bytes front to back. Past the end every read gives zero bytes, so a short
// input is a valid input (the rest defaults to zero) and exhausted() tells the caller to stop.
class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) noexcept : data_(data), size_(size) {}

  [[nodiscard]] bool exhausted() const noexcept { return pos_ >= size_; }
  [[nodiscard]] std::size_t remaining() const noexcept { return exhausted() ? 0u : size_ - pos_; }

  void copy(void* out, std::size_t n) noexcept {
    auto* o = static_cast<unsigned char*>(out);
    for (std::size_t i = 0; i < n; ++i) o[i] = pos_ + i < size_ ? data_[pos_ + i] : std::uint8_t{0};
    pos_ += n;
  }
  [[nodiscard]] std::uint8_t u8() noexcept { return take<std::uint8_t>(); }
  [[nodiscard]] std::uint16_t u16() noexcept { return take<std::uint16_t>(); }
  [[nodiscard]] std::uint32_t u32() noexcept { return take<std::uint32_t>(); }
  [[nodiscard]] std::uint64_t u64() noexcept { return take<std::uint64_t>(); }
  [[nodiscard]] bool flag() noexcept { return (u8() & 1u) != 0u; }

  // The raw bit pattern of a T: every NaN payload, infinities, denormals, the extremes.
  template <typename T>
  [[nodiscard]] T raw() noexcept {
    return take<T>();
  }

  // A value of the order of `scale`, chosen by a tag byte so that a few bytes reach both the
  // plausible and the pathological:
  //   0     zero                     1     special (NaN, +-inf, denormals, extremes, -0, ...)
  //   2, 3  scale * i16/32767        4, 5  +-scale * 2^(i8/4) * (1 + u8/256): 2^-32 .. 2^32
  //   6     scale * 1e-3 * i8/127    7     raw bit pattern (sizeof(T) bytes)
  template <typename T>
  [[nodiscard]] T value(T scale) noexcept {
    static_assert(std::is_floating_point_v<T>);
    const std::uint8_t tag = u8();
    switch (tag & 7u) {
      case 0: return T(0);
      case 1: return special<T>(u8());
      case 2:
      case 3: return scale * static_cast<T>(static_cast<std::int16_t>(u16())) / T(32767);
      case 4:
      case 5: {
        const T e = static_cast<T>(static_cast<std::int8_t>(u8())) / T(4);
        const T m = T(1) + static_cast<T>(u8()) / T(256);
        return ((tag & 8u) ? -scale : scale) * std::exp2(e) * m;
      }
      case 6: return scale * T(1e-3) * static_cast<T>(static_cast<std::int8_t>(u8())) / T(127);
      default: return raw<T>();
    }
  }

  template <typename T>
  [[nodiscard]] static T special(std::uint8_t i) noexcept {
    using L = std::numeric_limits<T>;
    const T table[] = {
        L::quiet_NaN(),  -L::quiet_NaN(), L::infinity(),    -L::infinity(),  L::denorm_min(),
        -L::denorm_min(), L::min(),       -L::min(),        L::max(),        -L::max(),
        L::epsilon(),     T(-0.0),        T(1),             T(-1),           T(1e-30),
        T(1e30),          L::min() / T(3), T(0.5),          T(2),            L::signaling_NaN(),
        T(1e-7),          T(1e7),         L::max() / T(2),  T(3.14159265358979323846),
    };
    return table[i % (sizeof(table) / sizeof(table[0]))];
  }

 private:
  template <typename U>
  [[nodiscard]] U take() noexcept {
    U v;
    unsigned char b[sizeof(U)];
    copy(b, sizeof(U));
    std::memcpy(&v, b, sizeof(U));
    return v;
  }

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_{0};
};

// Bit-for-bit equality of the coefficients of Eigen objects (never of padded structs).
template <typename A>
[[nodiscard]] bool same_bits(const A& a, const A& b) noexcept {
  return std::memcmp(a.data(), b.data(), sizeof(a.data()[0]) * static_cast<std::size_t>(a.size())) == 0;
}
template <typename T>
[[nodiscard]] bool same_scalar_bits(T a, T b) noexcept {
  static_assert(std::is_arithmetic_v<T>);
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

template <typename A>
[[nodiscard]] bool finite_coeffs(const A& a) noexcept {
  for (int i = 0; i < static_cast<int>(a.size()); ++i) {
    if (!std::isfinite(a.data()[i])) return false;
  }
  return true;
}

}  // namespace gyro::fuzz
