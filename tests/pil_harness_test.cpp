// The PIL harness messages: each one encoded and decoded through the frame decoder in float
// and double, with the documented payload sizes; every configuration field and every
// telemetry value crosses the wire (distinct values per field); refusals leave the output.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "gyro/link/gyro_link_messages.hpp"
#include "gyro/pil/harness.hpp"

namespace gyro::pil {
namespace {

// The frame after a trip through bytes and the decoder.
template <typename T>
HarnessFrame<T> over_the_wire(const HarnessFrame<T>& f) {
  std::array<std::uint8_t, kHarnessFrameBytes<T>> bytes{};
  const std::size_t n = link::encode_frame(f, bytes);
  EXPECT_EQ(n, link::kFrameOverhead + f.length);
  HarnessDecoder<T> d;
  HarnessFrame<T> out;
  bool got = false;
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_TRUE(d.push(bytes[i]));
    got = d.next(out) || got;
  }
  EXPECT_TRUE(got);
  return out;
}

template <typename T>
GyroComponentConfig<T> distinct_config() {
  GyroComponentConfig<T> c;
  T v = T(1);
  std::uint32_t n = 100;
  visit_fields(
      [&](const Field&, auto& m) {
        using M = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<M, T>) m = (v += T(0.5));
        if constexpr (std::is_same_v<M, std::uint32_t>) m = ++n;
      },
      c);
  c.use_spin_readback = false;
  c.friction_compensation = true;
  return c;
}

template <typename T>
void config_round_trip() {
  Config<T> in;
  in.component = distinct_config<T>();
  in.timer_period = 25000;
  const HarnessFrame<T> f = over_the_wire<T>(encode_config(in, 3));
  EXPECT_EQ(f.length, kConfigReals * sizeof(T) + 1 + 4 * kConfigCounts + 4);
  Config<T> out;
  ASSERT_TRUE(decode_config(f, out));
  EXPECT_EQ(std::memcmp(&out.component.tick_s, &in.component.tick_s, sizeof(T)), 0);
  int fields = 0;
  visit_fields(
      [&](const Field& field, const auto& a, const auto& b) {
        EXPECT_EQ(a, b) << field.name;
        ++fields;
      },
      out.component, in.component);
  EXPECT_EQ(static_cast<std::size_t>(fields), kConfigReals + kConfigCounts + kConfigSwitches);
  EXPECT_EQ(out.component.use_spin_readback, false);
  EXPECT_EQ(out.component.friction_compensation, true);
  EXPECT_EQ(out.timer_period, 25000u);
}

// The target's gyro line under noise: each tick brings `noise` random bytes and then the
// pickoff frame into the receive FIFO, the port reads once. What arrived, and the bytes the
// FIFO dropped.
struct LineRun {
  std::uint32_t readings{0};  // reads that returned kOk
  std::uint32_t current{0};   // of them, with the frame of their own tick (not a late one)
  std::uint32_t dropped{0};
};

template <typename T, typename Port>
LineRun noisy_line(std::size_t noise, int ticks) {
  GyroWire wire;
  Port port(wire);
  LineRun run;
  std::uint64_t state = 0x243F6A8885A308D3ull;
  for (int k = 0; k < ticks; ++k) {
    for (std::size_t i = 0; i < noise; ++i) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      if (!wire.rx().push(static_cast<std::uint8_t>(state >> 56u))) ++run.dropped;
    }
    PickoffReading<T> r;
    r.gimbal_angle_rad = Vector2<T>(T(0.01), T(-0.02));
    r.sequence = static_cast<std::uint32_t>(k + 1);
    r.valid = true;
    std::array<std::uint8_t, link::kGyroLinkFrameBytes<T>> frame{};
    const std::size_t n = link::encode_frame(link::encode_pickoff(r, static_cast<std::uint8_t>(k)), frame);
    for (std::size_t i = 0; i < n; ++i) {
      if (!wire.rx().push(frame[i])) ++run.dropped;
    }
    PickoffReading<T> out;
    if (port.read_pickoffs(out) == PortStatus::kOk) {
      ++run.readings;
      if (out.sequence == r.sequence) ++run.current;
    }
  }
  return run;
}

