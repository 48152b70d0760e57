// Fuzz target: the frame decoder of gyro::link on arbitrary bytes, with the message set of
// the gyro link or of the PIL harness (float or double reals), and LinkGyroPort reading the
// same bytes as they arrive in chunks.
//
// Input: byte 0 (bits 0-1: 0 gyro link float, 1 gyro link double, 2 harness float, 3 harness
// double; bits 2-7: the chunk in which bytes reach the port, 1 .. 64); then the bytes on the wire.
//
// Invariants:
//   - every delivered frame is one the receiver accepts (type, real format, exact length), its
//     CRC matches, and its encoding occurs verbatim in the input;
//   - every byte is accounted for: bytes pushed = bytes of delivered frames + bytes skipped +
//     bytes still held (less than one frame); next() drained after each push never overflows;
//   - a frame a message decoder accepts encodes back to the same payload bytes (no value is
//     altered or invented on the way in);
//   - the port's answer agrees with its counters (kOk: one more reading; kTimeout, kBusError:
//     one more of those; nothing else answered, nothing written but on kOk), a kOk reading is
//     bit for bit one the decoder saw in a pickoff frame, and every frame the port's own
//     decoder delivered is accounted for once (reading, superseded, duplicate, malformed or
//     unexpected).
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "fuzz_support.hpp"
#include "gyro/link/byte_fifo.hpp"
#include "gyro/link/frame_decoder.hpp"
#include "gyro/link/gyro_link_messages.hpp"
#include "gyro/link/link_gyro_port.hpp"
#include "gyro/pil/harness.hpp"

