// The torque law (gyro/torque_law.hpp), without a port: the rate each mode flies, the rate limits,
// the torquers that hold a rate against friction, saturation and stop protection.
#include <gtest/gtest.h>

#include <cmath>

#include "gyro/seeker_component_example.hpp"
#include "gyro/torque_law.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace torque_law_test {

const GyroComponentConfig<double> kSeeker = SeekerComponentExample<double>::component();
const Vector2<double> kZero = Vector2<double>::Zero();
const GimbalFrame<double> kCentred = gimbal_frame_at(kZero);
const double kSpin = kSeeker.nominal_spin_hz;
const double kH = 2 * M_PI * kSeeker.spin_inertia * kSpin;

RateCommand<double> free_slew(const TorqueLaw<double>& law, const Vector2<double>& cmd) {
  return law.rate_command(GyroMode::kFree, kCentred, kZero, kZero, true, cmd);
}

TEST(TorqueLaw, SafeModeDrivesNothing) {
  GYRO_VERIFIES("TORQ-2");
  const TorqueLaw<double> law(kSeeker);
  const RateCommand<double> r = law.rate_command(GyroMode::kFault, kCentred, Vector2<double>(0.3, 0.2),
                                                 Vector2<double>(0.1, 0.1), true, Vector2<double>(0.5, 0.5));
  EXPECT_FALSE(r.torquing);
  EXPECT_EQ(r.flags, 0u);
  const TorqueCommand<double> t = law.torque_command(kCentred, r, kZero, kSpin, 0.0);
  EXPECT_EQ(t.torque, kZero);
}

TEST(TorqueLaw, CagedTheGimbalClosesOnTheBodyAtTheCageGain) {
  GYRO_VERIFIES("TORQ-1");
  const TorqueLaw<double> law(kSeeker);
  const Vector2<double> g(0.01, -0.02), body(0.05, -0.03);  // within the rate limits
  const GimbalFrame<double> f = gimbal_frame_at(g);
  const RateCommand<double> r = law.rate_command(GyroMode::kCaged, f, body, g, true, Vector2<double>(0.9, 0.9));
  // th' = -k th and ps' = -k ps: the yaw rate on z_I is ps' cos th.
  const double k = kSeeker.cage_gain_1_s;
  EXPECT_TRUE(r.torquing);
  EXPECT_NEAR(r.rate_rad_s(0) - body(0), -k * g(0), 1e-15);
  EXPECT_NEAR(r.rate_rad_s(1) - body(1), -k * g(1) * std::cos(g(0)), 1e-15);
  const RateCommand<double> stale = law.rate_command(GyroMode::kCaged, f, body, g, false, kZero);
  EXPECT_EQ(stale.rate_rad_s, body) << "without a fresh reading the spin axis follows the body alone";
}

TEST(TorqueLaw, UncagingTorquesOnlyWhileProtecting) {
  GYRO_VERIFIES("TORQ-2", "STOP-1");
  const TorqueLaw<double> law(kSeeker);
  EXPECT_FALSE(law.rate_command(GyroMode::kUncaging, kCentred, Vector2<double>(0.5, 0), kZero, true, kZero).torquing);
  // Near the protection cone (0.45 rad) with the body turning it outward.
  const Vector2<double> g(0.44, 0.0);
  const RateCommand<double> r =
      law.rate_command(GyroMode::kUncaging, gimbal_frame_at(g), Vector2<double>(-0.5, 0), g, true, kZero);
  EXPECT_TRUE(r.torquing);
  EXPECT_TRUE(r.protecting);
  EXPECT_EQ(r.flags & kGimbalStopProtect, static_cast<std::uint32_t>(kGimbalStopProtect));
}

TEST(TorqueLaw, FreeTheSlewIsFlownWithinItsLimits) {
  GYRO_VERIFIES("TORQ-2", "TORQ-3");
  GyroComponentConfig<double> c = kSeeker;
  c.max_pitch_rate_rad_s = 0.5;
  c.max_yaw_rate_rad_s = 0.25;
  const TorqueLaw<double> law(c);
  const RateCommand<double> within = free_slew(law, Vector2<double>(-0.5, 0.25));
  EXPECT_EQ(within.rate_rad_s, Vector2<double>(-0.5, 0.25));
  EXPECT_EQ(within.flags, 0u) << "the limits are inclusive";
  const RateCommand<double> beyond = free_slew(law, Vector2<double>(0.3, -0.3));
  EXPECT_EQ(beyond.rate_rad_s, Vector2<double>(0.3, -0.25)) << "each axis by its own limit";
  EXPECT_EQ(beyond.flags, static_cast<std::uint32_t>(kSlewRateLimited));
}

