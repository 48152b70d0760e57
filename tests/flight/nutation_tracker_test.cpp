// The nutation tracker (gyro/nutation_tracker.hpp): the nutation frequency as the torquers see
// it at the spin flown, the gimbal's pitch and the inner gimbal's roll, and the shaper's design
// for it, kept within a tolerance of the frequency they were made for.
#include <gtest/gtest.h>

#include <cmath>

#include "gyro/nutation_tracker.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace nutation_tracker_test {

struct Rotor {
  double pitch_inertia{2e-4};
  double yaw_inertia{2e-4};
  double friction{0};
  double spin_inertia{1e-4};
  double tick_s{1e-3};
  double gimbal_cone_limit_rad{0.5};
  double max_body_rate_rad_s{100};
};

const GimbalFrame<double> kCentred{};  // zero gimbal angles

// The frame at pitch th (only its sine and cosine enter the nutation).
GimbalFrame<double> pitched(double th) {
  GimbalFrame<double> f;
  f.sin_pitch = std::sin(th);
  f.cos_pitch = std::cos(th);
  return f;
}

TEST(NutationTracker, BetaIsTheMomentumOverTheGimbalInertia) {
  GYRO_VERIFIES("SHAPE-1");
  NutationTracker<double> n;
  const Rotor r;
  const NutationUpdate<double> u = n.follow(100.0, 0.0, kCentred, r);
  ASSERT_TRUE(u.redesigned);
  const double h = 2 * kPi<double> * 100.0 * r.spin_inertia;  // H = 2 pi f Is
  EXPECT_NEAR(n.beta_rad_s(), h / r.pitch_inertia, 1e-12 * h / r.pitch_inertia);
  EXPECT_EQ(u.shaper.spacing, design_shaper(n.beta_rad_s() * r.tick_s).spacing);
  EXPECT_FALSE(n.aliased());
}

TEST(NutationTracker, TheDesignIsKeptWithinTheSpinTolerance) {
  GYRO_VERIFIES("SHAPE-3");
  NutationTracker<double> n;
  const Rotor r;
  ASSERT_TRUE(n.follow(100.0, 0.0, kCentred, r).redesigned);
  EXPECT_FALSE(n.follow(100.0 * (1 + 0.9e-3), 0.0, kCentred, r).redesigned);
  EXPECT_FALSE(n.follow(100.0 * (1 - 0.9e-3), 0.0, kCentred, r).redesigned);
  EXPECT_TRUE(n.follow(100.0 * (1 + 1.1e-3), 0.0, kCentred, r).redesigned);
  EXPECT_TRUE(n.follow(100.0 * (1 + 1.1e-3) * (1 - 1.1e-3), 0.0, kCentred, r).redesigned);
}

TEST(NutationTracker, ForgettingRedesignsAtTheSameSpin) {
  GYRO_VERIFIES("SHAPE-3");
  NutationTracker<double> n;
  const Rotor r;
  (void)n.follow(100.0, 0.0, kCentred, r);
  n.forget();
  EXPECT_TRUE(n.follow(100.0, 0.0, kCentred, r).redesigned);
}

TEST(NutationTracker, FewerThanTwoTicksPerPeriodAliases) {
  GYRO_VERIFIES("TLM-3");
  NutationTracker<double> n;
  Rotor r;
  r.tick_s = 1.01 * kPi<double> / (2 * kPi<double> * 100.0 * r.spin_inertia / r.pitch_inertia);
  (void)n.follow(100.0, 0.0, kCentred, r);
  EXPECT_TRUE(n.aliased());
}

// The aliasing follows the spin: beta = pi f here, pi f / 1000 a 1 ms tick, aliased above 1 kHz.
TEST(NutationTracker, AliasingFollowsTheSpin) {
  GYRO_VERIFIES("TLM-3", "SHAPE-3");
  NutationTracker<double> n;
  const Rotor r;
  (void)n.follow(1500.0, 0.0, kCentred, r);
  EXPECT_TRUE(n.aliased());
  (void)n.follow(500.0, 0.0, kCentred, r);
  EXPECT_FALSE(n.aliased()) << "the spin dropped below twice the tick rate of nutation";
  (void)n.follow(1500.0, 0.0, kCentred, r);
  EXPECT_TRUE(n.aliased());
}

