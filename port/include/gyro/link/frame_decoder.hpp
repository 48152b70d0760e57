// FrameDecoder: bytes in, checked frames out. It trusts no byte: a frame is delivered only
// when its two sync bytes, a type the receiver knows in the real format it expects, the exact
// length that type defines and the CRC all agree. After any mismatch it drops one byte and
// hunts for the next sync pair within the bytes it already holds, so a frame that starts
// inside the remains of a truncated or corrupted one is still found.
//
// Messages (the receiver's message set) provides
//   static constexpr std::size_t kMaxPayload;                      // largest payload
//   static constexpr int payload_length(std::uint8_t type) noexcept;  // -1: not accepted
//
// Use: push() bytes while room() allows, then call next() until it returns false (or one byte
// at a time, each followed by next()). Bounded work: next() drops
// at least one byte per failed candidate and checks each candidate's CRC once (at most
// kMaxPayload + 7 bytes), so every byte costs at most one CRC of a full frame. No heap.
// Sequence numbers are reported, not judged: duplicates and gaps are the receiver's call.
#pragma once

#include <array>
#include <cstdint>

#include "gyro/link/crc16.hpp"
#include "gyro/link/frame.hpp"
#include "gyro/link/saturating_count.hpp"

namespace gyro::link {

struct DecoderCounters {
  std::uint32_t bytes{};          // bytes pushed
  std::uint32_t frames{};         // frames delivered
  std::uint32_t header_errors{};  // a sync pair followed by an unknown type or a wrong length
  std::uint32_t crc_errors{};     // complete candidates whose CRC did not match
  std::uint32_t bytes_skipped{};  // bytes dropped outside any delivered frame (noise, bad frames)
  std::uint32_t overflows{};      // bytes refused by push() because next() was not drained

  // Everything that was not a good frame (a receiver compares it before and after a read).
  [[nodiscard]] std::uint32_t faults() const noexcept {
    return header_errors + crc_errors + bytes_skipped + overflows;  // wraps harmlessly: only compared
  }
};

template <typename Messages>
class FrameDecoder {
 public:
  static constexpr std::size_t kMaxPayload = Messages::kMaxPayload;
  static constexpr std::size_t kCapacity = kMaxPayload + kFrameOverhead;
  using FrameType = Frame<kMaxPayload>;

  // Appends a byte. false: the window is full because next() was not drained; the byte is
  // dropped and counted.
  [[nodiscard]] bool push(std::uint8_t byte) noexcept {
    bump(counters_.bytes);
    if (end_ == kCapacity) compact();
    if (end_ == kCapacity) {
      bump(counters_.overflows);
      return false;
    }
    window_[end_++] = byte;
    return true;
  }

  // The next complete frame that passes every check; false when the bytes held do not (yet)
  // contain one.
  [[nodiscard]] bool next(FrameType& out) noexcept {
    if (end_ - begin_ < need_) return false;  // the candidate's header is checked: wait for the rest
    // Each pass either returns or drops at least one byte: kCapacity + 1 passes suffice.
    for (std::size_t pass = 0; pass <= kCapacity; ++pass) {
      const std::size_t held = end_ - begin_;
      if (held == 0) return false;
      if (window_[begin_] != kSync1) {
        skip(1);
        continue;
      }
      if (held < 2) return false;
      if (window_[begin_ + 1] != kSync2) {
        skip(1);
        continue;
      }
      if (held < kHeaderBytes) return false;
      const std::uint8_t type = window_[begin_ + 2];
      const std::uint8_t length = window_[begin_ + 4];
      const int expected = Messages::payload_length(type);
      if (expected < 0 || static_cast<int>(length) != expected || length > kMaxPayload) {
        bump(counters_.header_errors);
        skip(1);
        continue;
      }
      const std::size_t total = kFrameOverhead + length;
      if (held < total) {
        need_ = total;
        return false;
      }
      const std::uint16_t crc = crc16(window_, begin_ + 2, 3u + length);
      const std::size_t crc_at = begin_ + kHeaderBytes + length;
      const auto stored = static_cast<std::uint16_t>(window_[crc_at] | (window_[crc_at + 1] << 8u));
      if (crc != stored) {
        bump(counters_.crc_errors);
        skip(1);
        continue;
      }
      out.type = type;
      out.seq = window_[begin_ + 3];
      out.length = length;
      for (std::size_t i = 0; i < length; ++i) out.payload[i] = window_[begin_ + kHeaderBytes + i];
      begin_ += total;
      need_ = 0;
      bump(counters_.frames);
      return true;
    }
    return false;
  }

  // Forgets the bytes held (counted as skipped); the counters stay.
  void reset() noexcept { skip(end_ - begin_); }

  [[nodiscard]] std::size_t buffered() const noexcept { return end_ - begin_; }
  // Bytes push() takes before next() must run (a whole largest frame fits in the window).
  [[nodiscard]] std::size_t room() const noexcept { return kCapacity - (end_ - begin_); }
  [[nodiscard]] const DecoderCounters& counters() const noexcept { return counters_; }

 private:
  static void bump(std::uint32_t& c) noexcept { c = saturating_increment(c); }
  void skip(std::size_t n) noexcept {
    begin_ += n;
    need_ = 0;
    for (std::size_t i = 0; i < n; ++i) bump(counters_.bytes_skipped);
    if (begin_ == end_) begin_ = end_ = 0;
  }
  // Moves the held bytes to the front of the window.
  void compact() noexcept {
    const std::size_t held = end_ - begin_;
    for (std::size_t i = 0; i < held; ++i) window_[i] = window_[begin_ + i];
    begin_ = 0;
    end_ = held;
  }

  std::array<std::uint8_t, kCapacity> window_{};
  std::size_t begin_{0};
  std::size_t end_{0};
  std::size_t need_{0};  // bytes the candidate at begin_ needs (0: its header is not checked yet)
  DecoderCounters counters_{};
};

}  // namespace gyro::link
