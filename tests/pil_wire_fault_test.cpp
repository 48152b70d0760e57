// gyro_sil --pil's wire faults: the command-line form, which ticks they hit, what each does
// to the bytes on the wire, and what the target's port then reports (the reaction the PIL
// runs in scripts/pil.sh check end to end).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "gyro/link/byte_fifo.hpp"
#include "gyro/link/gyro_link_messages.hpp"
#include "gyro/link/link_gyro_port.hpp"
#include "wire_faults.hpp"

namespace gyro::sil {
namespace {

std::uint32_t bit(WireFaultKind k) { return 1u << static_cast<unsigned>(k); }

TEST(PilWireFaults, GivenTheCommandLineFormThenParsedAndGivenAnythingElseThenRefusedWithAReason) {
  std::string error;
  const std::optional<WireFault> a = parse_wire_fault("crc@600+5", error);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->kind, WireFaultKind::kCorruptCrc);
  EXPECT_EQ(a->start_tick, 600u);
  EXPECT_EQ(a->ticks, 5u);
  const std::optional<WireFault> b = parse_wire_fault("stall@0", error);
  ASSERT_TRUE(b);
  EXPECT_EQ(b->ticks, 1u);
  for (const char* bad : {"crc", "crc@", "crc@x", "crc@5+0", "crc@5+", "jam@5", "@5", "drop@-1", "drop@1+2+3"}) {
    error.clear();
    EXPECT_FALSE(parse_wire_fault(bad, error)) << bad;
    EXPECT_FALSE(error.empty()) << bad;
  }
}

TEST(PilWireFaults, GivenWindowsThenActiveExactlyInsideThem) {
  const std::vector<WireFault> faults = {{WireFaultKind::kDrop, 10, 3}, {WireFaultKind::kNoise, 11, 1}};
  EXPECT_EQ(active_wire_faults(faults, 9), 0u);
  EXPECT_EQ(active_wire_faults(faults, 10), bit(WireFaultKind::kDrop));
  EXPECT_EQ(active_wire_faults(faults, 11), bit(WireFaultKind::kDrop) | bit(WireFaultKind::kNoise));
  EXPECT_EQ(active_wire_faults(faults, 12), bit(WireFaultKind::kDrop));
  EXPECT_EQ(active_wire_faults(faults, 13), 0u);
}

class PortUnderFault : public ::testing::Test {
 protected:
  // The port's answer to one tick's bytes under `faults`.
  PortStatus tick(std::uint32_t faults, std::uint64_t k) {
    PickoffReading<float> r;
    r.gimbal_angle_rad = Eigen::Vector2f(0.01f, 0.02f);
    r.sequence = static_cast<std::uint32_t>(k);
    r.valid = true;
    std::array<std::uint8_t, link::kGyroLinkFrameBytes<float>> frame{};
    const std::size_t n = link::encode_frame(link::encode_pickoff(r, seq_++), frame);
    wire_bytes_ = faulted_downlink(std::span<const std::uint8_t>(frame.data(), n), faults, k);
    for (std::uint8_t b : wire_bytes_) EXPECT_TRUE(wire_.rx().push(b));
    PickoffReading<float> out;
    return port_.read_pickoffs(out);
  }

  link::FifoLink<512, 64> wire_;
  LinkGyroPort<float> port_{wire_};
  std::uint8_t seq_{0};
  std::vector<std::uint8_t> wire_bytes_;
};

TEST_F(PortUnderFault, GivenEachWireFaultThenTheBytesAndThePortsAnswerAreTheDocumentedOnes) {
  EXPECT_EQ(tick(0, 0), PortStatus::kOk);
  EXPECT_EQ(wire_bytes_.size(), 24u);

  EXPECT_EQ(tick(bit(WireFaultKind::kCorruptCrc), 1), PortStatus::kBusError);
  EXPECT_EQ(wire_bytes_.size(), 24u);
  EXPECT_EQ(port_.decoder_counters().crc_errors, 1u);

  EXPECT_EQ(tick(bit(WireFaultKind::kDrop), 2), PortStatus::kTimeout);
  EXPECT_TRUE(wire_bytes_.empty());

  EXPECT_EQ(tick(bit(WireFaultKind::kDuplicate), 3), PortStatus::kOk);
  EXPECT_EQ(wire_bytes_.size(), 48u);
  EXPECT_EQ(port_.counters().duplicates, 1u);
  EXPECT_EQ(port_.counters().frames_lost, 2u);  // the corrupted and the dropped frame

  EXPECT_EQ(tick(bit(WireFaultKind::kNoise), 4), PortStatus::kOk);
  EXPECT_EQ(wire_bytes_.size(), 16u + 24u);

  EXPECT_EQ(tick(bit(WireFaultKind::kStall) | bit(WireFaultKind::kDuplicate), 5), PortStatus::kTimeout);
  EXPECT_TRUE(wire_bytes_.empty());

  EXPECT_EQ(tick(0, 6), PortStatus::kOk);
  EXPECT_EQ(port_.counters().readings, 4u);
}

TEST(PilWireFaults, GivenTheSameTickThenTheSameNoise) {
  const std::vector<std::uint8_t> frame(24, 0x55);
  const std::uint32_t noise = bit(WireFaultKind::kNoise);
  EXPECT_EQ(faulted_downlink(frame, noise, 7), faulted_downlink(frame, noise, 7));
  EXPECT_NE(faulted_downlink(frame, noise, 7), faulted_downlink(frame, noise, 8));
}

}  // namespace
}  // namespace gyro::sil
