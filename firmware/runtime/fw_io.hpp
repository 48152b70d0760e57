// Console output for the firmware images without stdio (printf would link newlib's
// malloc): text, integers and reals formatted into a fixed line buffer and written
// through semihosting. Reals are printed to 9 significant digits for diagnostics (the
// scaling is done in double, so the last digit can be off by one).
#pragma once

#include <cstddef>
#include <cstdint>

#include "semihosting.h"

namespace gyro_fw {

class Line {
 public:
  Line& operator<<(const char* s) noexcept {
    while (*s != '\0') put(*s++);
    return *this;
  }
  Line& operator<<(char c) noexcept {
    put(c);
    return *this;
  }
  Line& operator<<(long v) noexcept {
    if (v < 0) {
      put('-');
      return unsigned_decimal(0UL - static_cast<unsigned long>(v));
    }
    return unsigned_decimal(static_cast<unsigned long>(v));
  }
  Line& operator<<(int v) noexcept { return *this << static_cast<long>(v); }
  Line& operator<<(unsigned long v) noexcept { return unsigned_decimal(v); }
  Line& operator<<(unsigned v) noexcept { return unsigned_decimal(v); }
  Line& operator<<(double v) noexcept { return real(v, 9); }
  Line& operator<<(float v) noexcept { return real(static_cast<double>(v), 9); }

  // Writes the buffered text (the buffer is also flushed when full and at each '\n').
  void flush() noexcept {
    if (len_ == 0) return;
    buf_[len_] = '\0';
    gyro_fw_write0(buf_);
    len_ = 0;
  }
  ~Line() { flush(); }

  // d.dddddddde+XX with `digits` significant digits (1..17); nan, inf as words.
  Line& real(double v, int digits) noexcept {
    if (v != v) return *this << "nan";
    if (v < 0.0 || (v == 0.0 && 1.0 / v < 0.0)) {
      put('-');
      v = -v;
    }
    if (v > 1.7976931348623157e308) return *this << "inf";
    if (digits < 1) digits = 1;
    if (digits > 17) digits = 17;
    int exp10 = 0;
    if (v != 0.0) {
      while (v >= 10.0) {
        v /= 10.0;
        ++exp10;
      }
      while (v < 1.0) {
        v *= 10.0;
        --exp10;
      }
    }
    std::uint64_t limit = 1;  // 10^digits
    for (int i = 0; i < digits; ++i) limit *= 10U;
    std::uint64_t m = static_cast<std::uint64_t>(v * static_cast<double>(limit / 10U) + 0.5);
    if (m >= limit) {
      m /= 10U;
      ++exp10;
    }
    char d[20];
    for (int i = digits - 1; i >= 0; --i) {
      d[i] = static_cast<char>('0' + static_cast<int>(m % 10U));
      m /= 10U;
    }
    put(d[0]);
    if (digits > 1) put('.');
    for (int i = 1; i < digits; ++i) put(d[i]);
    put('e');
    put(exp10 < 0 ? '-' : '+');
    const int e = exp10 < 0 ? -exp10 : exp10;
    if (e >= 100) put(static_cast<char>('0' + e / 100));
    put(static_cast<char>('0' + (e / 10) % 10));
    put(static_cast<char>('0' + e % 10));
    return *this;
  }

 private:
  Line& unsigned_decimal(unsigned long v) noexcept {
    char d[24];
    int n = 0;
    do {
      d[n++] = static_cast<char>('0' + static_cast<int>(v % 10U));
      v /= 10U;
    } while (v != 0U);
    while (n > 0) put(d[--n]);
    return *this;
  }
  void put(char c) noexcept {
    buf_[len_++] = c;
    if (c == '\n' || len_ == kCapacity) flush();
  }

  static constexpr std::size_t kCapacity = 159;
  char buf_[kCapacity + 1]{};
  std::size_t len_ = 0;
};

}  // namespace gyro_fw
