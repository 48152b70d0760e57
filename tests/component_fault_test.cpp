// Faults of the hardware, against the SIL stub, a scripted port and a faulty harness: each
// fault the stub injects is detected within a stated number of ticks, a low spin and failing
// torquer writes latch after their persistence; the component goes to safe mode, counts it,
// and nothing in telemetry becomes NaN. Glitches shorter than the persistence are counted only.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>

#include "support/faulty_harness.hpp"
#include "support/requirements.hpp"
#include "support/scripted_bench.hpp"
#include "support/sil_fixture.hpp"

namespace gyro {
namespace component_fault_test {

using testing::Bench;
using testing::counter_of;
using testing::FaultyRig;
using testing::SeekerGyro;
using testing::Sil;
using testing::telemetry_finite;

const GyroComponentConfig<double> kSeeker = SeekerGyro<double>::component();

// ---- the faults the stub injects -------------------------------------------------------------

struct FaultCase {
  const char* name;
  FaultKind kind;
  int axis;
  double magnitude;
  std::uint32_t flag;     // the telemetry flag that must have been raised
  int max_latency_ticks;  // stated bound: fault start to safe mode
};

// Latency bounds, at 2 kHz with the seeker configuration of the fixture:
// - invalid/stale readings: invalid_persistence_ticks (10) consecutive rejections;
// - a bias jump above max_pickoff_step_rad: rejected as a jump, then as invalid persistence;
// - a stuck pickoff or a dead/saturated torquer while slewing at 0.3 rad/s: the residual
//   grows by 1.5e-4 rad a tick to its 2e-3 limit (14 ticks), then residual persistence (20);
// - spin motor failure (the motor brakes the rotor with time constant 0.05 s): spin below
//   300 Hz after 0.05*ln(4/3) = 29 ticks, then spin-low persistence (50); on the gimbal plant
//   the brake's reaction (1.5 N m about the spin axis) swings the outer gimbal first, and the
//   residual latches the fault before the spin is low.
const FaultCase kCases[] = {
    {"stuck pickoff", FaultKind::kStuckPickoff, -1, 0.0, kResidualFault, 40},
    {"invalid reading (valid bit clear)", FaultKind::kInvalidReading, -1, 0.0, kPickoffInvalid, 10},
    {"invalid reading (NaN, valid bit set)", FaultKind::kInvalidReading, 0, 0.0, kPickoffInvalid, 10},
    {"dropout", FaultKind::kDropout, -1, 0.0, kPickoffStale, 10},
    {"bias jump 0.01 rad", FaultKind::kBiasJump, 1, 0.01, kPickoffJump, 10},
    {"bias jump 0.004 rad", FaultKind::kBiasJump, 0, 0.004, kResidualFault, 21},
    {"dead torquer", FaultKind::kDeadTorquer, -1, 0.0, kResidualFault, 40},
    {"saturated torquer", FaultKind::kSaturatedTorquer, 0, 0.05, kResidualFault, 40},
    {"spin motor failure", FaultKind::kSpinMotorFailure, -1, 0.05, kSpinLow, 80},
};

TEST(ComponentFaults, EachInjectedFaultIsDetectedInItsBound) {
  GYRO_VERIFIES("FAULT-3", "MODE-4", "STUB-3");
  constexpr std::uint64_t kStart = 1000;  // after uncaging (600 ticks) and 400 ticks of slew
  for (const FaultCase& fc : kCases) {
    SimulatedGyroConfig<double> s = SeekerGyro<double>::stub();
    s.faults[0].kind = fc.kind;
    s.faults[0].start_tick = kStart;
    s.faults[0].axis = fc.axis;
    s.faults[0].magnitude = fc.magnitude;
    Sil<double> sil;
    ASSERT_TRUE(sil.start(SeekerGyro<double>::component(), s)) << fc.name;
    ASSERT_TRUE(sil.uncage()) << fc.name;
    sil.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.3, 0.2);
    std::uint32_t seen = 0;
    int latency = -1;
    while (sil.tick < kStart + 400) {
      ASSERT_EQ(sil.step(), Status::kOk) << fc.name;
      ASSERT_TRUE(testing::telemetry_finite(sil.tm())) << fc.name << " at tick " << sil.tick;
      if (sil.tick < kStart) {
        ASSERT_NE(sil.component.mode(), GyroMode::kFault) << fc.name << ": false alarm at " << sil.tick;
        continue;
      }
      seen |= sil.tm().flags;
      if (latency < 0 && sil.component.mode() == GyroMode::kFault) {
        latency = static_cast<int>(sil.tick - kStart);
      }
    }
    std::printf("%-38s detected after %3d ticks (%.1f ms), bound %d\n", fc.name, latency, latency * 0.5,
                fc.max_latency_ticks);
    EXPECT_GE(latency, 0) << fc.name << " never detected";
    EXPECT_LE(latency, fc.max_latency_ticks) << fc.name;
    EXPECT_NE(seen & fc.flag, 0u) << fc.name;
    EXPECT_EQ(sil.component.mode(), GyroMode::kFault) << fc.name << " (a permanent fault stays latched)";
    EXPECT_EQ(sil.tm().torque_cmd, Vector2<double>::Zero()) << fc.name << ": safe mode = torquers off";
    EXPECT_GT(sil.tm().counters[14], 0u) << fc.name;
  }
}

TEST(ComponentFaults, ACageRequestRecoversFromADropout) {
  GYRO_VERIFIES("MODE-5");
  SimulatedGyroConfig<double> s = SeekerGyro<double>::stub();
  s.faults[0].kind = FaultKind::kDropout;
  s.faults[0].start_tick = 800;
  s.faults[0].duration_ticks = 30;
  Sil<double> sil;
  ASSERT_TRUE(sil.start(SeekerGyro<double>::component(), s));
  ASSERT_TRUE(sil.uncage());
  while (sil.tick < 850) ASSERT_EQ(sil.step(), Status::kOk);
  ASSERT_EQ(sil.component.mode(), GyroMode::kFault);
  ASSERT_EQ(sil.step(ModeRequest::kCage), Status::kOk);
  EXPECT_EQ(sil.component.mode(), GyroMode::kCaged);
  ASSERT_TRUE(sil.uncage());
  EXPECT_EQ(sil.component.mode(), GyroMode::kFree);
}

TEST(ComponentFaults, ShortGlitchesAreCountedNotLatched) {
  GYRO_VERIFIES("FAULT-3");
  SimulatedGyroConfig<double> s = SeekerGyro<double>::stub();
  s.faults[0] = {FaultKind::kInvalidReading, 800, 5, -1, 0.0};
  s.faults[1] = {FaultKind::kDropout, 900, 5, -1, 0.0};
  Sil<double> sil;
  ASSERT_TRUE(sil.start(SeekerGyro<double>::component(), s));
  ASSERT_TRUE(sil.uncage());
  sil.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.1, 0.0);
  while (sil.tick < 1200) ASSERT_EQ(sil.step(), Status::kOk);
  EXPECT_EQ(sil.component.mode(), GyroMode::kFree);
  EXPECT_EQ(sil.tm().counters[3], 5u);  // kPickoffInvalid
  EXPECT_EQ(sil.tm().counters[4], 5u);  // kPickoffStale
  EXPECT_EQ(sil.tm().counters[6], 0u);  // the estimator coasted through: no residual fault
}

