// gyro::link frames: the CRC against its catalogue check value, the wire encoding byte by
// byte, and the decoder against noise, truncation, corruption (every single-bit error of a
// frame), wrong lengths and types, and a window it is not allowed to overrun.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "gyro/link/crc16.hpp"
#include "gyro/link/frame.hpp"
#include "gyro/link/frame_decoder.hpp"
#include "gyro/link/gyro_link_messages.hpp"
#include "gyro/link/wire.hpp"
#include "support/requirements.hpp"

namespace gyro::link {
namespace {

template <typename T>
using Decoder = FrameDecoder<GyroLinkMessages<T>>;

template <typename T>
PickoffReading<T> sample_reading() {
  PickoffReading<T> r;
  r.gimbal_angle_rad = Eigen::Matrix<T, 2, 1>(T(0.125), T(-0.0625));
  r.sequence = 0x01020304u;
  r.valid = true;
  r.spin_valid = true;
  r.spin_hz = T(400.5);
  return r;
}

template <typename T>
std::vector<std::uint8_t> bytes_of(const GyroLinkFrame<T>& f) {
  std::array<std::uint8_t, kGyroLinkFrameBytes<T>> buf{};
  const std::size_t n = encode_frame(f, buf);
  return std::vector<std::uint8_t>(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
}

// Feeds bytes, collecting every frame the decoder delivers.
template <typename T>
std::vector<GyroLinkFrame<T>> feed(Decoder<T>& d, const std::vector<std::uint8_t>& bytes) {
  std::vector<GyroLinkFrame<T>> out;
  for (std::uint8_t b : bytes) {
    EXPECT_TRUE(d.push(b));
    for (GyroLinkFrame<T> f; d.next(f);) out.push_back(f);
  }
  return out;
}

TEST(LinkCrc, GivenTheCatalogueCheckStringThenItsCheckValue) {
  GYRO_VERIFIES("LINK-1");
  const char* text = "123456789";
  std::array<std::uint8_t, 9> bytes{};
  std::memcpy(bytes.data(), text, 9);
  EXPECT_EQ(crc16(bytes, 0, 9), 0x29B1u);  // CRC-16/CCITT-FALSE (IBM-3740)
  EXPECT_EQ(crc16(bytes, 0, 0), kCrc16Initial);
}

TEST(LinkWire, GivenKnownValuesThenLittleEndianIeeeBytes) {
  GYRO_VERIFIES("LINK-2");
  std::array<std::uint8_t, 19> buf{};
  WireWriter w(buf, 0);
  w.u16(0x1234u);
  w.u32(0xA1B2C3D4u);
  w.real(1.0f);   // 0x3F800000
  w.real(-2.0);   // 0xC000000000000000
  w.u8(0x7Fu);
  ASSERT_TRUE(w.ok());
  const std::array<std::uint8_t, 19> expected = {0x34, 0x12, 0xD4, 0xC3, 0xB2, 0xA1, 0x00, 0x00, 0x80, 0x3F,
                                                 0,    0,    0,    0,    0,    0,    0,    0xC0, 0x7F};
  EXPECT_EQ(buf, expected);
  WireReader r(buf, 0);
  EXPECT_EQ(r.u16(), 0x1234u);
  EXPECT_EQ(r.u32(), 0xA1B2C3D4u);
  EXPECT_EQ(r.real<float>(), 1.0f);
  EXPECT_EQ(r.real<double>(), -2.0);
  EXPECT_EQ(r.u8(), 0x7Fu);
  EXPECT_TRUE(r.ok());
  // Past the end: nothing read or written, and it says so.
  EXPECT_EQ(r.u8(), 0u);
  EXPECT_FALSE(r.ok());
  w.u8(1);
  EXPECT_FALSE(w.ok());
}

TEST(LinkFrame, GivenAPickoffFrameThenTheDocumentedLayout) {
  GYRO_VERIFIES("LINK-1", "LINK-5");
  const std::vector<std::uint8_t> f = bytes_of<float>(encode_pickoff(sample_reading<float>(), 7));
  ASSERT_EQ(f.size(), 7u + 17u);
  EXPECT_EQ(f[0], 0xA5u);
  EXPECT_EQ(f[1], 0x5Au);
  EXPECT_EQ(f[2], 0x01u);  // pickoff, binary32
  EXPECT_EQ(f[3], 7u);
  EXPECT_EQ(f[4], 17u);
  EXPECT_EQ(f[5], 0x04u);  // sequence 0x01020304, little-endian
  EXPECT_EQ(f[9], 0x03u);  // valid | spin valid
  std::array<std::uint8_t, 24> all{};
  std::copy(f.begin(), f.end(), all.begin());
  EXPECT_EQ(crc16(all, 2, 3 + 17), static_cast<std::uint16_t>(f[22] | (f[23] << 8)));
  const std::vector<std::uint8_t> d = bytes_of<double>(encode_pickoff(sample_reading<double>(), 7));
  EXPECT_EQ(d.size(), 7u + 29u);
  EXPECT_EQ(d[2], 0x81u);  // pickoff, binary64
}

template <typename T>
void round_trip() {
  Decoder<T> dec;
  const PickoffReading<T> in = sample_reading<T>();
  const std::vector<GyroLinkFrame<T>> frames = feed(dec, bytes_of<T>(encode_pickoff(in, 200)));
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].seq, 200u);
  PickoffReading<T> out;
  ASSERT_TRUE(decode_pickoff(frames[0], out));
  EXPECT_EQ(out.gimbal_angle_rad, in.gimbal_angle_rad);
  EXPECT_EQ(out.sequence, in.sequence);
  EXPECT_EQ(out.valid, in.valid);
  EXPECT_EQ(out.spin_valid, in.spin_valid);
  EXPECT_EQ(out.spin_hz, in.spin_hz);
  EXPECT_EQ(dec.counters().frames, 1u);
  EXPECT_EQ(dec.counters().faults(), 0u);
}

TEST(LinkDecoder, GivenAFrameThenDecodedBitForBitInFloatAndDouble) {
  GYRO_VERIFIES("LINK-2", "LINK-3", "RULE-8");
  round_trip<float>();
  round_trip<double>();
}

TEST(LinkDecoder, GivenNoiseBeforeAndBetweenFramesThenEveryFrameFoundAndTheNoiseCounted) {
  GYRO_VERIFIES("LINK-3", "LINK-4");
  Decoder<float> dec;
  std::vector<std::uint8_t> stream = {0x00, 0xA5, 0x13, 0x5A, 0xFF, 0xA5};  // incl. lone sync bytes
  const std::vector<std::uint8_t> a = bytes_of<float>(encode_pickoff(sample_reading<float>(), 1));
  const std::vector<std::uint8_t> b = bytes_of<float>(encode_torque(Eigen::Vector2f(1.0f, -1.0f), 2));
  stream.insert(stream.end(), a.begin(), a.end());
  stream.insert(stream.end(), {0x5A, 0xA5, 0x5A});  // a sync pair with a short header after it
  stream.insert(stream.end(), b.begin(), b.end());
  const std::vector<GyroLinkFrame<float>> frames = feed(dec, stream);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].seq, 1u);
  EXPECT_EQ(frames[1].seq, 2u);
  EXPECT_EQ(dec.counters().bytes_skipped, 9u);
  EXPECT_EQ(dec.buffered(), 0u);
}

