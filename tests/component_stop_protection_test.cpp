// GyroComponent's stop protection against the SIL stub's gimbal plant: whatever turns the
// gimbal outward (the body, the command), within the torquer's authority it never reaches
// its stop, in every mode that torques; beyond it the component says so before contact.
// The seeker example: stop 0.55 rad, protection cone 0.45 rad, authority min(max_torque / H,
// slew-rate limit) = min(1.33, 1.0) rad/s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "support/requirements.hpp"
#include "support/scripted_bench.hpp"
#include "support/sil_fixture.hpp"

namespace gyro {
namespace component_stop_protection_test {

using testing::Bench;
using testing::SeekerGyro;
using testing::Sil;

struct Flight {
  bool contact{false};
  int first_contact{-1};
  int first_beyond_authority{-1};
  double largest_cone{0};
  std::uint32_t flags_seen{0};
};

// `ticks` ticks of the loop as it stands, watching the plant's truth.
template <typename T>
Flight fly(Sil<T>& sil, int ticks) {
  Flight f;
  for (int k = 0; k < ticks; ++k) {
    (void)sil.step();
    const std::uint32_t flags = sil.tm().flags;
    f.flags_seen |= flags;
    if ((flags & kStopBeyondAuthority) != 0u && f.first_beyond_authority < 0) f.first_beyond_authority = k;
    if (sil.gyro.at_gimbal_stop() && !f.contact) {
      f.contact = true;
      f.first_contact = k;
    }
    f.largest_cone = std::max(f.largest_cone, static_cast<double>(sil.gyro.cone_rad()));
  }
  return f;
}

struct Turn {
  Vector2<double> body_rate;  // (pitch, yaw) rad/s
  Vector2<double> command;    // free-mode slew command
};

TEST(ComponentStopProtection, FreeGyroStaysOffItsStop) {
  GYRO_VERIFIES("STOP-1", "STOP-2");
  const Turn turns[] = {
      {{0.0, 0.5}, {0.0, 0.0}},   {{0.5, 0.0}, {0.0, 0.0}},    {{-0.6, 0.6}, {0.0, 0.0}},
      {{0.0, 0.9}, {0.0, 0.0}},   {{0.3, 0.0}, {-0.4, 0.0}},  // the command outward with the turn
      {{0.0, -0.4}, {0.0, 0.3}},  // the command inward: the turn still wins
  };
  for (const Turn& t : turns) {
    Sil<double> sil;
    ASSERT_TRUE(sil.start());
    ASSERT_TRUE(sil.uncage());
    sil.body_rate = t.body_rate;
    sil.guidance.slew_rate_cmd_rad_s = t.command;
    const Flight f = fly(sil, 6000);  // 3 s: the unprotected gimbal meets its stop within 1.2 s
    EXPECT_FALSE(f.contact) << t.body_rate.transpose() << " at tick " << f.first_contact;
    EXPECT_LT(f.largest_cone, 0.47) << t.body_rate.transpose();
    EXPECT_NE(f.flags_seen & kGimbalStopProtect, 0u) << t.body_rate.transpose();
    EXPECT_EQ(f.flags_seen & (kStopBeyondAuthority | kFaultLatched), 0u) << t.body_rate.transpose();
    EXPECT_EQ(sil.component.mode(), GyroMode::kFree);
  }
}

TEST(ComponentStopProtection, HeldOffTheStopWithoutNavigation) {
  GYRO_VERIFIES("STOP-5");
  // Without navigation the body's rate is unknown: the bound still pulls the gimbal back from
  // beyond the protection cone, so it settles where the pull matches the turn.
  Sil<double> sil;
  ASSERT_TRUE(sil.start());
  ASSERT_TRUE(sil.uncage());
  sil.body_rate = Vector2<double>(0.0, 0.5);
  sil.nav_valid = false;
  const Flight f = fly(sil, 6000);
  EXPECT_FALSE(f.contact) << "tick " << f.first_contact;
  EXPECT_LT(f.largest_cone, 0.52);
  EXPECT_EQ(f.flags_seen & kFaultLatched, 0u);
}

TEST(ComponentStopProtection, UncagingTorquesOnlyWhenTheBoundActs) {
  GYRO_VERIFIES("TORQ-2", "STOP-1");
  GyroComponentConfig<double> c = SeekerGyro<double>::component();
  c.uncage_settle_ticks = 20000;  // uncaging for the whole flight (10 s, the contract's longest)
  Sil<double> sil;
  ASSERT_TRUE(sil.start(c));
  sil.run(200);
  (void)sil.step(ModeRequest::kUncage);
  ASSERT_EQ(sil.component.mode(), GyroMode::kUncaging);
  sil.body_rate = Vector2<double>(0.0, 0.5);
  sil.run(20);  // the shaper's taps empty of the cage loop's last torques
  EXPECT_TRUE(sil.tm().torque_cmd.isZero()) << "far from the stop: torquers off while settling";
  const Flight f = fly(sil, 6000);
  EXPECT_EQ(sil.component.mode(), GyroMode::kUncaging);
  EXPECT_FALSE(f.contact) << "tick " << f.first_contact;
  EXPECT_LT(f.largest_cone, 0.47);
  EXPECT_NE(f.flags_seen & kGimbalStopProtect, 0u);
  EXPECT_FALSE(sil.tm().torque_cmd.isZero()) << "held off the stop by the torquers";
}

TEST(ComponentStopProtection, BeyondAuthorityFlaggedBeforeContact) {
  GYRO_VERIFIES("STOP-3");
  for (const Vector2<double>& body : {Vector2<double>(0.0, 2.0), Vector2<double>(1.5, 0.0)}) {
    Sil<double> sil;
    ASSERT_TRUE(sil.start());
    ASSERT_TRUE(sil.uncage());
    sil.body_rate = body;
    const Flight f = fly(sil, 4000);
    ASSERT_TRUE(f.contact) << "2 rad/s is beyond the 1 rad/s slew-rate limit: " << body.transpose();
    ASSERT_GE(f.first_beyond_authority, 0);
    // The flag comes once the gimbal is within the bound's reach of the protection cone,
    // tens of ms before the stop's 0.1 rad further out.
    EXPECT_LT(f.first_beyond_authority + 40, f.first_contact) << body.transpose();
  }
}

// Uncaged at 0.5 rad of pitch, beyond the 0.45 rad protection cone, with a torquer that gives
// 0.66 rad/s where the bound asks a pull-back of 1.0: saturated, yet moving in, which is no
// danger. With the body pitching away at 2 rad/s the same torque leaves it moving out.
TEST(ComponentStopProtection, BeyondAuthorityOnlyWhenMovingOut) {
  GYRO_VERIFIES("STOP-3");
  GyroComponentConfig<double> c = SeekerGyro<double>::component();
  c.max_torque = 0.05;
  c.uncage_settle_ticks = 1;
  for (const double body_pitch_rate : {0.0, -2.0}) {
    Bench b(c);
    ASSERT_TRUE(b.ok);
    b.port.reading.gimbal_angle_rad = Vector2<double>(0.5, 0.0);
    b.guidance.body_rate_rad_s = Vector3<double>(0.0, body_pitch_rate, 0.0);
    b.run(3);
    ASSERT_EQ(b.step(ModeRequest::kUncage), Status::kOk);
    (void)b.step();
    ASSERT_EQ(b.component.mode(), GyroMode::kFree);
    ASSERT_EQ(b.step(), Status::kOk);
    EXPECT_TRUE(b.raised(kGimbalStopProtect));
    EXPECT_TRUE(b.raised(kTorquerSaturated));
    EXPECT_EQ(b.raised(kStopBeyondAuthority), body_pitch_rate != 0.0) << body_pitch_rate;
  }
}

TEST(ComponentStopProtection, CagedGyroStaysOffItsStop) {
  GYRO_VERIFIES("STOP-2");
  Sil<double> sil;
  ASSERT_TRUE(sil.start());
  sil.body_rate = Vector2<double>(0.6, -0.6);
  const Flight f = fly(sil, 4000);
  EXPECT_FALSE(f.contact);
  EXPECT_LT(f.largest_cone, 0.1) << "the cage loop keeps the spin axis on body x";
  EXPECT_EQ(f.flags_seen & kStopBeyondAuthority, 0u);
}

// A slew commanded toward the stop is cut to the bound's outward rate and settles at the
// protection cone (0.5 - 0.05 rad) instead of running into the stop; slewing back out is flown.
TEST(ComponentStopProtection, ASlewOutwardIsHeldAtTheCone) {
  GYRO_VERIFIES("STOP-1");
  Sil<double> sil;
  ASSERT_TRUE(sil.start());
  ASSERT_TRUE(sil.uncage());
  sil.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.8, 0.0);
  bool protected_seen = false;
  for (int k = 0; k < 2000 && !protected_seen; ++k) {
    (void)sil.step();
    protected_seen = (sil.tm().flags & kGimbalStopProtect) != 0u;
  }
  ASSERT_TRUE(protected_seen);
  EXPECT_LT(sil.tm().rate_cmd_rad_s(0), 0.8) << "the outward command is cut";
  sil.run(400);
  EXPECT_NEAR(sil.gyro.cone_rad(), 0.45, 3e-3);
  EXPECT_LT(std::abs(sil.tm().rate_cmd_rad_s(0)), 0.03) << "the outward rate dies away as e^(-k t), k = 20 1/s";
  EXPECT_FALSE(sil.gyro.at_gimbal_stop());
  // Slewing back out is allowed.
  sil.guidance.slew_rate_cmd_rad_s = Vector2<double>(-0.3, 0.0);
  ASSERT_EQ(sil.step(), Status::kOk);
  EXPECT_EQ(sil.tm().rate_cmd_rad_s(0), -0.3);
}

}  // namespace component_stop_protection_test
}  // namespace gyro