TEST(TorqueLaw, TorquersHoldTheRateInSteadyPrecession) {
  GYRO_VERIFIES("TORQ-4");
  // At zero gimbal angles, body at rest: the report's steady precession under T1, T2 is w1 = (f T1
  // - H T2) / (f^2 + H^2), w2 = (H T1 + f T2) / (f^2 + H^2).
  const TorqueLaw<double> law(kSeeker);
  const Vector2<double> w(0.2, -0.3);
  const TorqueCommand<double> t = law.torque_command(kCentred, free_slew(law, w), kZero, kSpin, 0.0);
  const double f = kSeeker.friction, d = f * f + kH * kH;
  EXPECT_NEAR((f * t.torque(0) - kH * t.torque(1)) / d, w(0), 1e-15);
  EXPECT_NEAR((kH * t.torque(0) + f * t.torque(1)) / d, w(1), 1e-15);
  EXPECT_EQ(t.flags, 0u);
}

TEST(TorqueLaw, WithoutCompensationTheTorqueIsTheReportsHRate) {
  GYRO_VERIFIES("TORQ-4");
  GyroComponentConfig<double> c = kSeeker;
  c.friction_compensation = false;
  const TorqueLaw<double> law(c);
  const Vector2<double> w(0.2, -0.3);
  const TorqueCommand<double> t = law.torque_command(kCentred, free_slew(law, w), kZero, kSpin, 0.0);
  EXPECT_NEAR(t.torque(0), kH * w(1), 1e-17);
  EXPECT_NEAR(t.torque(1), -kH * w(0), 1e-17);
}

TEST(TorqueLaw, TheInnerGimbalsRollAddsToTheMomentum) {
  GYRO_VERIFIES("TORQ-4");
  const TorqueLaw<double> law(kSeeker);
  const RateCommand<double> r = free_slew(law, Vector2<double>(0, 0.2));
  const double roll = 30.0;
  const TorqueCommand<double> rolling = law.torque_command(kCentred, r, kZero, kSpin, roll);
  EXPECT_NEAR(rolling.torque(0), (kH + kSeeker.spin_inertia * roll) * 0.2, 1e-15);
}

TEST(TorqueLaw, BeyondTheTorquerTheSlewIsScaledInDirection) {
  GYRO_VERIFIES("TORQ-5");
  const TorqueLaw<double> law(kSeeker);
  const Vector2<double> w(0.9, 0.6);  // torquers (0.046, -0.068): within max_torque 0.1, beyond 0.02
  GyroComponentConfig<double> weak = kSeeker;
  weak.max_torque = 0.02;
  const TorqueLaw<double> weak_law(weak);
  const TorqueCommand<double> full = law.torque_command(kCentred, free_slew(law, w), kZero, kSpin, 0.0);
  const TorqueCommand<double> cut = weak_law.torque_command(kCentred, free_slew(weak_law, w), kZero, kSpin, 0.0);
  ASSERT_GT(full.torque.cwiseAbs().maxCoeff(), 0.02);
  EXPECT_EQ(cut.flags, static_cast<std::uint32_t>(kTorquerSaturated));
  EXPECT_DOUBLE_EQ(cut.torque.cwiseAbs().maxCoeff(), 0.02);
  EXPECT_NEAR(cut.torque(0) * full.torque(1) - cut.torque(1) * full.torque(0), 0.0, 1e-18) << "same direction";
}

TEST(TorqueLaw, OverflowingProductsStillSaturateInDirection) {
  GYRO_VERIFIES("TORQ-5");
  GyroComponentConfig<double> c = kSeeker;
  c.max_pitch_rate_rad_s = 1e308;
  c.max_yaw_rate_rad_s = 1e308;
  const TorqueLaw<double> law(c);  // beyond the contract: the law alone
  // h = 18.8 at 1e5 Hz: h w_y = 1.9e308 overflows. The torquers are in the ratio of (h w_z + f w_y,
  // -h w_y + f w_z), about (-0.5, -1).
  const TorqueCommand<double> t =
      law.torque_command(kCentred, free_slew(law, Vector2<double>(1e307, -5e306)), kZero, 1e5, 0.0);
  EXPECT_EQ(t.flags, static_cast<std::uint32_t>(kTorquerSaturated));
  EXPECT_EQ(t.torque(1), -kSeeker.max_torque);
  EXPECT_NEAR(t.torque(0) / t.torque(1), 0.5, 1e-4);
}