TEST(LinkDecoder, GivenATruncatedFrameThenTheFrameAfterItIsStillFound) {
  GYRO_VERIFIES("LINK-3");
  // The stub of a frame claims a length that swallows the next frame's first bytes: its CRC
  // fails, and the decoder finds the good frame inside the bytes it already holds.
  Decoder<float> dec;
  const std::vector<std::uint8_t> good = bytes_of<float>(encode_pickoff(sample_reading<float>(), 9));
  std::vector<std::uint8_t> stream(good.begin(), good.begin() + 10);  // header and half a payload
  stream.insert(stream.end(), good.begin(), good.end());
  const std::vector<GyroLinkFrame<float>> frames = feed(dec, stream);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].seq, 9u);
  EXPECT_EQ(dec.counters().crc_errors, 1u);
}

TEST(LinkDecoder, GivenEverySingleBitErrorOfAFrameThenNoFrameIsDelivered) {
  GYRO_VERIFIES("LINK-3");
  const std::vector<std::uint8_t> good = bytes_of<double>(encode_pickoff(sample_reading<double>(), 3));
  for (std::size_t byte = 0; byte < good.size(); ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      std::vector<std::uint8_t> bad = good;
      bad[byte] = static_cast<std::uint8_t>(bad[byte] ^ (1u << bit));
      Decoder<double> dec;
      EXPECT_TRUE(feed(dec, bad).empty()) << "byte " << byte << " bit " << bit;
      // The next good frame is still found.
      const std::vector<GyroLinkFrame<double>> after = feed(dec, good);
      EXPECT_EQ(after.size(), 1u) << "byte " << byte << " bit " << bit;
    }
  }
}

