// The component keeps flying whatever its inputs (docs/component.md, "Corrupt input"): each
// class of corrupt input alone, then random streams of corrupt and good input interleaved,
// against the SIL stub, in float and double.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "gyro/gyro_component.hpp"
#include "gyro/persistence.hpp"
#include "gyro/seeker_example.hpp"
#include "gyro/sil_loop.hpp"
#include "gyro/simulated_gyro.hpp"
#include "support/corrupting_port.hpp"
#include "support/sil_fixture.hpp"

namespace gyro {
namespace {

using testing::CorruptingPort;
using testing::SeekerGyro;
using testing::telemetry_finite;
using testing::WireFault;

constexpr std::uint32_t kIgnoredInput = kCommandRejected | kTickInvalid;

// The component behind a corrupting wire to the SIL stub; the body turns slowly. `tick` is
// the true tick (the stub's); each call may hand the component another count.
// The component as the loop calls it, handed the test's tick count and input instead of the
// loop's, or not called at all (a tick lost).
template <typename T>
struct TamperedComponent {
  GyroComponent<T>& component;
  std::uint64_t count{0};
  GuidanceInput<T> input{};
  bool skip{false};

  [[nodiscard]] Status activate() noexcept { return component.activate(); }
  [[nodiscard]] Status step(std::uint64_t /*tick*/, const GuidanceInput<T>& /*in*/) noexcept {
    return skip ? Status::kOk : component.step(count, input);
  }
};

template <typename T>
struct Rig {
  SimulatedGyro<T> gyro;
  CorruptingPort<T> wire{gyro};
  GyroComponent<T> component{wire};
  TamperedComponent<T> tampered{component};
  SilLoop<T, TamperedComponent<T>> loop{gyro, tampered, StubBodyFeed::kAttitude};
  GuidanceInput<T> guidance;
  Matrix3<T> R_earth_to_body{Matrix3<T>::Identity()};
  Vector3<T> body_rate{T(0), T(0.05), T(-0.04)};
  std::uint64_t tick{0};
  bool ever_at_stop{false};

  bool start() {
    guidance.nav_valid = true;
    if (!gyro.configure(SeekerGyro<T>::stub()).ok() || !component.configure(SeekerGyro<T>::component()).ok()) {
      return false;
    }
    const SilStatus<Status> started = loop.start(turning_body(R_earth_to_body, pitch_yaw()));
    return started.stub == Status::kOk && started.component == Status::kOk;
  }