namespace {

using gyro::PortStatus;

template <typename Messages>
std::vector<std::uint8_t> encoded(const gyro::link::Frame<Messages::kMaxPayload>& f) {
  std::array<std::uint8_t, Messages::kMaxPayload + gyro::link::kFrameOverhead> buf{};
  const std::size_t n = gyro::link::encode_frame(f, buf);
  GYRO_FUZZ_CHECK(n == gyro::link::kFrameOverhead + f.length);
  return std::vector<std::uint8_t>(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
}

template <std::size_t N>
bool same_payload(const gyro::link::Frame<N>& a, const gyro::link::Frame<N>& b) {
  return a.length == b.length && std::equal(a.payload.begin(), a.payload.begin() + a.length, b.payload.begin());
}

// Decode then encode: the same payload, or the decoder refused.
template <typename T>
void check_gyro_link_identity(const gyro::link::GyroLinkFrame<T>& f) {
  gyro::PickoffReading<T> r;
  if (gyro::link::decode_pickoff(f, r)) {
    GYRO_FUZZ_CHECK(same_payload(gyro::link::encode_pickoff(r, f.seq), f));
  }
  Eigen::Matrix<T, 2, 1> t;
  if (gyro::link::decode_torque(f, t)) {
    GYRO_FUZZ_CHECK(same_payload(gyro::link::encode_torque(t, f.seq), f));
  }
}

template <typename T>
void check_harness_identity(const gyro::pil::HarnessFrame<T>& f) {
  namespace pil = gyro::pil;
  pil::Hello hello;
  if (pil::decode_hello<T>(f, hello)) GYRO_FUZZ_CHECK(same_payload(pil::encode_hello<T>(hello, f.seq), f));
  pil::Config<T> config;
  if (pil::decode_config(f, config)) GYRO_FUZZ_CHECK(same_payload(pil::encode_config(config, f.seq), f));
  pil::ConfigAck ack;
  if (pil::decode_config_ack<T>(f, ack)) GYRO_FUZZ_CHECK(same_payload(pil::encode_config_ack<T>(ack, f.seq), f));
  pil::TickIn<T> in;
  if (pil::decode_tick_in(f, in)) GYRO_FUZZ_CHECK(same_payload(pil::encode_tick_in(in, f.seq), f));
  pil::TickOut out;
  if (pil::decode_tick_out<T>(f, out)) GYRO_FUZZ_CHECK(same_payload(pil::encode_tick_out<T>(out, f.seq), f));
  gyro::GyroTelemetry<T> tm;
  if (pil::decode_telemetry(f, tm)) {
    // The tick travels as its low 32 bits: decoded, it is exactly those.
    GYRO_FUZZ_CHECK(same_payload(pil::encode_telemetry(tm, f.seq), f));
  }
}

// The decoder alone, byte by byte; returns the delivered frames.
template <typename Messages, typename Check>
std::vector<gyro::link::Frame<Messages::kMaxPayload>> decode_all(const std::vector<std::uint8_t>& wire, Check&& check) {
  gyro::link::FrameDecoder<Messages> d;
  std::vector<gyro::link::Frame<Messages::kMaxPayload>> frames;
  std::size_t frame_bytes = 0;
  for (std::uint8_t b : wire) {
    GYRO_FUZZ_CHECK(d.push(b));
    for (gyro::link::Frame<Messages::kMaxPayload> f; d.next(f);) {
      GYRO_FUZZ_CHECK(Messages::payload_length(f.type) == static_cast<int>(f.length));
      const std::vector<std::uint8_t> bytes = encoded<Messages>(f);
      GYRO_FUZZ_CHECK(std::search(wire.begin(), wire.end(), bytes.begin(), bytes.end()) != wire.end());
      frame_bytes += bytes.size();
      check(f);
      frames.push_back(f);
    }
    GYRO_FUZZ_CHECK(d.buffered() < gyro::link::FrameDecoder<Messages>::kCapacity);
  }
  const gyro::link::DecoderCounters& c = d.counters();
  GYRO_FUZZ_CHECK(c.overflows == 0u);
  GYRO_FUZZ_CHECK(c.frames == frames.size());
  GYRO_FUZZ_CHECK(c.bytes == wire.size());
  GYRO_FUZZ_CHECK(c.bytes == frame_bytes + c.bytes_skipped + d.buffered());
  return frames;
}

template <typename T>
void gyro_link(const std::vector<std::uint8_t>& wire, std::size_t chunk) {
  using Frame = gyro::link::GyroLinkFrame<T>;
  const std::vector<Frame> frames =
      decode_all<gyro::link::GyroLinkMessages<T>>(wire, [](const Frame& f) { check_gyro_link_identity<T>(f); });
  std::vector<gyro::PickoffReading<T>> seen;
  for (const Frame& f : frames) {
    gyro::PickoffReading<T> r;
    if (gyro::link::decode_pickoff(f, r)) seen.push_back(r);
  }

  gyro::link::FifoLink<512, 64> link;
  gyro::LinkGyroPort<T> port(link);
  for (std::size_t at = 0; at < wire.size() + chunk; at += chunk) {
    for (std::size_t i = at; i < std::min(wire.size(), at + chunk); ++i) GYRO_FUZZ_CHECK(link.rx().push(wire[i]));
    const gyro::LinkPortCounters before = port.counters();
    gyro::PickoffReading<T> r;
    r.sequence = 0xDEADBEEFu;
    const PortStatus st = port.read_pickoffs(r);
    const gyro::LinkPortCounters& after = port.counters();
    switch (st) {
      case PortStatus::kOk: {
        GYRO_FUZZ_CHECK(after.readings == before.readings + 1u);
        const bool from_a_frame = std::any_of(seen.begin(), seen.end(), [&r](const gyro::PickoffReading<T>& s) {
          return s.sequence == r.sequence && s.valid == r.valid && s.spin_valid == r.spin_valid &&
                 std::memcmp(&s.spin_hz, &r.spin_hz, sizeof(T)) == 0 &&
                 std::memcmp(s.gimbal_angle_rad.data(), r.gimbal_angle_rad.data(), 2 * sizeof(T)) == 0;
        });
        GYRO_FUZZ_CHECK(from_a_frame);
        break;
      }
      case PortStatus::kTimeout:
        GYRO_FUZZ_CHECK(after.timeouts == before.timeouts + 1u && r.sequence == 0xDEADBEEFu);
        break;
      case PortStatus::kBusError:
        GYRO_FUZZ_CHECK(after.bus_errors == before.bus_errors + 1u && r.sequence == 0xDEADBEEFu);
        break;
      default: GYRO_FUZZ_FAIL("read_pickoffs answered neither kOk, kTimeout nor kBusError");
    }
  }
  const gyro::LinkPortCounters& c = port.counters();
  GYRO_FUZZ_CHECK(port.decoder_counters().frames == frames.size());
  GYRO_FUZZ_CHECK(c.readings + c.superseded + c.duplicates + c.malformed + c.unexpected == frames.size());
}

template <typename T>
void harness(const std::vector<std::uint8_t>& wire) {
  (void)decode_all<gyro::pil::HarnessMessages<T>>(
      wire, [](const gyro::pil::HarnessFrame<T>& f) { check_harness_identity<T>(f); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t head = data[0];
  const std::vector<std::uint8_t> wire(data + 1, data + size);
  const std::size_t chunk = 1u + (head >> 2u);
  switch (head & 3u) {
    case 0: gyro_link<float>(wire, chunk); break;
    case 1: gyro_link<double>(wire, chunk); break;
    case 2: harness<float>(wire); break;
    default: harness<double>(wire); break;
  }
  return 0;
}
