// The nutation tracker (gyro/nutation_tracker.hpp): the nutation frequency and the shaper's
// design at the spin flown, kept within a tolerance of the spin they were made for.
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
};

TEST(NutationTracker, BetaIsTheMomentumOverTheGimbalInertia) {
  GYRO_VERIFIES("SHAPE-1");
  NutationTracker<double> n;
  const Rotor r;
  const NutationUpdate<double> u = n.follow(100.0, r);
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
  ASSERT_TRUE(n.follow(100.0, r).redesigned);
  EXPECT_FALSE(n.follow(100.0 * (1 + 0.9e-3), r).redesigned);
  EXPECT_FALSE(n.follow(100.0 * (1 - 0.9e-3), r).redesigned);
  EXPECT_TRUE(n.follow(100.0 * (1 + 1.1e-3), r).redesigned);
}

TEST(NutationTracker, ForgettingRedesignsAtTheSameSpin) {
  GYRO_VERIFIES("SHAPE-3");
  NutationTracker<double> n;
  const Rotor r;
  (void)n.follow(100.0, r);
  n.forget();
  EXPECT_TRUE(n.follow(100.0, r).redesigned);
}

TEST(NutationTracker, FewerThanTwoTicksPerPeriodAliases) {
  GYRO_VERIFIES("TLM-3");
  NutationTracker<double> n;
  Rotor r;
  r.tick_s = 1.01 * kPi<double> / (2 * kPi<double> * 100.0 * r.spin_inertia / r.pitch_inertia);
  (void)n.follow(100.0, r);
  EXPECT_TRUE(n.aliased());
}

// The aliasing follows the spin: beta = pi f here, pi f / 1000 a 1 ms tick, aliased above 1 kHz.
TEST(NutationTracker, AliasingFollowsTheSpin) {
  GYRO_VERIFIES("TLM-3", "SHAPE-3");
  NutationTracker<double> n;
  const Rotor r;
  (void)n.follow(1500.0, r);
  EXPECT_TRUE(n.aliased());
  (void)n.follow(500.0, r);
  EXPECT_FALSE(n.aliased()) << "the spin dropped below twice the tick rate of nutation";
  (void)n.follow(1500.0, r);
  EXPECT_TRUE(n.aliased());
}

TEST(NutationTracker, NoSpinNoNutationNoShaper) {
  GYRO_VERIFIES("SHAPE-1");
  NutationTracker<double> n;
  const NutationUpdate<double> u = n.follow(0.0, Rotor{});
  EXPECT_TRUE(u.redesigned);
  EXPECT_EQ(n.beta_rad_s(), 0.0);
  EXPECT_EQ(u.shaper.spacing, 0u);
}

}  // namespace nutation_tracker_test
}  // namespace gyro