TEST(NutationTracker, NoSpinNoNutationNoShaper) {
  GYRO_VERIFIES("SHAPE-1");
  NutationTracker<double> n;
  const NutationUpdate<double> u = n.follow(0.0, 0.0, kCentred, Rotor{});
  EXPECT_TRUE(u.redesigned);
  EXPECT_EQ(n.beta_rad_s(), 0.0);
  EXPECT_EQ(u.shaper.spacing, 0u);
}

// The motor-held spin adds C tan^2 th to the yaw inertia at pitch th (docs/gimbal-plant.md, the
// mass matrix with the spin held, for the spin axis's rate on z_I and massless rings).
TEST(NutationTracker, PitchAddsTheSpinInertiaToTheYaw) {
  GYRO_VERIFIES("SHAPE-3");
  EXPECT_DOUBLE_EQ(yaw_inertia_at_pitch(2e-4, 1e-4, 0.0), 2e-4);
  EXPECT_DOUBLE_EQ(yaw_inertia_at_pitch(2e-4, 1e-4, 0.5), 2e-4 + 1e-4 * 0.25);
  NutationTracker<double> n;
  const Rotor r;
  const double th = 0.35;
  (void)n.follow(100.0, 0.0, pitched(th), r);
  // H / sqrt(J1 J2) with J2 = (C s^2 + J c^2) / c^2: the yaw row of the held-spin mass
  // matrix (Oz + (Ix + J0) s^2 + (Iz + A) c^2) over cos^2 th, with the rings massless (A = J).
  const double h = 2 * kPi<double> * 100.0 * r.spin_inertia;
  const double s = std::sin(th), c = std::cos(th);
  const double j2 = (r.spin_inertia * s * s + r.yaw_inertia * c * c) / (c * c);
  EXPECT_NEAR(n.beta_rad_s(), h / std::sqrt(r.pitch_inertia * j2), 1e-12 * h / r.pitch_inertia);
}

TEST(NutationTracker, ThePitchMovingTheNutationRedesigns) {
  GYRO_VERIFIES("SHAPE-3");
  NutationTracker<double> n;
  const Rotor r;
  ASSERT_TRUE(n.follow(100.0, 0.0, kCentred, r).redesigned);
  // J2 grows by C tan^2 th / J2 = tan^2 th / 2: beta falls by about tan^2 th / 4.
  EXPECT_FALSE(n.follow(100.0, 0.0, pitched(0.05), r).redesigned);  // 0.06 %
  EXPECT_TRUE(n.follow(100.0, 0.0, pitched(0.2), r).redesigned);    // 1 %
}

// The inner gimbal rolling at r: the rotor's momentum is C (spin + r), and the torquers, which
// roll with the inner gimbal, see the nutation (turning with the spin) slower by r.
TEST(NutationTracker, RollAddsToTheMomentumAndTurnsTheTorquers) {
  GYRO_VERIFIES("SHAPE-3");
  NutationTracker<double> n;
  const Rotor r;
  const double roll = 40.0;
  (void)n.follow(100.0, roll, kCentred, r);
  const double h = r.spin_inertia * (2 * kPi<double> * 100.0 + roll);
  EXPECT_NEAR(n.beta_rad_s(), h / r.pitch_inertia - roll, 1e-12 * h / r.pitch_inertia);
}

TEST(NutationTracker, GeometryBeyondTheEnvelopeDesignsForItsEdge) {
  GYRO_VERIFIES("SHAPE-3");
  const Rotor r;
  NutationTracker<double> beyond, edge;
  (void)beyond.follow(100.0, 1e30, pitched(1.5), r);  // an estimate gone wild, as after a fault
  (void)edge.follow(100.0, r.max_body_rate_rad_s, pitched(r.gimbal_cone_limit_rad), r);
  EXPECT_DOUBLE_EQ(beyond.beta_rad_s(), edge.beta_rad_s());
  EXPECT_GT(beyond.beta_rad_s(), 0.0);
}

TEST(NutationTracker, AnOverflowingSpinGivesNoShaper) {
  GYRO_VERIFIES("SHAPE-1");
  NutationTracker<double> n;
  const NutationUpdate<double> u = n.follow(1e300, 0.0, kCentred, Rotor{});
  EXPECT_EQ(n.beta_rad_s(), 0.0);
  EXPECT_EQ(u.shaper.spacing, 0u);
}

}  // namespace nutation_tracker_test
}  // namespace gyro
