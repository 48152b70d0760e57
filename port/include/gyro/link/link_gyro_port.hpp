// LinkGyroPort: the gyro port over a byte link (a serial line to the gyro electronics), with
// the frames of gyro/link/gyro_link_messages.hpp. The electronics send one pickoff frame per
// conversion; the flight computer sends one torque frame per command.
//
// read_pickoffs() reads what has arrived since the last call (at most kMaxBytesPerRead bytes:
// bounded work per tick) and returns
//   kOk        a new pickoff frame arrived: the newest one (older ones of the same read are
//              superseded, a repeat of the last sequence number is a duplicate and ignored);
//   kBusError  bytes arrived but no good frame among them (CRC, framing, bad length or
//              type, reserved bits): the transfer failed;
//   kTimeout   nothing new arrived (silence, only duplicates, or a frame still incomplete).
// Sequence gaps are counted as lost frames. write_torquer() queues a whole torque frame or
// nothing (kBusError: non-finite command, or no room on the link).
//
// No heap, no exceptions; never trusts a byte (see FrameDecoder); the counters say what the
// link did, for telemetry.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "gyro/gyro_port.hpp"
#include "gyro/link/byte_link.hpp"
#include "gyro/link/frame_decoder.hpp"
#include "gyro/link/gyro_link_messages.hpp"
#include "gyro/link/saturating_count.hpp"

namespace gyro {

struct LinkPortCounters {
  std::uint32_t readings{};        // pickoff frames handed to the caller
  std::uint32_t duplicates{};      // frames repeating the last sequence number: ignored
  std::uint32_t frames_lost{};     // sequence numbers skipped: frames that never arrived
  std::uint32_t superseded{};      // older frames of a read that held several
  std::uint32_t malformed{};       // checked frames with reserved bits set
  std::uint32_t unexpected{};      // good frames of another message type
  std::uint32_t timeouts{};        // reads that returned kTimeout
  std::uint32_t bus_errors{};      // reads that returned kBusError
  std::uint32_t torque_frames{};   // torque commands queued
  std::uint32_t torque_refused{};  // torque commands refused (kBusError)
};

// kMaxBytesPerRead bounds a read's work. It must be at least the bytes the line can deliver
// in a tick (its bits per second / 10 bits a byte / ticks per second, rounded up: frames and
// noise alike), and the receive buffer must hold that much: a port that reads less falls
// behind, and once its buffer is full the frames are lost. The default, 4 frames, suits a line
// that carries a frame or two a tick; the PIL image's line carries up to 255 bytes a tick and
// its port reads 256 (gyro/pil/harness.hpp).
template <typename T, std::size_t kMaxBytesPerRead = 4 * link::kGyroLinkFrameBytes<T>>
class LinkGyroPort final : public GyroPort<T> {
 public:
  using Decoder = link::FrameDecoder<link::GyroLinkMessages<T>>;

  explicit LinkGyroPort(link::ByteLink& byte_link) noexcept : link_(byte_link) {}

  [[nodiscard]] PortStatus read_pickoffs(PickoffReading<T>& out) noexcept override {
    const std::uint32_t faults_before = decoder_.counters().faults() + counters_.malformed;
    Read read;
    // Bytes in batches of what the decoder's window takes, each batch drained of its frames.
    std::uint8_t byte = 0;
    std::size_t taken = 0;
    for (std::size_t batch = 0; batch <= kMaxBytesPerRead && taken < kMaxBytesPerRead; ++batch) {
      const std::size_t room = decoder_.room();
      std::size_t n = 0;
      for (; n < room && taken + n < kMaxBytesPerRead && link_.read_byte(byte); ++n) (void)decoder_.push(byte);
      taken += n;
      for (std::size_t f = 0; f <= Decoder::kCapacity && decoder_.next(frame_); ++f) take(frame_, read);
      if (n < room) break;  // the link has nothing more (or the read's budget is spent)
    }
    if (read.fresh) {
      bump(counters_.readings);
      out = read.newest;
      return PortStatus::kOk;
    }
    if (decoder_.counters().faults() + counters_.malformed != faults_before) {
      bump(counters_.bus_errors);
      return PortStatus::kBusError;
    }
    bump(counters_.timeouts);
    return PortStatus::kTimeout;
  }

  [[nodiscard]] PortStatus write_torquer(const Eigen::Matrix<T, 2, 1>& torque) noexcept override {
    if (!std::isfinite(torque(0)) || !std::isfinite(torque(1))) return refuse_torque();
    std::array<std::uint8_t, link::kGyroLinkFrameBytes<T>> bytes{};
    const std::size_t n = link::encode_frame(link::encode_torque(torque, tx_seq_), bytes);
    if (n == 0 || link_.write_room() < n) return refuse_torque();
    for (std::size_t i = 0; i < n; ++i) (void)link_.write_byte(bytes[i]);  // room checked above
    ++tx_seq_;
    bump(counters_.torque_frames);
    return PortStatus::kOk;
  }

  [[nodiscard]] const LinkPortCounters& counters() const noexcept { return counters_; }
  [[nodiscard]] const link::DecoderCounters& decoder_counters() const noexcept { return decoder_.counters(); }

 private:
  struct Read {
    bool fresh{false};
    PickoffReading<T> newest{};
  };

  static void bump(std::uint32_t& c) noexcept { c = link::saturating_increment(c); }

  [[nodiscard]] PortStatus refuse_torque() noexcept {
    bump(counters_.torque_refused);
    return PortStatus::kBusError;
  }

  // One checked frame: judged by type, sequence number and content.
  void take(const typename Decoder::FrameType& f, Read& read) noexcept {
    if (f.type != link::frame_type<T>(link::kPickoffMessage)) {
      bump(counters_.unexpected);
      return;
    }
    if (have_seq_ && f.seq == last_seq_) {
      bump(counters_.duplicates);
      return;
    }
    PickoffReading<T> r;
    if (!link::decode_pickoff(f, r)) {
      bump(counters_.malformed);
      return;
    }
    if (have_seq_) {
      const auto gap = static_cast<std::uint8_t>(f.seq - last_seq_ - 1u);
      for (std::uint8_t g = 0; g < gap; ++g) bump(counters_.frames_lost);
    }
    last_seq_ = f.seq;
    have_seq_ = true;
    if (read.fresh) bump(counters_.superseded);
    read.newest = r;
    read.fresh = true;
  }

  link::ByteLink& link_;
  Decoder decoder_{};
  typename Decoder::FrameType frame_{};
  LinkPortCounters counters_{};
  std::uint8_t last_seq_{0};
  bool have_seq_{false};
  std::uint8_t tx_seq_{0};
};

}  // namespace gyro