TEST(LinkDecoder, GivenTheOtherRealFormatOrAnUnknownTypeOrWrongLengthThenRefusedAsHeaderErrors) {
  GYRO_VERIFIES("LINK-3", "LINK-4");
  const std::vector<std::uint8_t> as_double = bytes_of<double>(encode_pickoff(sample_reading<double>(), 1));
  Decoder<float> dec;
  EXPECT_TRUE(feed(dec, as_double).empty());  // a float receiver never takes binary64 reals
  EXPECT_GE(dec.counters().header_errors, 1u);

  std::vector<std::uint8_t> unknown = bytes_of<float>(encode_pickoff(sample_reading<float>(), 1));
  unknown[2] = 0x03;  // no such message
  Decoder<float> dec2;
  EXPECT_TRUE(feed(dec2, unknown).empty());
  EXPECT_GE(dec2.counters().header_errors, 1u);

  std::vector<std::uint8_t> longer = bytes_of<float>(encode_pickoff(sample_reading<float>(), 1));
  longer[4] = 18;  // one more than a pickoff frame has
  Decoder<float> dec3;
  EXPECT_TRUE(feed(dec3, longer).empty());
  EXPECT_GE(dec3.counters().header_errors, 1u);
}

TEST(LinkDecoder, GivenBytesPushedWithoutDrainingThenTheWindowRefusesAndCountsTheOverflow) {
  GYRO_VERIFIES("LINK-4");
  Decoder<float> dec;
  std::size_t accepted = 0;
  // A sync pair and a header announcing a full frame: the decoder must hold them.
  for (std::size_t i = 0; i < Decoder<float>::kCapacity + 5; ++i) {
    const std::uint8_t b = i == 0 ? 0xA5 : (i == 1 ? 0x5A : 0x00);
    if (dec.push(b)) ++accepted;
  }
  EXPECT_EQ(accepted, Decoder<float>::kCapacity);
  EXPECT_EQ(dec.counters().overflows, 5u);
}

TEST(LinkMessages, GivenReservedStatusBitsOrANonFiniteTorqueThenDecodingRefusesAndLeavesTheOutput) {
  GYRO_VERIFIES("LINK-5");
  GyroLinkFrame<float> f = encode_pickoff(sample_reading<float>(), 1);
  f.payload[4] = 0x07;  // bit 2 is reserved
  PickoffReading<float> out;
  out.sequence = 42;
  EXPECT_FALSE(decode_pickoff(f, out));
  EXPECT_EQ(out.sequence, 42u);
  Eigen::Vector2f t(5.0f, 6.0f);
  EXPECT_FALSE(decode_torque(encode_torque(Eigen::Vector2f(std::nanf(""), 0.0f), 1), t));
  EXPECT_EQ(t, Eigen::Vector2f(5.0f, 6.0f));
  EXPECT_TRUE(decode_torque(encode_torque(Eigen::Vector2f(-0.5f, 0.25f), 1), t));
  EXPECT_EQ(t, Eigen::Vector2f(-0.5f, 0.25f));
}