TEST(ComponentFaults, NoFalseAlarmInTenSecondsOfNoise) {
  GYRO_VERIFIES("FAULT-3");
  SimulatedGyroConfig<double> s = SeekerGyro<double>::stub();
  s.pickoff.noise_rad = 2e-4;  // 10% of the residual limit, 1 sigma
  s.pickoff.lsb_rad = 1e-4;
  s.pickoff.lag_s = 1e-4;
  s.torquer.scale_factor = Vector2<double>(1.01, 0.99);
  Sil<double> sil;
  sil.body_rate = Vector2<double>(0.0, 0.05);  // the gyro follows in yaw, weaves in pitch
  ASSERT_TRUE(sil.start(SeekerGyro<double>::component(), s));
  ASSERT_TRUE(sil.uncage());
  for (int k = 0; k < 20000; ++k) {
    sil.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.1 * std::sin(k * 5e-4), 0.05);
    ASSERT_EQ(sil.step(), Status::kOk);
    ASSERT_NE(sil.component.mode(), GyroMode::kFault)
        << "false alarm at tick " << sil.tick << " flags " << sil.tm().flags;
  }
  EXPECT_EQ(sil.tm().counters[6], 0u);
  EXPECT_LT(sil.gyro.cone_rad(), 0.3);
}

// ---- the spin ---------------------------------------------------------------------------------

TEST(ComponentFaults, ALowSpinLatchesAfterItsPersistence) {
  GYRO_VERIFIES("SPIN-2");
  Bench b;
  ASSERT_TRUE(b.ok);
  b.port.reading.spin_hz = 250.0;
  for (std::uint32_t n = 1; n < kSeeker.spin_low_persistence_ticks; ++n) {
    ASSERT_EQ(b.step(), Status::kOk);
    ASSERT_EQ(b.component.mode(), GyroMode::kCaged) << n;
  }
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_EQ(b.component.mode(), GyroMode::kFault);
  EXPECT_EQ(b.tm().counters[counter_of(kSpinLow)], kSeeker.spin_low_persistence_ticks);
  EXPECT_EQ(b.tm().torque_cmd, Vector2<double>::Zero()) << "safe mode: torquers off";
}

