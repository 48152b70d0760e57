// Driver of the Arm CMSDK APB UART (Cortex-M System Design Kit TRM, DDI0479C), the UART of
// the MPS2 FPGA images (AN386 Cortex-M4, AN500 Cortex-M7: UART0 at 0x40004000, as QEMU's
// mps2 machines model them). One byte of buffer each way, 8N1, no flow control:
//
//   +0x00 DATA       read: received byte (clears RX full); write: byte to send
//   +0x04 STATE      bit 0 TX full, bit 1 RX full, bit 2 TX overrun, bit 3 RX overrun (W1C)
//   +0x08 CTRL       bit 0 TX enable, bit 1 RX enable, bit 2 TX interrupt, bit 3 RX interrupt
//   +0x0C INTSTATUS  read: interrupt status; write 1 to clear (bit 0 TX, bit 1 RX)
//   +0x10 BAUDDIV    PCLK / baud rate, at least 16
//
// A ByteLink: read_byte() takes the received byte if there is one, write_byte() hands a byte
// to the transmitter if it is free; neither waits. The register block is passed in (the
// firmware maps it at its address; the host tests use one in RAM).
#pragma once

#include <cstddef>
#include <cstdint>

#include "gyro/link/byte_link.hpp"
#include "gyro/link/saturating_count.hpp"

namespace gyro::link {

struct CmsdkApbUartRegisters {
  std::uint32_t data;
  std::uint32_t state;
  std::uint32_t ctrl;
  std::uint32_t intstatus;
  std::uint32_t bauddiv;
};
static_assert(sizeof(CmsdkApbUartRegisters) == 0x14, "registers at +0x00 .. +0x10");

inline constexpr std::uintptr_t kMps2Uart0Base = 0x40004000u;

// final: destroyed as itself, never through ByteLink (whose destructor is protected).
class CmsdkApbUart final : public ByteLink {  // NOLINT(cppcoreguidelines-virtual-class-destructor)
 public:
  static constexpr std::uint32_t kTxFull = 1u << 0;
  static constexpr std::uint32_t kRxFull = 1u << 1;
  static constexpr std::uint32_t kTxOverrun = 1u << 2;
  static constexpr std::uint32_t kRxOverrun = 1u << 3;
  static constexpr std::uint32_t kTxEnable = 1u << 0;
  static constexpr std::uint32_t kRxEnable = 1u << 1;
  static constexpr std::uint32_t kRxInterruptEnable = 1u << 3;
  static constexpr std::uint32_t kRxInterrupt = 1u << 1;
  static constexpr std::uint32_t kMinBaudDivider = 16;

  explicit CmsdkApbUart(volatile CmsdkApbUartRegisters& registers) noexcept : regs_(registers) {}

  // Sets the baud rate (pclk_hz / baud, rounded to nearest) and enables both directions.
  // false: the divider would be below 16 (baud too high for the clock); nothing written.
  [[nodiscard]] bool enable(std::uint32_t pclk_hz, std::uint32_t baud) noexcept {
    if (baud == 0u) return false;
    const std::uint32_t divider = (pclk_hz + baud / 2u) / baud;
    if (divider < kMinBaudDivider) return false;
    regs_.bauddiv = divider;
    regs_.ctrl = kTxEnable | kRxEnable;
    return true;
  }

  [[nodiscard]] bool read_byte(std::uint8_t& out) noexcept override {
    const std::uint32_t state = regs_.state;
    if ((state & kRxOverrun) != 0u) {
      regs_.state = kRxOverrun;  // write one to clear; a byte was lost before this one
      rx_overruns_ = saturating_increment(rx_overruns_);
    }
    if ((state & kRxFull) == 0u) return false;
    out = static_cast<std::uint8_t>(regs_.data & 0xFFu);
    return true;
  }

  [[nodiscard]] std::size_t write_room() const noexcept override { return (regs_.state & kTxFull) != 0u ? 0u : 1u; }

  [[nodiscard]] bool write_byte(std::uint8_t byte) noexcept override {
    if ((regs_.state & kTxFull) != 0u) return false;
    regs_.data = byte;
    return true;
  }

  // The receive interrupt (for a processor that sleeps until a byte arrives): enabled or not,
  // and its pending status cleared.
  void set_rx_interrupt(bool enabled) noexcept {
    regs_.ctrl = kTxEnable | kRxEnable | (enabled ? kRxInterruptEnable : 0u);
  }
  void clear_rx_interrupt() noexcept { regs_.intstatus = kRxInterrupt; }

  // Bytes the receiver lost because the previous one had not been read (RX overrun).
  [[nodiscard]] std::uint32_t rx_overruns() const noexcept { return rx_overruns_; }

 private:
  volatile CmsdkApbUartRegisters& regs_;
  std::uint32_t rx_overruns_{0};
};

}  // namespace gyro::link