// 120 bytes of line noise a tick: a read of 4 frames (144 bytes in double, 96 in float) fell
// behind by the excess every tick until the FIFO dropped bytes and the readings starved (9 of
// 3,000 here in double, 3 in float; 10 of 3,001 in the M7 image under gyro_sil --pil). The PIL's port drains the FIFO (256 bytes a read, more than the 255 the
// line delivers a tick): nothing is dropped and a reading arrives on (nearly) every tick.
template <typename T>
void expect_readings_keep_arriving() {
  constexpr int kTicks = 3000;
  static_assert(link::kGyroLinkFrameBytes<T> + 120 <= kGyroLineBytesPerTick, "a tick's bytes fit the line");
  const LineRun drained = noisy_line<T, GyroLinkPort<T>>(120, kTicks);
  EXPECT_EQ(drained.dropped, 0u);
  EXPECT_GE(drained.current, static_cast<std::uint32_t>(kTicks * 99 / 100));
  EXPECT_EQ(drained.current, drained.readings);
  // The most the line can bring, 255 bytes a tick, is drained as well.
  const LineRun full = noisy_line<T, GyroLinkPort<T>>(kGyroLineBytesPerTick - link::kGyroLinkFrameBytes<T>, kTicks);
  EXPECT_EQ(full.dropped, 0u);
  EXPECT_GE(full.current, static_cast<std::uint32_t>(kTicks * 98 / 100));
  // The old bound of a read, 4 frames, under the same noise: the backlog fills the FIFO.
  const LineRun four_frames = noisy_line<T, LinkGyroPort<T>>(120, kTicks);
  EXPECT_GT(four_frames.dropped, 10000u);  // 12 bytes a tick behind in double, 48 in float
  EXPECT_LT(four_frames.readings, static_cast<std::uint32_t>(kTicks / 10));
  std::printf("%zu-byte frames, 120 bytes of noise a tick, %d ticks: %u readings (%u bytes dropped) draining, "
              "%u at the line's 255 bytes a tick; %u readings (%u current, %u bytes dropped) reading 4 frames\n",
              link::kGyroLinkFrameBytes<T>, kTicks, drained.current, drained.dropped, full.current,
              four_frames.readings, four_frames.current, four_frames.dropped);
}

TEST(PilGyroLine, GivenAHundredAndTwentyBytesOfNoiseATickThenReadingsKeepArrivingInFloat) {
  expect_readings_keep_arriving<float>();
}

TEST(PilGyroLine, GivenAHundredAndTwentyBytesOfNoiseATickThenReadingsKeepArrivingInDouble) {
  expect_readings_keep_arriving<double>();
}

TEST(PilHarness, GivenAConfigurationThenEveryFieldCrossesTheWire) {
  config_round_trip<float>();
  config_round_trip<double>();
}

TEST(PilHarness, GivenTheFieldTableThenItNamesEveryMemberOnce) {
  // Distinct values land in distinct members: every real of the table is its own member.
  const GyroComponentConfig<double> c = distinct_config<double>();
  std::vector<double> seen;
  visit_fields(
      [&](const Field&, const auto& m) {
        if constexpr (std::is_same_v<std::decay_t<decltype(m)>, double>) {
          for (double s : seen) EXPECT_NE(s, m);
          seen.push_back(m);
        }
      },
      c);
  EXPECT_EQ(seen.size(), kConfigReals);
}

