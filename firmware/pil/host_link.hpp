// The serial line to the PIL host in the target's frozen time (tick_timer.hpp): whole frames
// and raw bytes over the CMSDK UART, waiting as long as the host takes. While it waits for a
// byte the core sleeps (WFI with interrupts masked, woken by the UART's receive interrupt,
// which is never taken), so QEMU's virtual clock and the paused timer stand still.
#pragma once

#include <array>
#include <cstdint>

#include "cortex_m.hpp"
#include "gyro/link/cmsdk_apb_uart.hpp"
#include "gyro/pil/harness.hpp"

namespace gyro_fw {

// MPS2 AN386/AN500: UART0's receive interrupt is external interrupt 0 (its transmit one is 1).
inline constexpr unsigned kUart0RxIrq = 0;

template <typename T>
class HostLink {
 public:
  explicit HostLink(gyro::link::CmsdkApbUart& uart) noexcept : uart_(uart) {}

  void send_byte(std::uint8_t b) noexcept {
    while (!uart_.write_byte(b)) {
    }
  }

  void send(const gyro::pil::HarnessFrame<T>& f) noexcept {
    std::array<std::uint8_t, gyro::pil::kHarnessFrameBytes<T>> bytes{};
    const std::size_t n = gyro::link::encode_frame(f, bytes);
    for (std::size_t i = 0; i < n; ++i) send_byte(bytes[i]);
    ++seq_;
  }

  // The next byte from the host (sleeps until it comes).
  [[nodiscard]] std::uint8_t receive_byte() noexcept {
    std::uint8_t b = 0;
    if (uart_.read_byte(b)) return b;
    disable_interrupts();
    uart_.set_rx_interrupt(true);
    nvic_enable(kUart0RxIrq);
    while (!uart_.read_byte(b)) {
      wait_for_interrupt();
      uart_.clear_rx_interrupt();
      nvic_clear_pending(kUart0RxIrq);
    }
    uart_.set_rx_interrupt(false);
    uart_.clear_rx_interrupt();
    nvic_disable(kUart0RxIrq);
    nvic_clear_pending(kUart0RxIrq);
    enable_interrupts();
    return b;
  }

  // The next harness frame; false if bytes that are not a good frame arrived first (the
  // harness link is not faulted on purpose: that is a broken run).
  [[nodiscard]] bool receive(gyro::pil::HarnessFrame<T>& out) noexcept {
    const std::uint32_t faults = decoder_.counters().faults();
    for (;;) {
      (void)decoder_.push(receive_byte());
      if (decoder_.next(out)) return true;
      if (decoder_.counters().faults() != faults) return false;
    }
  }

  [[nodiscard]] std::uint8_t seq() const noexcept { return seq_; }

 private:
  gyro::link::CmsdkApbUart& uart_;
  gyro::pil::HarnessDecoder<T> decoder_{};
  std::uint8_t seq_{0};
};

}  // namespace gyro_fw