  // The world moves one tick; the component is called with `g` (its tick count, request,
  // commands and navigation as given: the test corrupts them).
  Status step_with(std::uint64_t count, GuidanceInput<T> g) { return world_tick(count, g, false); }
  // The world moves one tick; the component is not called.
  Status lose_tick() { return world_tick(0, good_guidance(), true); }
  // A good tick: the true count and navigation.
  Status step(ModeRequest request = ModeRequest::kNone) {
    GuidanceInput<T> g = good_guidance();
    g.request = request;
    return step_with(tick + 1, g);
  }
  [[nodiscard]] GuidanceInput<T> good_guidance() const {
    GuidanceInput<T> g = guidance;
    g.nav_valid = true;
    g.R_earth_to_body = next_attitude();
    g.body_rate_rad_s = body_rate;
    return g;
  }
  [[nodiscard]] Vector2<T> pitch_yaw() const { return Vector2<T>(body_rate(1), body_rate(2)); }
  [[nodiscard]] Matrix3<T> next_attitude() const {
    return pitch_then_yaw_turn(pitch_yaw(), SeekerGyro<T>::kTick) * R_earth_to_body;
  }
  Status world_tick(std::uint64_t count, const GuidanceInput<T>& g, bool skip) {
    R_earth_to_body = next_attitude();
    ++tick;
    tampered.count = count;
    tampered.input = g;
    tampered.skip = skip;
    const SilStatus<Status> ran = loop.tick(tick, turning_body(R_earth_to_body, pitch_yaw()), GuidanceCommand<T>{});
    EXPECT_EQ(ran.stub, Status::kOk);
    ever_at_stop = ever_at_stop || gyro.at_gimbal_stop();
    return ran.stub != Status::kOk ? ran.stub : ran.component;
  }
  void run(int ticks) {
    for (int k = 0; k < ticks; ++k) EXPECT_EQ(step(), Status::kOk) << k;
  }
  bool uncage() {
    run(100);
    (void)step(ModeRequest::kUncage);
    run(static_cast<int>(SeekerGyro<T>::component().uncage_settle_ticks));
    return component.mode() == GyroMode::kFree;
  }
  [[nodiscard]] const GyroTelemetry<T>& tm() const { return component.telemetry(); }
  [[nodiscard]] std::uint32_t count(ComponentFlag f) const {
    for (int i = 0; i < kComponentFlagCount; ++i) {
      if (f == (1u << static_cast<unsigned>(i))) return tm().counters[static_cast<std::size_t>(i)];
    }
    return 0;
  }
};

const GyroComponentConfig<double> kSeekerConfig = SeekerGyro<double>::component();

// ---- the persistence monitor ---------------------------------------------------------------

TEST(PersistenceMonitor, GivenNConsecutiveBadTicksThenTripsExactlyAtTheNth) {
  PersistenceMonitor m;
  for (std::uint32_t k = 1; k < 10; ++k) EXPECT_FALSE(m.update(true, 10)) << k;
  EXPECT_TRUE(m.update(true, 10));
}

TEST(PersistenceMonitor, GivenAnIntermittentConditionThenItTripsAboveOneInThreeAndNeverBelow) {
  const auto ticks_to_trip = [](int bad, int period, int limit) {
    PersistenceMonitor m;
    for (int k = 0; k < limit; ++k) {
      if (m.update(k % period < bad, 10)) return k + 1;
    }
    return -1;
  };
  EXPECT_EQ(ticks_to_trip(19, 20, 1000), 10) << "19 bad in 20: as fast as consecutive ones";
  EXPECT_GT(ticks_to_trip(1, 2, 1000), 0) << "one in two";
  EXPECT_LE(ticks_to_trip(1, 2, 1000), 4 * 10 + 2);
  EXPECT_EQ(ticks_to_trip(1, 3, 100000), -1) << "one in three: counted, never latched";
  EXPECT_EQ(ticks_to_trip(1, 20, 100000), -1);
}

TEST(PersistenceMonitor, GivenATrippedMonitorThenOneGoodTickUntripsItAndItsFillIsCapped) {
  PersistenceMonitor m;
  for (int k = 0; k < 1000; ++k) (void)m.update(true, 5);
  EXPECT_EQ(m.fill(), 10u);
  EXPECT_FALSE(m.update(false, 5));
  EXPECT_TRUE(m.update(true, 5)) << "and the next bad tick trips it again";
}

// ---- calls before activation ---------------------------------------------------------------

TEST(ComponentFailOperational, GivenStepsBeforeActivationThenRefusedCountedAndNothingTouched) {
  SimulatedGyro<double> gyro;
  CorruptingPort<double> wire{gyro};
  GyroComponent<double> c{wire};
  GuidanceInput<double> g;
  EXPECT_EQ(c.step(1, g), Status::kNotConfigured);
  ASSERT_TRUE(c.configure(kSeekerConfig).ok());
  EXPECT_EQ(c.step(2, g), Status::kNotConfigured);
  EXPECT_EQ(c.telemetry().flags, static_cast<std::uint32_t>(kNotActive));
  EXPECT_EQ(c.telemetry().counters[16], 2u) << "both refusals are counted";
  EXPECT_EQ(c.mode(), GyroMode::kIdle);
  EXPECT_EQ(wire.writes, 0);
}

// ---- the tick count --------------------------------------------------------------------------

TEST(ComponentFailOperational, GivenOneCorruptedTickFarAheadThenTwoTicksFlaggedAndTheRunFliesOn) {
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  rig.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.2, -0.1);
  rig.run(100);
  EXPECT_EQ(rig.step_with(rig.tick + 1'000'000'000ULL, rig.good_guidance()), Status::kInputIgnored);
  EXPECT_NE(rig.tm().flags & kTickInvalid, 0u);
  // The next correct count is behind the corrupted one: flagged once more, resynchronised.
  EXPECT_EQ(rig.step_with(rig.tick + 1, rig.good_guidance()), Status::kInputIgnored);
  EXPECT_NE(rig.tm().flags & kTickInvalid, 0u);
  for (int k = 0; k < 200; ++k) {
    ASSERT_EQ(rig.step(), Status::kOk) << k;
    EXPECT_EQ(rig.tm().flags & kIgnoredInput, 0u);
  }
  EXPECT_EQ(rig.count(kTickInvalid), 2u);
  EXPECT_EQ(rig.component.mode(), GyroMode::kFree);
  EXPECT_EQ(rig.tm().rate_cmd_rad_s, Vector2<double>(0.2, -0.1)) << "still slewing as commanded";
  EXPECT_LT(rig.tm().residual_rad.cwiseAbs().maxCoeff(), kSeekerConfig.residual_limit_rad / 10);
  // A cage request is honoured at once.
  ASSERT_EQ(rig.step(ModeRequest::kCage), Status::kOk);
  EXPECT_EQ(rig.component.mode(), GyroMode::kCaged);
}

TEST(ComponentFailOperational, GivenARepeatedOrBackwardCountThenEachIsOneTickAndTheEstimatorStaysRight) {
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  rig.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.3, 0.3);
  for (int k = 0; k < 300; ++k) {
    // Every third call repeats the last count, every fifth goes back by ten.
    const std::uint64_t count = (k % 3 == 0) ? rig.tick : (k % 5 == 0) ? rig.tick - 10 : rig.tick + 1;
    (void)rig.step_with(count, rig.good_guidance());
    // The component is never refused and never predicts a tick that did not pass: the
    // residual stays at the clean run's level.
    EXPECT_LT(rig.tm().residual_rad.cwiseAbs().maxCoeff(), kSeekerConfig.residual_limit_rad / 10) << k;
  }
  EXPECT_NE(rig.tm().counters[15], 0u);
  EXPECT_EQ(rig.component.mode(), GyroMode::kFault) << "counts this bad for this long latch a fault";
  EXPECT_NE(rig.tm().counters[17], 0u) << "and say it was the input";
  // Good counts again: the cage request of the second good tick is honoured.
  (void)rig.step();
  ASSERT_EQ(rig.step(ModeRequest::kCage), Status::kOk);
  EXPECT_EQ(rig.component.mode(), GyroMode::kCaged);
}

TEST(ComponentFailOperational, GivenAGapOfLostTicksThenItIsBridgedFlaggedAndTheResidualStaysSmall) {
  // Two rigs, one ticked every tick, one missing ticks: after a gap of g ticks the component
  // predicts over g ticks, so its residual stays at the level of the rig that missed nothing.
  for (const std::uint64_t gap : {2ULL, 5ULL, 8ULL}) {
    SCOPED_TRACE(gap);
    Rig<double> rig;
    ASSERT_TRUE(rig.start());
    ASSERT_TRUE(rig.uncage());
    rig.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.5, -0.4);
    rig.run(50);
    for (std::uint64_t k = 1; k < gap; ++k) ASSERT_EQ(rig.lose_tick(), Status::kOk);  // the world moves
    ASSERT_EQ(rig.step(), Status::kOk);
    EXPECT_NE(rig.tm().flags & kTickSkipped, 0u);
    EXPECT_EQ(rig.tm().flags & kTickInvalid, 0u);
    EXPECT_LT(rig.tm().residual_rad.cwiseAbs().maxCoeff(), 2e-5) << "predicted over the whole gap";
  }
  // One tick more than max_tick_gap is not believed: one tick, flagged invalid.
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  rig.run(10);
  EXPECT_EQ(rig.step_with(rig.tick + 1 + kSeekerConfig.max_tick_gap, rig.good_guidance()), Status::kInputIgnored);
  EXPECT_NE(rig.tm().flags & kTickInvalid, 0u);
}

// ---- guidance commands and navigation ---------------------------------------------------------

TEST(ComponentFailOperational, GivenANonFiniteSlewCommandThenTheLastUsableOneIsHeldFlaggedAndCounted) {
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  rig.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.1, 0.05);
  rig.run(20);
  GuidanceInput<double> bad = rig.good_guidance();
  bad.slew_rate_cmd_rad_s(1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(rig.step_with(rig.tick + 1, bad), Status::kInputIgnored);
  EXPECT_EQ(rig.tm().flags & kIgnoredInput, static_cast<std::uint32_t>(kCommandRejected));
  EXPECT_EQ(rig.tm().rate_cmd_rad_s, Vector2<double>(0.1, 0.05)) << "the last usable command, held";
  EXPECT_TRUE(telemetry_finite(rig.tm()));
  bad.request = static_cast<ModeRequest>(7);
  bad.slew_rate_cmd_rad_s = Vector2<double>(0.2, 0.0);
  EXPECT_EQ(rig.step_with(rig.tick + 1, bad), Status::kInputIgnored) << "an unknown request is dropped";
  EXPECT_EQ(rig.tm().rate_cmd_rad_s, Vector2<double>(0.2, 0.0)) << "the rest of the input is used";
  EXPECT_EQ(rig.component.mode(), GyroMode::kFree);
  EXPECT_EQ(rig.tm().counters[11], 2u);
}

TEST(ComponentFailOperational, GivenNavigationMarkedInvalidWithNonFiniteRatesThenTheTickIsFlownNotRefused) {
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  // A long outage, the body turning on: the caller says invalid and sends NaN rates.
  for (int k = 0; k < 4000; ++k) {
    GuidanceInput<double> g = rig.good_guidance();
    g.nav_valid = false;
    g.body_rate_rad_s.setConstant(std::numeric_limits<double>::quiet_NaN());
    g.R_earth_to_body.setConstant(std::numeric_limits<double>::quiet_NaN());
    ASSERT_EQ(rig.step_with(rig.tick + 1, g), Status::kOk) << "nothing the caller marked invalid is an error";
    ASSERT_NE(rig.tm().flags & kNavInvalid, 0u);
    ASSERT_TRUE(telemetry_finite(rig.tm()));
  }
  EXPECT_EQ(rig.component.mode(), GyroMode::kFree) << "an outage is no gyro fault";
  EXPECT_FALSE(rig.ever_at_stop);
  // Caged during the outage: the gimbal loop alone closes the angles.
  for (int k = 0; k < 400; ++k) {
    GuidanceInput<double> g = rig.good_guidance();
    g.nav_valid = false;
    g.request = k == 0 ? ModeRequest::kCage : ModeRequest::kNone;
    ASSERT_EQ(rig.step_with(rig.tick + 1, g), Status::kOk);
  }
  EXPECT_EQ(rig.component.mode(), GyroMode::kCaged);
  EXPECT_LT(rig.tm().gimbal_measured_rad.cwiseAbs().maxCoeff(), 0.01);
  EXPECT_FALSE(rig.ever_at_stop);
}

TEST(ComponentFailOperational, GivenNavigationMarkedValidButUnusableThenIgnoredFlaggedAndCounted) {
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  const auto expect_ignored = [&](const GuidanceInput<double>& g, const char* what) {
    EXPECT_EQ(rig.step_with(rig.tick + 1, g), Status::kInputIgnored) << what;
    EXPECT_EQ(rig.tm().flags & (kNavInvalid | kCommandRejected), kNavInvalid | kCommandRejected) << what;
    EXPECT_TRUE(telemetry_finite(rig.tm())) << what;
  };
  GuidanceInput<double> g = rig.good_guidance();
  g.body_rate_rad_s(0) = std::numeric_limits<double>::infinity();
  expect_ignored(g, "non-finite rate");
  g = rig.good_guidance();
  g.body_rate_rad_s(2) = 1e160;
  expect_ignored(g, "a rate beyond max_body_rate_rad_s");
  g = rig.good_guidance();
  g.R_earth_to_body(0, 0) = 2.0;
  expect_ignored(g, "not a rotation");
  rig.run(10);
  EXPECT_EQ(rig.component.mode(), GyroMode::kFree);
}

// ---- the pickoffs -------------------------------------------------------------------------------

TEST(ComponentFailOperational, GivenNineteenInvalidReadingsInEveryTwentyThenTheFaultLatches) {
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  int k = 0;
  for (; k < 400 && rig.component.mode() != GyroMode::kFault; ++k) {
    rig.wire.fault = (k % 20 == 19) ? WireFault::kNone : WireFault::kNotValid;
    (void)rig.step();
  }
  EXPECT_EQ(rig.component.mode(), GyroMode::kFault);
  EXPECT_LE(k, static_cast<int>(kSeekerConfig.invalid_persistence_ticks) + 2);
}

TEST(ComponentFailOperational, GivenAPersistentBiasJumpThenFaultLatchedAndACageRequestRecoversTheGyro) {
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  rig.wire.fault = WireFault::kJump;  // from now on every reading is 0.1 rad off
  int k = 0;
  for (; k < 100 && rig.component.mode() != GyroMode::kFault; ++k) (void)rig.step();
  EXPECT_EQ(rig.component.mode(), GyroMode::kFault);
  EXPECT_EQ(k, static_cast<int>(kSeekerConfig.invalid_persistence_ticks)) << "each reading rejected as a jump";
  // In safe mode the shifted readings are the reference: caging is possible.
  (void)rig.step();
  ASSERT_EQ(rig.step(ModeRequest::kCage), Status::kOk);
  EXPECT_EQ(rig.component.mode(), GyroMode::kCaged);
  rig.run(50);
  EXPECT_EQ(rig.tm().flags & kPickoffJump, 0u);
}

TEST(ComponentFailOperational, GivenReadingsMissingLongerThanAJumpAllowsThenTheFirstGoodOneIsAccepted) {
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  rig.guidance.slew_rate_cmd_rad_s = Vector2<double>(1.0, 0.0);  // 5e-4 rad per tick
  rig.run(20);
  // Stale for 8 ticks (below the fault's persistence): the gimbal moves 4e-3 rad, and the jump
  // bound grows with the blind ticks.
  rig.wire.fault = WireFault::kStale;
  for (int k = 0; k < 8; ++k) (void)rig.step();
  rig.wire.fault = WireFault::kNone;
  ASSERT_EQ(rig.step(), Status::kOk);
  EXPECT_EQ(rig.tm().flags & (kPickoffJump | kPickoffStale | kPickoffInvalid), 0u);
  EXPECT_EQ(rig.component.mode(), GyroMode::kFree);
}

// ---- random streams of corrupt and good input -----------------------------------------------

// Spoils one thing of a tick, of a random class: the tick count, a command, the navigation or
// the wire. Applied once or several times to the same tick, the classes mix.
template <typename T>
void corrupt(Rig<T>& rig, std::mt19937_64& rng, std::uint64_t& count, GuidanceInput<T>& g) {
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const auto index = [&rng](int n) { return static_cast<Eigen::Index>(rng() % static_cast<std::uint64_t>(n)); };
  switch (rng() % 10) {
    case 0: count = rng(); break;
    case 1: count = rig.tick - (rng() % 50); break;
    case 2: g.slew_rate_cmd_rad_s(index(2)) = nan; break;
    case 3: g.request = static_cast<ModeRequest>(3 + rng() % 200); break;
    case 4:
      g.nav_valid = false;
      g.body_rate_rad_s.setConstant(nan);
      break;
    case 5: g.body_rate_rad_s(index(3)) = std::numeric_limits<T>::infinity(); break;
    case 6: g.R_earth_to_body(index(3), index(3)) += T(0.5); break;
    default: rig.wire.fault = static_cast<WireFault>(1 + rng() % (testing::kWireFaultCount - 1)); break;
  }
}

template <typename T>
void run_random_streams(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Rig<T> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  const T max_torque = SeekerGyro<T>::component().max_torque;
  int worst_back_in_control = 0;
  int worst_cage = 0;
  for (int burst = 0; burst < 12; ++burst) {
    // Good flying, a modest slew (the body turns slowly: only corrupt input could reach the stop).
    const T slew = T(0.2) * (static_cast<T>(rng() % 200) / T(100) - T(1));
    rig.guidance.slew_rate_cmd_rad_s = Vector2<T>(slew, -slew / T(2));
    for (int k = 0; k < 100; ++k) (void)rig.step();
    // A stretch of corrupt input: each tick corrupt with probability 1/2 (alone or mixed).
    const int length = 5 + static_cast<int>(rng() % 150);
    for (int k = 0; k < length; ++k) {
      std::uint64_t count = rig.tick + 1;
      GuidanceInput<T> g = rig.good_guidance();
      rig.wire.fault = WireFault::kNone;
      if (rng() % 2 == 0) {
        const int classes = 1 + static_cast<int>(rng() % 3);
        for (int c = 0; c < classes; ++c) corrupt(rig, rng, count, g);
      }
      if (rng() % 40 == 0) g.request = ModeRequest::kCage;
      (void)rig.step_with(count, g);
      const GyroTelemetry<T>& t = rig.tm();
      ASSERT_TRUE(telemetry_finite(t)) << "burst " << burst << " tick " << k;
      ASSERT_LE(t.torque_cmd.cwiseAbs().maxCoeff(), max_torque);
      ASSERT_FALSE(rig.ever_at_stop) << "burst " << burst << " tick " << k;
    }
    rig.wire.fault = WireFault::kNone;
    // Good input resumes, with a cage request every tick: how many ticks until a clean tick
    // (status kOk, nothing ignored), and until the cage request is honoured?
    int clean = 0, caged = 0;
    for (int k = 1; k <= 100 && (clean == 0 || caged == 0); ++k) {
      const Status st = rig.step(ModeRequest::kCage);
      if (clean == 0 && st == Status::kOk) clean = k;
      if (caged == 0 && rig.component.mode() == GyroMode::kCaged) caged = k;
    }
    worst_back_in_control = std::max(worst_back_in_control, clean);
    worst_cage = std::max(worst_cage, caged);
    ASSERT_EQ(rig.component.mode(), GyroMode::kCaged) << "burst " << burst;
    ASSERT_GT(clean, 0) << "burst " << burst;
    // And back to free flight.
    rig.run(100);
    (void)rig.step(ModeRequest::kUncage);
    rig.run(static_cast<int>(SeekerGyro<T>::component().uncage_settle_ticks));
    ASSERT_EQ(rig.component.mode(), GyroMode::kFree) << "burst " << burst;
  }
  std::printf("seed %llu: clean tick within %d ticks of good input, cage within %d\n",
              static_cast<unsigned long long>(seed), worst_back_in_control, worst_cage);
  EXPECT_LE(worst_back_in_control, 2) << "the first good tick may still follow an untrusted count";
  EXPECT_LE(worst_cage, 2) << "the first good tick may still see the last bad tick's failed write";
  EXPECT_FALSE(rig.ever_at_stop);
}

TEST(ComponentFailOperationalProperty, GivenRandomStreamsOfCorruptAndGoodInputDoubleThenItAlwaysRecovers) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) run_random_streams<double>(seed);
}
TEST(ComponentFailOperationalProperty, GivenRandomStreamsOfCorruptAndGoodInputFloatThenItAlwaysRecovers) {
  for (std::uint64_t seed = 101; seed <= 110; ++seed) run_random_streams<float>(seed);
}

}  // namespace
}  // namespace gyro
