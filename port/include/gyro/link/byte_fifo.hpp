// ByteFifo: a fixed-capacity first-in first-out byte queue (no heap). FifoLink: a ByteLink
// made of two of them, received bytes in one and bytes to send in the other; whatever moves
// bytes between the FIFOs and the wire (an interrupt handler, DMA, the processor-in-the-loop
// exchange, a test) uses the FIFOs directly.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "gyro/link/byte_link.hpp"

namespace gyro::link {

template <std::size_t N>
class ByteFifo {
 public:
  static_assert(N > 0, "a FIFO holds at least one byte");
  static constexpr std::size_t kCapacity = N;

  // Appends a byte; false (nothing stored) when full.
  [[nodiscard]] bool push(std::uint8_t byte) noexcept {
    if (count_ == N) return false;
    const std::size_t at = head_ + count_;
    bytes_[at < N ? at : at - N] = byte;
    ++count_;
    return true;
  }
  // Removes the oldest byte; false when empty.
  [[nodiscard]] bool pop(std::uint8_t& out) noexcept {
    if (count_ == 0) return false;
    out = bytes_[head_];
    head_ = head_ + 1 == N ? 0 : head_ + 1;
    --count_;
    return true;
  }
  void clear() noexcept { head_ = count_ = 0; }

  [[nodiscard]] std::size_t size() const noexcept { return count_; }
  [[nodiscard]] std::size_t room() const noexcept { return N - count_; }
  [[nodiscard]] bool empty() const noexcept { return count_ == 0; }

 private:
  std::array<std::uint8_t, N> bytes_{};
  std::size_t head_{0};
  std::size_t count_{0};
};

template <std::size_t kRxBytes, std::size_t kTxBytes>
class FifoLink final : public ByteLink {
 public:
  [[nodiscard]] bool read_byte(std::uint8_t& out) noexcept override { return rx_.pop(out); }
  [[nodiscard]] std::size_t write_room() const noexcept override { return tx_.room(); }
  [[nodiscard]] bool write_byte(std::uint8_t byte) noexcept override { return tx_.push(byte); }

  // The wire's side: bytes that arrived go into rx(), bytes to send come out of tx().
  [[nodiscard]] ByteFifo<kRxBytes>& rx() noexcept { return rx_; }
  [[nodiscard]] ByteFifo<kTxBytes>& tx() noexcept { return tx_; }

 private:
  ByteFifo<kRxBytes> rx_{};
  ByteFifo<kTxBytes> tx_{};
};

}  // namespace gyro::link