TEST(LinkCrc, GivenARangePastTheArraysEndThenOnlyTheArraysBytesCount) {
  GYRO_VERIFIES("LINK-2");
  std::array<std::uint8_t, 9> bytes{};
  std::memcpy(bytes.data(), "123456789", 9);
  EXPECT_EQ(crc16(bytes, 0, 100), 0x29B1u);
  EXPECT_EQ(crc16(bytes, 5, 100), crc16(bytes, 5, 4));
}

TEST(LinkFrame, GivenAMessageIdAtRunTimeThenTheTypeByteNamesTheRealFormat) {
  GYRO_VERIFIES("LINK-1");
  volatile std::uint8_t id = 0x82;  // not a constant: the type byte as a receiver computes it
  EXPECT_EQ(frame_type<float>(id), 0x02u);  // bit 7 of the id is not the id's
  EXPECT_EQ(frame_type<double>(id), 0x82u);
  EXPECT_EQ(real_bytes(frame_type<double>(id)), 8u);
  EXPECT_EQ(real_bytes(frame_type<float>(id)), 4u);
  EXPECT_EQ(message_id(frame_type<double>(id)), 0x02u);
}

TEST(LinkFrame, GivenALengthBeyondThePayloadOrTheBufferThenNothingIsWritten) {
  GYRO_VERIFIES("LINK-2");
  Frame<4> f;
  std::array<std::uint8_t, kFrameOverhead + 3> out{};  // room for 3 bytes of payload
  out.fill(0xEE);
  f.length = 5;  // one more than the frame's payload array
  EXPECT_EQ(encode_frame(f, out), 0u);
  f.length = 4;  // fits the frame, not the buffer: 11 bytes into 10
  EXPECT_EQ(encode_frame(f, out), 0u);
  EXPECT_EQ(out[0], 0xEEu);
  f.length = 3;
  EXPECT_EQ(encode_frame(f, out), kFrameOverhead + 3);
  EXPECT_EQ(out[0], kSync1);
}

// A message set whose type announces more than its largest payload (a definition error) must
// not make the decoder read past its window: the header is refused.
struct OverlongMessages {
  static constexpr std::size_t kMaxPayload = 4;
  [[nodiscard]] static constexpr int payload_length(std::uint8_t type) noexcept { return type == 1 ? 6 : 4; }
};

TEST(LinkDecoder, GivenAMessageSetAnnouncingMoreThanItsMaximumThenRefusedAsAHeaderError) {
  GYRO_VERIFIES("LINK-3", "LINK-4");
  using Overlong = FrameDecoder<OverlongMessages>;
  Overlong::FrameType good;
  good.type = 2;
  good.length = 4;
  good.payload = {1, 2, 3, 4};
  std::array<std::uint8_t, kFrameOverhead + 4> encoded{};
  ASSERT_EQ(encode_frame(good, encoded), encoded.size());
  std::vector<std::uint8_t> bytes = {0xA5, 0x5A, 1, 0, 6};  // type 1 announces 6 of at most 4
  bytes.insert(bytes.end(), encoded.begin(), encoded.end());
  Overlong dec;
  std::vector<Overlong::FrameType> frames;
  for (std::uint8_t b : bytes) {
    ASSERT_TRUE(dec.push(b));
    for (Overlong::FrameType f; dec.next(f);) frames.push_back(f);
  }
  EXPECT_EQ(dec.counters().header_errors, 1u);
  ASSERT_EQ(frames.size(), 1u);  // the frame after it still found
  EXPECT_EQ(frames[0].type, 2u);
  EXPECT_EQ(frames[0].payload, good.payload);
}

