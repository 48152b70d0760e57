// LinkGyroPort over FIFOs: what each kind of arrival makes read_pickoffs() return, the
// sequence checks, whole-frame torque writes, bounded reads, the UART driver against a
// register block in RAM; and the port as a transparent wire: the component over the link
// flies bit for bit as it does with the stub as its port.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "gyro/gyro_component.hpp"
#include "gyro/link/byte_fifo.hpp"
#include "gyro/link/cmsdk_apb_uart.hpp"
#include "gyro/link/frame_decoder.hpp"
#include "gyro/link/gyro_link_messages.hpp"
#include "gyro/link/link_gyro_port.hpp"
#include "gyro/seeker_example.hpp"
#include "gyro/sil_loop.hpp"
#include "gyro/simulated_gyro.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace {

using Wire = link::FifoLink<512, 128>;

template <typename T>
PickoffReading<T> reading(std::uint32_t sequence, T pitch = T(0.01)) {
  PickoffReading<T> r;
  r.gimbal_angle_rad = Vector2<T>(pitch, T(-0.02));
  r.sequence = sequence;
  r.valid = true;
  r.spin_valid = true;
  r.spin_hz = T(400);
  return r;
}

template <typename T>
std::vector<std::uint8_t> frame_bytes(const PickoffReading<T>& r, std::uint8_t seq) {
  std::array<std::uint8_t, link::kGyroLinkFrameBytes<T>> buf{};
  const std::size_t n = link::encode_frame(link::encode_pickoff(r, seq), buf);
  return std::vector<std::uint8_t>(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
}

void arrive(Wire& wire, const std::vector<std::uint8_t>& bytes) {
  for (std::uint8_t b : bytes) ASSERT_TRUE(wire.rx().push(b));
}

TEST(LinkPort, GivenAFrameThenOkWithItsReadingAndGivenSilenceThenTimeout) {
  GYRO_VERIFIES("LINK-6");
  Wire wire;
  LinkGyroPort<float> port(wire);
  PickoffReading<float> out;
  EXPECT_EQ(port.read_pickoffs(out), PortStatus::kTimeout);
  arrive(wire, frame_bytes(reading<float>(5, 0.125f), 0));
  ASSERT_EQ(port.read_pickoffs(out), PortStatus::kOk);
  EXPECT_EQ(out.sequence, 5u);
  EXPECT_EQ(out.gimbal_angle_rad(0), 0.125f);
  out.sequence = 99;
  EXPECT_EQ(port.read_pickoffs(out), PortStatus::kTimeout);
  EXPECT_EQ(out.sequence, 99u);  // nothing read: untouched
  EXPECT_EQ(port.counters().readings, 1u);
  EXPECT_EQ(port.counters().timeouts, 2u);
}

TEST(LinkPort, GivenOnlyBadBytesThenBusErrorAndGivenAPartialFrameThenTimeoutUntilItCompletes) {
  GYRO_VERIFIES("LINK-6");
  Wire wire;
  LinkGyroPort<double> port(wire);
  PickoffReading<double> out;
  std::vector<std::uint8_t> bad = frame_bytes(reading<double>(1), 0);
  bad[10] ^= 0x40u;  // payload bit: CRC mismatch
  arrive(wire, bad);
  EXPECT_EQ(port.read_pickoffs(out), PortStatus::kBusError);
  arrive(wire, {0x11, 0x22, 0x33});  // noise: not a frame either
  EXPECT_EQ(port.read_pickoffs(out), PortStatus::kBusError);
  const std::vector<std::uint8_t> good = frame_bytes(reading<double>(2), 1);
  arrive(wire, std::vector<std::uint8_t>(good.begin(), good.begin() + 20));
  EXPECT_EQ(port.read_pickoffs(out), PortStatus::kTimeout);  // not late yet: incomplete
  arrive(wire, std::vector<std::uint8_t>(good.begin() + 20, good.end()));
  ASSERT_EQ(port.read_pickoffs(out), PortStatus::kOk);
  EXPECT_EQ(out.sequence, 2u);
  EXPECT_EQ(port.counters().bus_errors, 2u);
  EXPECT_EQ(port.decoder_counters().crc_errors, 1u);
}

TEST(LinkPort, GivenDuplicatesGapsAndABacklogThenSequenceNumbersJudgeThem) {
  GYRO_VERIFIES("LINK-6");
  Wire wire;
  LinkGyroPort<float> port(wire);
  PickoffReading<float> out;
  arrive(wire, frame_bytes(reading<float>(10), 7));
  arrive(wire, frame_bytes(reading<float>(10), 7));  // the same frame twice
  ASSERT_EQ(port.read_pickoffs(out), PortStatus::kOk);
  EXPECT_EQ(port.counters().duplicates, 1u);
  arrive(wire, frame_bytes(reading<float>(10), 7));  // a late repeat alone: nothing new
  EXPECT_EQ(port.read_pickoffs(out), PortStatus::kTimeout);
  EXPECT_EQ(port.counters().duplicates, 2u);
  arrive(wire, frame_bytes(reading<float>(13), 10));  // 8 and 9 never came
  ASSERT_EQ(port.read_pickoffs(out), PortStatus::kOk);
  EXPECT_EQ(port.counters().frames_lost, 2u);
  arrive(wire, frame_bytes(reading<float>(14), 11));  // a backlog: the newest wins
  arrive(wire, frame_bytes(reading<float>(15), 12));
  ASSERT_EQ(port.read_pickoffs(out), PortStatus::kOk);
  EXPECT_EQ(out.sequence, 15u);
  EXPECT_EQ(port.counters().superseded, 1u);
  arrive(wire, frame_bytes(reading<float>(16), 255));  // wraps: 13 .. 254 lost
  ASSERT_EQ(port.read_pickoffs(out), PortStatus::kOk);
  arrive(wire, frame_bytes(reading<float>(17), 0));
  ASSERT_EQ(port.read_pickoffs(out), PortStatus::kOk);
  EXPECT_EQ(port.counters().frames_lost, 2u + 242u);
}

TEST(LinkPort, GivenReservedBitsOrATorqueFrameThenNotAReading) {
  GYRO_VERIFIES("LINK-6", "LINK-5");
  Wire wire;
  LinkGyroPort<float> port(wire);
  PickoffReading<float> out;
  link::GyroLinkFrame<float> f = link::encode_pickoff(reading<float>(1), 0);
  f.payload[4] = 0x80;  // reserved status bit
  std::array<std::uint8_t, link::kGyroLinkFrameBytes<float>> buf{};
  std::size_t n = link::encode_frame(f, buf);
  arrive(wire, std::vector<std::uint8_t>(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n)));
  EXPECT_EQ(port.read_pickoffs(out), PortStatus::kBusError);
  EXPECT_EQ(port.counters().malformed, 1u);
  n = link::encode_frame(link::encode_torque(Vector2<float>(1.0f, 2.0f), 1), buf);
  arrive(wire, std::vector<std::uint8_t>(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n)));
  EXPECT_EQ(port.read_pickoffs(out), PortStatus::kTimeout);
  EXPECT_EQ(port.counters().unexpected, 1u);
}