TEST(TorqueLaw, BeyondAuthorityNearTheStopIsFlagged) {
  GYRO_VERIFIES("STOP-3");
  // The body turns the gimbal outward at the protection cone faster than the torquer can follow:
  // H x 5 rad/s = 0.38, beyond max_torque 0.1 (the rate limits raised out of the way).
  GyroComponentConfig<double> c = kSeeker;
  c.max_pitch_rate_rad_s = 10.0;
  c.max_yaw_rate_rad_s = 10.0;
  const TorqueLaw<double> law(c);
  const Vector2<double> g(0.45, 0.0);
  const GimbalFrame<double> f = gimbal_frame_at(g);
  const Vector2<double> body(-5.0, 0.0);
  const RateCommand<double> r = law.rate_command(GyroMode::kFree, f, body, g, true, kZero);
  const TorqueCommand<double> t = law.torque_command(f, r, body, kSpin, 0.0);
  EXPECT_TRUE(r.protecting);
  EXPECT_EQ(t.flags, static_cast<std::uint32_t>(kTorquerSaturated | kStopBeyondAuthority));
  const Vector2<double> slow_body(-0.5, 0.0);
  const TorqueCommand<double> slow =
      law.torque_command(f, law.rate_command(GyroMode::kFree, f, slow_body, g, true, kZero), slow_body, kSpin, 0.0);
  EXPECT_EQ(slow.flags, 0u) << "0.5 rad/s is within authority";
}

TEST(TorqueLaw, SaturatedWhileProtectingTheHoldComesFirst) {
  GYRO_VERIFIES("STOP-4", "TORQ-5");
  // At the protection cone the body turns the gimbal outward while guidance asks a slew across;
  // a weak torquer cannot give both. The part across is dropped: the torque written is the one
  // that holds the outward rate alone, which this torquer can give unsaturated.
  GyroComponentConfig<double> weak = kSeeker;
  weak.max_torque = 0.05;
  const TorqueLaw<double> law(weak);
  const Vector2<double> g(0.45, 0.0);
  const GimbalFrame<double> f = gimbal_frame_at(g);
  const Vector2<double> body(-0.5, 0.0);
  const RateCommand<double> r = law.rate_command(GyroMode::kFree, f, body, g, true, Vector2<double>(0.0, 1.0));
  ASSERT_TRUE(r.protecting);
  RateCommand<double> asked = r;
  asked.protecting = false;
  ASSERT_EQ(law.torque_command(f, asked, body, kSpin, 0.0).flags & kTorquerSaturated,
            static_cast<std::uint32_t>(kTorquerSaturated))
      << "the whole command is beyond the torquer";
  RateCommand<double> hold = asked;
  hold.rate_rad_s = r.outward * r.outward_rate_rad_s;
  const TorqueCommand<double> held = law.torque_command(f, hold, body, kSpin, 0.0);
  ASSERT_EQ(held.flags & kTorquerSaturated, 0u) << "the hold alone is within it";
  const TorqueCommand<double> t = law.torque_command(f, r, body, kSpin, 0.0);
  EXPECT_EQ(t.torque, held.torque);
  EXPECT_EQ(t.flags & kTorquerSaturated, 0u);
}

TEST(TorqueLaw, ARateCutByItsLimitNearTheStopIsBeyondAuthority) {
  GYRO_VERIFIES("STOP-3");
  // The seeker's 1 rad/s limit cuts the rate that would follow a body turning at 5 rad/s.
  const TorqueLaw<double> law(kSeeker);
  const Vector2<double> g(0.45, 0.0);
  const GimbalFrame<double> f = gimbal_frame_at(g);
  const Vector2<double> body(-5.0, 0.0);
  const RateCommand<double> r = law.rate_command(GyroMode::kFree, f, body, g, true, kZero);
  EXPECT_EQ(r.flags, static_cast<std::uint32_t>(kGimbalStopProtect | kSlewRateLimited));
  EXPECT_EQ(law.torque_command(f, r, body, kSpin, 0.0).flags, static_cast<std::uint32_t>(kStopBeyondAuthority));
}

}  // namespace torque_law_test
}  // namespace gyro