template <typename T>
void tick_round_trip() {
  TickIn<T> in;
  in.tick = 0xFFFFFFF0u;
  in.gyro_bytes = 24;
  in.guidance.request = ModeRequest::kUncage;
  in.guidance.nav_valid = true;
  in.guidance.slew_rate_cmd_rad_s = Vector2<T>(T(0.3), T(-0.2));
  for (int i = 0; i < 9; ++i) in.guidance.R_earth_to_body(i / 3, i % 3) = T(i) / T(7);
  in.guidance.body_rate_rad_s = Vector3<T>(T(0.5), T(0.05), T(-0.03));
  const HarnessFrame<T> f = over_the_wire<T>(encode_tick_in(in, 1));
  EXPECT_EQ(f.length, 6 + 14 * sizeof(T));
  TickIn<T> out;
  ASSERT_TRUE(decode_tick_in(f, out));
  EXPECT_EQ(out.tick, in.tick);
  EXPECT_EQ(out.gyro_bytes, 24u);
  EXPECT_EQ(out.guidance.request, ModeRequest::kUncage);
  EXPECT_TRUE(out.guidance.nav_valid);
  EXPECT_EQ(out.guidance.slew_rate_cmd_rad_s, in.guidance.slew_rate_cmd_rad_s);
  EXPECT_EQ(out.guidance.R_earth_to_body, in.guidance.R_earth_to_body);
  EXPECT_EQ(out.guidance.body_rate_rad_s, in.guidance.body_rate_rad_s);

  TickOut t;
  t.next_tick = 12;
  t.has_previous = true;
  t.previous_tick = 11;
  t.step_status = Status::kNonFiniteInput;
  t.step_counts = 141;
  t.gyro_bytes = 15;
  t.released = 13;
  t.cycles = 12;
  t.skipped = 1;
  t.overruns = 2;
  t.overrun = true;
  std::uint32_t v = 1000;
  for (std::uint32_t LinkPortCounters::*m : kPortCounters) t.port.*m = ++v;
  t.header_errors = 7;
  t.crc_errors = 8;
  t.bytes_skipped = 9;
  t.decoder_frames = 10;
  const HarnessFrame<T> g = over_the_wire<T>(encode_tick_out<T>(t, 2));
  EXPECT_EQ(g.length, 88u);
  TickOut back;
  ASSERT_TRUE(decode_tick_out<T>(g, back));
  EXPECT_EQ(std::memcmp(&back.port, &t.port, sizeof t.port), 0);
  EXPECT_EQ(back.step_status, Status::kNonFiniteInput);
  EXPECT_EQ(back.step_counts, 141u);
  EXPECT_EQ(back.skipped, 1u);
  EXPECT_TRUE(back.overrun);
  EXPECT_EQ(back.decoder_frames, 10u);
}

TEST(PilHarness, GivenTickRecordsThenGuidanceAndReportCrossTheWire) {
  tick_round_trip<float>();
  tick_round_trip<double>();
}

template <typename T>
void telemetry_round_trip() {
  GyroTelemetry<T> m;
  m.tick = 0x100000005ull;
  m.mode = GyroMode::kFault;
  m.flags = 0x4008u;
  for (std::size_t i = 0; i < m.counters.size(); ++i) m.counters[i] = static_cast<std::uint32_t>(i * 3 + 1);
  T v = T(0.25);
  for (Vector2<T> GyroTelemetry<T>::*p : TelemetryFields<T>::kPairs) {
    m.*p = Vector2<T>(v, -v);
    v += T(0.25);
  }
  m.attitude_gyro_to_earth = Quaternion<T>(T(0.5), T(0.5), T(-0.5), T(0.5));
  m.spin_hz = T(399.5);
  const HarnessFrame<T> f = over_the_wire<T>(encode_telemetry(m, 9));
  EXPECT_EQ(f.length, 9 + 4 * kComponentFlagCount + 19 * sizeof(T));
  GyroTelemetry<T> out;
  ASSERT_TRUE(decode_telemetry(f, out));
  EXPECT_EQ(out.tick, 5u);  // low 32 bits
  EXPECT_EQ(out.mode, GyroMode::kFault);
  EXPECT_EQ(out.flags, m.flags);
  EXPECT_EQ(out.counters, m.counters);
  for (Vector2<T> GyroTelemetry<T>::*p : TelemetryFields<T>::kPairs) EXPECT_EQ(out.*p, m.*p);
  EXPECT_EQ(out.attitude_gyro_to_earth.coeffs(), m.attitude_gyro_to_earth.coeffs());
  EXPECT_EQ(out.spin_hz, m.spin_hz);
}

TEST(PilHarness, GivenTelemetryThenEveryValueCrossesTheWire) {
  telemetry_round_trip<float>();
  telemetry_round_trip<double>();
}