TEST(LinkPort, GivenMoreBytesThanOneReadTakesThenTheRestWaitsForTheNextRead) {
  GYRO_VERIFIES("LINK-6");
  Wire wire;
  LinkGyroPort<float, 30> port(wire);  // a read takes at most 30 bytes: one frame and a bit
  PickoffReading<float> out;
  arrive(wire, frame_bytes(reading<float>(1), 0));
  arrive(wire, frame_bytes(reading<float>(2), 1));
  ASSERT_EQ(port.read_pickoffs(out), PortStatus::kOk);
  EXPECT_EQ(out.sequence, 1u);
  EXPECT_EQ(wire.rx().size(), 2u * 24u - 30u);
  ASSERT_EQ(port.read_pickoffs(out), PortStatus::kOk);
  EXPECT_EQ(out.sequence, 2u);
}

TEST(LinkPort, GivenATorqueThenOneWholeFrameAndGivenNoRoomOrNonFiniteThenNothingAndBusError) {
  GYRO_VERIFIES("LINK-7");
  link::FifoLink<16, 16> small;  // room for less than a double torque frame (23 bytes)
  LinkGyroPort<double> tight(small);
  EXPECT_EQ(tight.write_torquer(Vector2<double>(0.01, -0.02)), PortStatus::kBusError);
  EXPECT_EQ(small.tx().size(), 0u);

  Wire wire;
  LinkGyroPort<double> port(wire);
  EXPECT_EQ(port.write_torquer(Vector2<double>(std::nan(""), 0.0)), PortStatus::kBusError);
  EXPECT_EQ(port.write_torquer(Vector2<double>(0.0, std::nan(""))), PortStatus::kBusError);
  EXPECT_EQ(wire.tx().size(), 0u);
  ASSERT_EQ(port.write_torquer(Vector2<double>(0.01, -0.02)), PortStatus::kOk);
  ASSERT_EQ(port.write_torquer(Vector2<double>(0.03, -0.04)), PortStatus::kOk);
  link::FrameDecoder<link::GyroLinkMessages<double>> electronics;
  std::vector<Vector2<double>> got;
  std::vector<std::uint8_t> seqs;
  for (std::uint8_t b; wire.tx().pop(b);) {
    ASSERT_TRUE(electronics.push(b));
    for (link::GyroLinkFrame<double> f; electronics.next(f);) {
      Vector2<double> t;
      ASSERT_TRUE(link::decode_torque(f, t));
      got.push_back(t);
      seqs.push_back(f.seq);
    }
  }
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0], Vector2<double>(0.01, -0.02));
  EXPECT_EQ(got[1], Vector2<double>(0.03, -0.04));
  EXPECT_EQ(seqs[1], static_cast<std::uint8_t>(seqs[0] + 1u));
  EXPECT_EQ(port.counters().torque_frames, 2u);
  EXPECT_EQ(port.counters().torque_refused, 2u);
}