// ---- the torquer's writes ---------------------------------------------------------------------

constexpr std::size_t kWriteFailed = counter_of(kTorquerWriteFailed);

// A refused write: the hardware is taken to hold the last torque written, which the telemetry
// reports; the fault latches in the tick after the persistence-th consecutive failure (it is
// decided before the tick's write).
TEST(ComponentFaults, FailedWritesHoldTheLastTorqueThenLatch) {
  GYRO_VERIFIES("PORT-2");
  FaultyRig<double> rig;
  ASSERT_TRUE(rig.start());
  for (int k = 0; k < 50; ++k) ASSERT_EQ(rig.step(), Status::kOk);
  const Vector2<double> accepted = rig.gyro.torque_command();
  ASSERT_GT(accepted.cwiseAbs().maxCoeff(), 0.0) << "caging a turning body needs torque";
  ASSERT_EQ(rig.tm().torque_cmd, accepted);

  rig.harness.write_status = PortStatus::kBusError;
  const std::uint32_t persistence = kSeeker.torquer_fail_persistence_ticks;
  for (std::uint32_t n = 1; n <= persistence; ++n) {
    ASSERT_EQ(rig.step(), Status::kOk);
    EXPECT_NE(rig.tm().flags & kTorquerWriteFailed, 0U) << n;
    EXPECT_EQ(rig.tm().counters[kWriteFailed], n);
    EXPECT_EQ(rig.tm().torque_cmd, accepted) << "telemetry reports the torque the hardware holds";
    EXPECT_EQ(rig.gyro.torque_command(), accepted) << "no failed write reached the gyro";
    EXPECT_EQ(rig.component.mode(), GyroMode::kCaged) << n;
  }
  ASSERT_EQ(rig.step(), Status::kOk);
  EXPECT_EQ(rig.component.mode(), GyroMode::kFault);
  EXPECT_NE(rig.tm().flags & kFaultLatched, 0U);
  EXPECT_TRUE(telemetry_finite(rig.tm()));
}

// Bursts of persistence - 1 failures, each followed by twice as many good writes: the
// persistence monitor drains between the bursts and never trips.
TEST(ComponentFaults, WriteFailuresOneInThreeNeverLatch) {
  GYRO_VERIFIES("PORT-2", "FAULT-1");
  FaultyRig<double> rig;
  ASSERT_TRUE(rig.start());
  const std::uint32_t persistence = kSeeker.torquer_fail_persistence_ticks;
  for (int burst = 0; burst < 4; ++burst) {
    rig.harness.write_status = PortStatus::kTimeout;
    for (std::uint32_t n = 0; n + 1 < persistence; ++n) ASSERT_EQ(rig.step(), Status::kOk);
    rig.harness.write_status = PortStatus::kOk;
    for (std::uint32_t n = 0; n < 2 * (persistence - 1); ++n) {
      ASSERT_EQ(rig.step(), Status::kOk);
      EXPECT_EQ(rig.tm().flags & kTorquerWriteFailed, 0U);
    }
    EXPECT_EQ(rig.tm().torque_cmd, rig.gyro.torque_command()) << "the successful write is held";
  }
  EXPECT_EQ(rig.component.mode(), GyroMode::kCaged);
  EXPECT_EQ(rig.tm().counters[kWriteFailed], 4U * (persistence - 1U));
}

// The same bursts with a single good write between them: an intermittent torquer cannot
// dodge the persistence by succeeding now and then.
TEST(ComponentFaults, WritesFailingFourInFiveLatch) {
  GYRO_VERIFIES("PORT-2", "FAULT-1");
  FaultyRig<double> rig;
  ASSERT_TRUE(rig.start());
  const std::uint32_t persistence = kSeeker.torquer_fail_persistence_ticks;
  for (int burst = 0; burst < 4 && rig.component.mode() != GyroMode::kFault; ++burst) {
    rig.harness.write_status = PortStatus::kTimeout;
    for (std::uint32_t n = 0; n + 1 < persistence; ++n) ASSERT_EQ(rig.step(), Status::kOk);
    rig.harness.write_status = PortStatus::kOk;
    ASSERT_EQ(rig.step(), Status::kOk);
  }
  EXPECT_EQ(rig.component.mode(), GyroMode::kFault);
}

}  // namespace component_fault_test
}  // namespace gyro
