// What the component's telemetry says, against the SIL stub and a scripted port: the flags of
// an aliased nutation and of a step beyond the small-angle limit, and two runs bit for bit
// alike.
#include <gtest/gtest.h>

#include "support/requirements.hpp"
#include "support/scripted_bench.hpp"
#include "support/sil_fixture.hpp"

namespace gyro {
namespace component_telemetry_test {

using testing::Bench;
using testing::SeekerGyro;
using testing::Sil;

const GyroComponentConfig<double> kSeeker = SeekerGyro<double>::component();

// ---- the nutation unresolved ----------------------------------------------------------------

// 600 Hz nutation (H/J): a 1 kHz tick samples it less than twice a period; 2 kHz, more.
TEST(ComponentTelemetry, AnAliasedNutationIsFlaggedUnresolved) {
  GYRO_VERIFIES("TLM-3");
  GyroComponentConfig<double> c = kSeeker;
  SimulatedGyroConfig<double> s = SeekerGyro<double>::stub();
  c.tick_s = s.tick_s = 1e-3;
  c.cage_gain_1_s = 10;
  Sil<double> sil;
  ASSERT_TRUE(sil.start(c, s));
  sil.run(10);
  EXPECT_NE(sil.tm().flags & kNutationUnresolved, 0u);
  Sil<double> fine;
  ASSERT_TRUE(fine.start());
  fine.run(10);
  EXPECT_EQ(fine.tm().flags & kNutationUnresolved, 0u);
}

// The flag speaks of the estimate (its nutation cannot be checked against aliased pickoffs):
// none before the estimator has started, raised on the tick it starts.
TEST(ComponentTelemetry, UnresolvedOnlyOnceThereIsAnEstimate) {
  GYRO_VERIFIES("TLM-3");
  GyroComponentConfig<double> c = kSeeker;
  c.tick_s = 1e-3;  // 600 Hz nutation at a 1 kHz tick: aliased
  c.cage_gain_1_s = 10;
  Bench b(c);
  ASSERT_TRUE(b.ok);
  b.guidance.nav_valid = false;  // no navigation: nothing to start the estimator from
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(b.step(), Status::kOk);
    EXPECT_FALSE(b.raised(kNutationUnresolved)) << "tick " << b.tick;
  }
  b.guidance.nav_valid = true;
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_TRUE(b.raised(kNutationUnresolved));
}

// ---- the small-angle limit ----------------------------------------------------------------------

// The estimator's small-angle check reaches the telemetry: with a limit below one tick's
// rotation of the turning body every predicted tick is flagged and counted; a flag, not a fault.
TEST(ComponentTelemetry, SmallAngleExceededIsFlaggedAndCounted) {
  GYRO_VERIFIES("EST-5", "TLM-2");
  for (const double limit : {1e-3, 0.01}) {
    Sil<double> sil;
    sil.body_rate = Vector2<double>(2.4, -1.8);  // 1.5e-3 rad per 0.5 ms tick
    GyroComponentConfig<double> c = kSeeker;
    c.small_angle_limit_rad = limit;
    // What the contract asks of a 1e-3 limit: one tick's slew within it, a full-torque
    // step's nutation within a tenth of it, and the torquer's authority.
    c.max_pitch_rate_rad_s = c.max_yaw_rate_rad_s = 0.5;
    c.max_torque = 0.025;
    ASSERT_TRUE(sil.start(c, SeekerGyro<double>::stub()));
    sil.run(50);
    if (limit < 1.5e-3) {
      // Flagged and counted (not every tick: caging at its 0.5 rad/s limit lags the body).
      EXPECT_GE(sil.tm().counters[1], 10U);
    } else {
      EXPECT_EQ(sil.tm().flags & kSmallAngleExceeded, 0U);
      EXPECT_EQ(sil.tm().counters[1], 0U);
    }
    EXPECT_EQ(sil.component.mode(), GyroMode::kCaged) << "a flag, not a fault";
  }
}

// ---- determinism --------------------------------------------------------------------------------

TEST(ComponentDeterminism, TwoRunsGiveBitIdenticalTelemetry) {
  GYRO_VERIFIES("RULE-6");
  auto run = [](auto tag) {
    using T = decltype(tag);
    Sil<T> sil;
    SimulatedGyroConfig<T> s = SeekerGyro<T>::stub();
    s.pickoff.noise_rad = T(1e-5);
    s.pickoff.lsb_rad = T(1e-5);
    sil.body_rate = Vector2<T>(T(0.2), T(0.1));
    EXPECT_TRUE(sil.start(SeekerGyro<T>::component(), s));
    EXPECT_TRUE(sil.uncage());
    sil.guidance.slew_rate_cmd_rad_s = Vector2<T>(T(0.3), T(-0.1));
    sil.run(1000);
    return sil.tm();
  };
  const GyroTelemetry<double> d1 = run(0.0), d2 = run(0.0);
  EXPECT_TRUE(testing::identical(d1, d2));
  const GyroTelemetry<float> f1 = run(0.0f), f2 = run(0.0f);
  EXPECT_TRUE(testing::identical(f1, f2));
  EXPECT_EQ(f1.mode, GyroMode::kFree);
  EXPECT_NEAR(static_cast<double>(f1.precession_rate_rad_s(0)), d1.precession_rate_rad_s(0), 1e-3);
}

}  // namespace component_telemetry_test
}  // namespace gyro