// The register block of a CMSDK APB UART, in RAM: the test plays the hardware.
TEST(CmsdkUart, GivenRegisterStatesThenTheDriverReadsWritesAndCountsOverrunsAsTheHardwareDefines) {
  GYRO_VERIFIES("LINK-9");
  link::CmsdkApbUartRegisters regs{};
  link::CmsdkApbUart uart(regs);
  EXPECT_FALSE(uart.enable(25000000u, 2000000u));  // divider 12.5 < 16
  EXPECT_FALSE(uart.enable(25000000u, 0u));        // no divider at all
  EXPECT_EQ(regs.ctrl, 0u);
  EXPECT_EQ(regs.bauddiv, 0u);
  ASSERT_TRUE(uart.enable(25000000u, 115200u));
  EXPECT_EQ(regs.bauddiv, 217u);
  EXPECT_EQ(regs.ctrl, 0x3u);

  std::uint8_t b = 0;
  EXPECT_FALSE(uart.read_byte(b));  // RX empty
  regs.data = 0x1A5u;
  regs.state = link::CmsdkApbUart::kRxFull;
  ASSERT_TRUE(uart.read_byte(b));
  EXPECT_EQ(b, 0xA5u);  // bits 7:0
  regs.state = link::CmsdkApbUart::kRxFull | link::CmsdkApbUart::kRxOverrun;
  ASSERT_TRUE(uart.read_byte(b));
  EXPECT_EQ(uart.rx_overruns(), 1u);
  EXPECT_EQ(regs.state, link::CmsdkApbUart::kRxOverrun);  // the write-one-to-clear value written

  regs.state = link::CmsdkApbUart::kTxFull;
  EXPECT_EQ(uart.write_room(), 0u);
  EXPECT_FALSE(uart.write_byte(0x42));
  regs.state = 0;
  EXPECT_EQ(uart.write_room(), 1u);
  ASSERT_TRUE(uart.write_byte(0x42));
  EXPECT_EQ(regs.data, 0x42u);

  uart.set_rx_interrupt(true);
  EXPECT_EQ(regs.ctrl, 0xBu);
  uart.set_rx_interrupt(false);
  EXPECT_EQ(regs.ctrl, 0x3u);  // both directions stay enabled
  uart.clear_rx_interrupt();
  EXPECT_EQ(regs.intstatus, 0x2u);
}

// The component over the link, as the SIL loop calls it: the electronics side (the stub
// behind a decoder and an encoder) sends the stub's conversion as a frame before the step and
// hands the torque frames the component wrote to the stub after it.
template <typename T>
struct WiredComponent {
  SimulatedGyro<T>& stub;
  GyroComponent<T>& component;
  Wire& wire;
  link::FrameDecoder<link::GyroLinkMessages<T>> electronics{};
  std::uint8_t seq{0};
  bool link_ok{true};