TEST(PilHarness, GivenHelloAckAndStopThenTheirFieldsCrossTheWire) {
  Hello h;
  h.real_bytes = 4;
  h.timer_hz = 25000000;
  Hello back;
  ASSERT_TRUE(decode_hello<float>(over_the_wire<float>(encode_hello<float>(h, 0)), back));
  EXPECT_EQ(back.version, kProtocolVersion);
  EXPECT_EQ(back.timer_hz, 25000000u);

  const ConfigAck refused = make_config_ack(ConfigCheck{Status::kOutOfRange, "torquer_fail_persistence_ticks"});
  ConfigAck ack;
  ASSERT_TRUE(decode_config_ack<double>(over_the_wire<double>(encode_config_ack<double>(refused, 1)), ack));
  EXPECT_EQ(ack.status, Status::kOutOfRange);
  EXPECT_STREQ(ack.field.data(), "torquer_fail_persistenc");  // truncated to 23 characters
  EXPECT_STREQ(make_config_ack(ConfigCheck{}).field.data(), "");

  const HarnessFrame<float> stop = over_the_wire<float>(encode_stop<float>(0, 2));
  EXPECT_EQ(stop.type, link::frame_type<float>(kStop));
}

TEST(PilHarness, GivenAFrameOfAnotherMessageOrReservedBitsThenDecodingRefusesAndLeavesTheOutput) {
  Config<float> c;
  c.timer_period = 77;
  EXPECT_FALSE(decode_config(encode_stop<float>(0, 0), c));
  EXPECT_EQ(c.timer_period, 77u);
  TickIn<float> t;
  HarnessFrame<float> f = encode_tick_in(t, 0);
  f.payload[5] = 0x08;  // reserved bit of the request byte
  t.tick = 5;
  EXPECT_FALSE(decode_tick_in(f, t));
  EXPECT_EQ(t.tick, 5u);
}

// fuzz/make_seeds.py encodes every harness message from docs/pil-protocol.md alone, in Python;
// its seeds decode here: the document and the code describe the same bytes.
template <typename T>
void seed_decodes(const char* name) {
  std::ifstream in(std::string(GYRO_SOURCE_DIR) + "/fuzz/corpus/fuzz_frame_decoder/" + name, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 1u) << name;
  HarnessDecoder<T> d;
  std::vector<HarnessFrame<T>> frames;
  for (std::size_t i = 1; i < bytes.size(); ++i) {  // byte 0 is the fuzz target's selector
    ASSERT_TRUE(d.push(static_cast<std::uint8_t>(bytes[i])));
    for (HarnessFrame<T> f; d.next(f);) frames.push_back(f);
  }
  ASSERT_EQ(frames.size(), 7u) << name;
  EXPECT_EQ(d.counters().faults(), 0u) << name;
  Hello h;
  Config<T> c;
  ConfigAck a;
  TickIn<T> ti;
  TickOut to;
  GyroTelemetry<T> tm;
  EXPECT_TRUE(decode_hello<T>(frames[0], h));
  EXPECT_EQ(h.real_bytes, sizeof(T));
  EXPECT_TRUE(decode_config(frames[1], c));
  EXPECT_EQ(c.component.max_torque, T(0.04));
  EXPECT_EQ(c.timer_period, 25000u);
  EXPECT_TRUE(decode_config_ack<T>(frames[2], a));
  EXPECT_TRUE(decode_tick_in(frames[3], ti));
  EXPECT_EQ(ti.guidance.request, ModeRequest::kUncage);
  EXPECT_TRUE(ti.guidance.nav_valid);
  EXPECT_EQ(ti.guidance.R_earth_to_body, Matrix3<T>::Identity());
  EXPECT_TRUE(decode_tick_out<T>(frames[4], to));
  EXPECT_EQ(to.step_counts, 141u);
  EXPECT_TRUE(decode_telemetry(frames[5], tm));
  EXPECT_EQ(tm.mode, GyroMode::kFree);
  EXPECT_EQ(frames[6].type, link::frame_type<T>(kStop));
}

TEST(PilHarness, GivenFramesEncodedFromTheProtocolDocumentThenEveryMessageDecodes) {
  seed_decodes<float>("seed_harness_float");
  seed_decodes<double>("seed_harness_double");
}

}  // namespace
}  // namespace gyro::pil
