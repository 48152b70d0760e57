// ByteLink: the byte stream under a gyro::link channel (a UART, a FIFO filled by a UART's
// interrupt or DMA, a test's scripted bytes). Non-blocking both ways, so a caller in a
// fixed-rate tick never waits: it reads what has arrived and writes only what fits.
#pragma once

#include <cstddef>
#include <cstdint>

namespace gyro::link {

class ByteLink {
 public:
  // The next received byte, if one has arrived (true); false: nothing to read now.
  [[nodiscard]] virtual bool read_byte(std::uint8_t& out) noexcept = 0;
  // How many bytes write_byte() accepts now without refusing; a caller that needs a whole
  // frame sent checks this first.
  [[nodiscard]] virtual std::size_t write_room() const noexcept = 0;
  // Queues one byte for sending; false: no room, nothing queued.
  [[nodiscard]] virtual bool write_byte(std::uint8_t byte) noexcept = 0;

 protected:
  ByteLink() = default;
  ByteLink(const ByteLink&) = default;
  ByteLink(ByteLink&&) noexcept = default;
  ByteLink& operator=(const ByteLink&) = default;
  ByteLink& operator=(ByteLink&&) noexcept = default;
  ~ByteLink() = default;  // not deleted through the interface: no heap, no ownership
};

}  // namespace gyro::link