  [[nodiscard]] Status activate() { return component.activate(); }
  [[nodiscard]] Status step(std::uint64_t k, const GuidanceInput<T>& in) {
    PickoffReading<T> r;
    link_ok = link_ok && stub.read_pickoffs(r) == PortStatus::kOk;
    std::array<std::uint8_t, link::kGyroLinkFrameBytes<T>> buf{};
    const std::size_t n = link::encode_frame(link::encode_pickoff(r, seq++), buf);
    for (std::size_t i = 0; i < n; ++i) link_ok = link_ok && wire.rx().push(buf[i]);
    const Status st = component.step(k, in);
    for (std::uint8_t b; wire.tx().pop(b);) {
      link_ok = link_ok && electronics.push(b);
      for (link::GyroLinkFrame<T> f; electronics.next(f);) {
        Vector2<T> t;
        link_ok = link_ok && link::decode_torque(f, t) && stub.write_torquer(t) == PortStatus::kOk;
      }
    }
    return st;
  }
};

// The component over the link against the component with the stub as its port: identical
// telemetry, tick for tick.
template <typename T>
void transparent_wire() {
  using Ex = SeekerExample<T>;
  SimulatedGyro<T> direct_stub, wired_stub;
  GyroComponent<T> direct(direct_stub);
  Wire wire;
  LinkGyroPort<T> port(wire);
  GyroComponent<T> wired(port);
  WiredComponent<T> wired_side{wired_stub, wired, wire};
  SilLoop<T, GyroComponent<T>> direct_loop(direct_stub, direct, StubBodyFeed::kAttitude);
  SilLoop<T, WiredComponent<T>> wired_loop(wired_stub, wired_side, StubBodyFeed::kAttitude);
  for (SimulatedGyro<T>* s : {&direct_stub, &wired_stub}) ASSERT_TRUE(s->configure(Ex::stub()).ok());
  for (GyroComponent<T>* c : {&direct, &wired}) ASSERT_TRUE(c->configure(Ex::component()).ok());
  const BodySample<T> body = turning_body(Matrix3<T>(Matrix3<T>::Identity()), Vector2<T>(Vector2<T>::Zero()));
  ASSERT_EQ(direct_loop.start(body).component, Status::kOk);
  ASSERT_EQ(wired_loop.start(body).component, Status::kOk);
  GuidanceCommand<T> command;
  for (std::uint64_t k = 0; k <= 1500; ++k) {
    command.request = k == 100 ? ModeRequest::kUncage : ModeRequest::kNone;
    command.slew_rate_cmd_rad_s = k >= 600 ? Vector2<T>(T(0.2), T(-0.1)) : Vector2<T>::Zero();
    const SilStatus<Status> d = direct_loop.tick(k, body, command);
    const SilStatus<Status> w = wired_loop.tick(k, body, command);
    ASSERT_EQ(d.stub, Status::kOk);
    ASSERT_EQ(w.stub, Status::kOk);
    ASSERT_EQ(d.component, Status::kOk);
    ASSERT_EQ(w.component, Status::kOk);
    ASSERT_TRUE(wired_side.link_ok) << "tick " << k;
    const GyroTelemetry<T>& a = direct.telemetry();
    const GyroTelemetry<T>& b = wired.telemetry();
    ASSERT_EQ(a.mode, b.mode) << "tick " << k;
    ASSERT_EQ(a.flags, b.flags) << "tick " << k;
    ASSERT_EQ(a.torque_cmd, b.torque_cmd) << "tick " << k;
    ASSERT_EQ(a.gimbal_predicted_rad, b.gimbal_predicted_rad) << "tick " << k;
    ASSERT_EQ(direct_stub.gimbal_angle_rad(), wired_stub.gimbal_angle_rad()) << "tick " << k;
  }
  EXPECT_EQ(direct.mode(), GyroMode::kFree);
  EXPECT_EQ(port.counters().readings, 1501u);
  EXPECT_EQ(port.counters().torque_frames, 1501u);
}

// In float, the Cortex-M4F's case (the double one runs end to end on the Cortex-M7 in
// scripts/pil.sh; a second instantiation of the component doubles this file's build time).
TEST(LinkPort, GivenACleanLinkThenTheComponentFliesBitForBitAsWithTheStubAsItsPort) {
  GYRO_VERIFIES("LINK-8");
  transparent_wire<float>();
}

}  // namespace
}  // namespace gyro