TEST(LinkMessages, GivenAPayloadThatDoesNotFillItsLengthThenSealedToLengthZero) {
  GYRO_VERIFIES("LINK-5");
  GyroLinkFrame<float> f;  // a payload of 17 bytes
  f.length = 8;
  WireWriter short_writer(f.payload, 0);
  short_writer.real(1.0F);  // 4 of 8 bytes
  EXPECT_EQ(sealed(f, short_writer).length, 0u);
  WireWriter overrun(f.payload, 0);
  for (int i = 0; i < 5; ++i) overrun.real(1.0F);  // 20 bytes into 17: the last refused
  f.length = 17;
  EXPECT_EQ(overrun.position(), 17u);
  EXPECT_EQ(sealed(f, overrun).length, 0u);
  WireWriter full(f.payload, 0);
  full.real(1.0F);
  full.real(2.0F);
  f.length = 8;
  EXPECT_EQ(sealed(f, full).length, 8u);
}

TEST(LinkMessages, GivenAnInvalidReadingThenItsFlagsRoundTrip) {
  GYRO_VERIFIES("LINK-5");
  PickoffReading<double> r = sample_reading<double>();
  r.valid = false;
  r.spin_valid = false;
  const GyroLinkFrame<double> f = encode_pickoff(r, 3);
  EXPECT_EQ(f.payload[4], 0u);
  PickoffReading<double> out;
  out.valid = true;
  out.spin_valid = true;
  ASSERT_TRUE(decode_pickoff(f, out));
  EXPECT_FALSE(out.valid);
  EXPECT_FALSE(out.spin_valid);
  EXPECT_EQ(out.sequence, r.sequence);
}

TEST(LinkMessages, GivenTheOtherMessageOrTheWrongLengthThenRefused) {
  GYRO_VERIFIES("LINK-5");
  PickoffReading<float> untouched;
  untouched.sequence = 7;
  EXPECT_FALSE(decode_pickoff(encode_torque(Eigen::Vector2f(1.0f, 2.0f), 1), untouched));
  EXPECT_EQ(untouched.sequence, 7u);
  Eigen::Vector2f kept(5.0f, 6.0f);
  EXPECT_FALSE(decode_torque(encode_pickoff(sample_reading<float>(), 1), kept));
  EXPECT_EQ(kept, Eigen::Vector2f(5.0f, 6.0f));
  GyroLinkFrame<float> p = encode_pickoff(sample_reading<float>(), 1);
  p.length = static_cast<std::uint8_t>(p.length - 1);
  PickoffReading<float> out;
  out.sequence = 42;
  EXPECT_FALSE(decode_pickoff(p, out));
  EXPECT_EQ(out.sequence, 42u);
  GyroLinkFrame<float> t = encode_torque(Eigen::Vector2f(1.0f, 2.0f), 1);
  t.length = static_cast<std::uint8_t>(t.length + 1);
  Eigen::Vector2f torque(5.0f, 6.0f);
  EXPECT_FALSE(decode_torque(t, torque));
  EXPECT_EQ(torque, Eigen::Vector2f(5.0f, 6.0f));
}

TEST(LinkMessages, GivenANonFiniteSecondTorqueAxisThenRefused) {
  GYRO_VERIFIES("LINK-5");
  Eigen::Vector2d t(5.0, 6.0);
  for (const double bad : {std::nan(""), HUGE_VAL, -HUGE_VAL}) {
    EXPECT_FALSE(decode_torque(encode_torque(Eigen::Vector2d(0.25, bad), 1), t)) << bad;
  }
  EXPECT_EQ(t, Eigen::Vector2d(5.0, 6.0));
}

}  // namespace
}  // namespace gyro::link
