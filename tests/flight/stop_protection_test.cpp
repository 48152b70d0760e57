// The stop protection's bound (gyro/stop_protection.hpp), without a port: the outward
// direction against the cone angle's own rate of change, the bound's three regions, and the
// torque law's inverse the authority check uses.
#include <gtest/gtest.h>

#include <cmath>

#include "gyro/stop_protection.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace stop_protection_test {

constexpr double kProtectCone = 0.32;
const StopBound<double> kBound{std::sin(kProtectCone), 20.0};
const Vector2<double> kZero = Vector2<double>::Zero();

// The cone angle (spin axis against body x) at gimbal angles (pitch, yaw).
double cone(const Vector2<double>& g) { return std::acos(std::cos(g(0)) * std::cos(g(1))); }

// The cone's rate when the spin axis moves at `relative` (on y_I, z_I) against the body, by a
// central difference of the gimbal angles' own kinematics: th' = r_y, ps' = r_z / cos th.
double cone_rate(const Vector2<double>& g, const Vector2<double>& relative) {
  const double h = 1e-6;
  const Vector2<double> d(relative(0), relative(1) / std::cos(g(0)));
  return (cone(g + h * d) - cone(g - h * d)) / (2 * h);
}

TEST(StopProtection, OutwardDirectionIsTheConeAnglesGradient) {
  GYRO_VERIFIES("STOP-1");
  for (const Vector2<double>& g : {Vector2<double>(0.3, 0.0), Vector2<double>(0.0, -0.25),
                                   Vector2<double>(0.2, 0.2), Vector2<double>(-0.35, 0.1)}) {
    const GimbalFrame<double> f = gimbal_frame_at(g);
    for (const Vector2<double>& r : {Vector2<double>(1, 0), Vector2<double>(0, 1), Vector2<double>(0.6, -0.8)}) {
      const OutwardExcess<double> e = outward_excess(f, r, kZero, StopBound<double>{1, 0});
      EXPECT_NEAR(e.rate_rad_s, cone_rate(g, r), 1e-8) << g.transpose() << " / " << r.transpose();
      EXPECT_NEAR(e.outward.norm(), 1.0, 1e-15);
    }
  }
}

TEST(StopProtection, FarInsideTheBoundTheRateIsFlownAsAsked) {
  GYRO_VERIFIES("STOP-1");
  const GimbalFrame<double> f = gimbal_frame_at(Vector2<double>(0.1, 0.05));
  const Vector2<double> wanted(0.3, -0.2), body(0.4, 0.1);
  const ProtectedRate<double> p = protect_stop(f, wanted, body, kBound);
  EXPECT_FALSE(p.acting);
  EXPECT_TRUE(p.rate_rad_s == wanted);
}

TEST(StopProtection, AtTheBoundTheBodysTurnIsFollowed) {
  GYRO_VERIFIES("STOP-1");
  // A free gyro (no command) on a body yawing at 0.45 rad/s, the gimbal near the protection
  // cone in yaw: the body's turn carries the gimbal outward.
  const Vector2<double> g(0.0, kProtectCone - 0.005);
  const GimbalFrame<double> f = gimbal_frame_at(g);
  const Vector2<double> body(0.0, -0.45);
  ASSERT_GT(cone_rate(g, -body), 0.4) << "outward without protection";
  const ProtectedRate<double> p = protect_stop(f, kZero, body, kBound);
  ASSERT_TRUE(p.acting);
  const double allowed = kBound.gain_1_s * (kBound.sin_protect - std::sin(cone(g))) / std::cos(cone(g));
  EXPECT_NEAR(cone_rate(g, p.rate_rad_s - body), allowed, 1e-8) << "the cone moves at the bound's rate";
  EXPECT_NEAR(p.rate_rad_s(0), 0.0, 1e-15) << "moved along the outward direction only";
}

TEST(StopProtection, BeyondTheProtectionConeTheGimbalIsDrivenBack) {
  GYRO_VERIFIES("STOP-1");
  const Vector2<double> g(kProtectCone + 0.01, 0.02);
  const GimbalFrame<double> f = gimbal_frame_at(g);
  const Vector2<double> wanted(0.2, 0.3);  // a command outward, across too
  const ProtectedRate<double> p = protect_stop(f, wanted, kZero, kBound);
  ASSERT_TRUE(p.acting);
  EXPECT_LT(cone_rate(g, p.rate_rad_s), -0.1) << "inward at k (sin c - sin c_p) / cos c";
  const Vector2<double> across(-p.outward(1), p.outward(0));
  EXPECT_NEAR(across.dot(p.rate_rad_s), across.dot(wanted), 1e-15) << "the command across is kept";
}

TEST(StopProtection, CentredGimbalHasNoOutwardDirection) {
  GYRO_VERIFIES("STOP-1");
  const GimbalFrame<double> f = gimbal_frame_at(kZero);
  const ProtectedRate<double> p = protect_stop(f, Vector2<double>(50, -50), kZero, kBound);
  EXPECT_FALSE(p.acting);
  EXPECT_TRUE(p.rate_rad_s.allFinite());
}

TEST(StopProtection, FloatBoundAgreesWithDouble) {
  GYRO_VERIFIES("STOP-1", "RULE-8");
  const Vector2<double> g(0.25, -0.15);
  const ProtectedRate<double> d = protect_stop(gimbal_frame_at(g), Vector2<double>(1.0, -1.5),
                                               Vector2<double>(0.1, 0.2), kBound);
  const StopBound<float> bound_f{static_cast<float>(kBound.sin_protect), 20.0f};
  const ProtectedRate<float> s = protect_stop(gimbal_frame_at(Vector2<float>(g.cast<float>())),
                                              Vector2<float>(1.0f, -1.5f), Vector2<float>(0.1f, 0.2f), bound_f);
  ASSERT_TRUE(d.acting);
  ASSERT_TRUE(s.acting);
  EXPECT_NEAR(s.rate_rad_s(0), d.rate_rad_s(0), 1e-5);
  EXPECT_NEAR(s.rate_rad_s(1), d.rate_rad_s(1), 1e-5);
}

TEST(TorqueLawInverse, RateForTorquersUndoesTorquersForRate) {
  GYRO_VERIFIES("TORQ-4");
  for (const Vector2<double>& g : {Vector2<double>(0.0, 0.0), Vector2<double>(0.4, -0.3), Vector2<double>(-1.2, 2.0)}) {
    const GimbalFrame<double> f = gimbal_frame_at(g);
    for (const double friction : {0.0, 4e-4}) {
      const Vector2<double> rate(0.3, -0.7), body(-0.2, 0.5);
      const Vector2<double> t = torquers_for_rate(f, 0.0754, friction, rate, body);
      const Vector2<double> back = rate_for_torquers(f, 0.0754, friction, t, body);
      EXPECT_NEAR(back(0), rate(0), 1e-13);
      EXPECT_NEAR(back(1), rate(1), 1e-13);
    }
  }
  const GimbalFrame<double> f = gimbal_frame_at(Vector2<double>(0.1, 0.1));
  EXPECT_TRUE(rate_for_torquers(f, 0.0, 0.0, Vector2<double>(1, 1), Vector2<double>(1, 1)).isZero())
      << "no spin and no friction: no rate is held";
}

}  // namespace stop_protection_test
}  // namespace gyro
