// The line of sight and the tracker's command law (apps/los_tracking.hpp) against hand-worked
// geometry: a pointing error about one gimbal axis, a LOS turning about earth z seen from a
// body rolled a quarter turn, a crossing target's angle differentiated, the rate limits.
#include <gtest/gtest.h>

#include <cmath>

#include "los_tracking.hpp"

namespace gyro::sil::los_tracking_test {
namespace {

const Eigen::Vector2d kNoLimit(1e9, 1e9);

// R_earth_to_body of a body rolled by phi about x (earth axes seen from the body).
Eigen::Matrix3d rolled(double phi) {
  Eigen::Matrix3d r;
  r << 1, 0, 0, 0, std::cos(phi), std::sin(phi), 0, -std::sin(phi), std::cos(phi);
  return r;
}

TEST(TrackCommand, AnErrorAboveTheSpinAxisIsAPitchCommand) {
  // theta > 0 tilts the spin axis toward -z (docs/conventions.md): a LOS pitched up by a.
  const double a = 0.01, k = 20;
  LineOfSight los;
  los.direction = Eigen::Vector3d(std::cos(a), 0, -std::sin(a));
  const Eigen::Vector2d cmd = track_command(los, Eigen::Vector3d::UnitX(), Eigen::Matrix3d::Identity(), k, kNoLimit);
  EXPECT_NEAR(cmd(0), k * a, 1e-12);
  EXPECT_NEAR(cmd(1), 0.0, 1e-12);
}

TEST(TrackCommand, AnErrorRightOfTheSpinAxisIsAYawCommand) {
  const double a = 0.2, k = 5;
  LineOfSight los;
  los.direction = Eigen::Vector3d(std::cos(a), std::sin(a), 0);
  const Eigen::Vector2d cmd = track_command(los, Eigen::Vector3d::UnitX(), Eigen::Matrix3d::Identity(), k, kNoLimit);
  EXPECT_NEAR(cmd(0), 0.0, 1e-12);
  EXPECT_NEAR(cmd(1), k * a, 1e-12);  // the angle itself, not its sine
}

TEST(TrackCommand, OnTheLosTheCommandIsTheLosRateOnTheGimbalAxes) {
  // The LOS turns about earth z at w; a body rolled +90 deg about x sees earth z along its +y,
  // which at zero gimbal angles is the pitch gimbal axis.
  const double w = 0.3;
  LineOfSight los;
  los.rate_rad_s = Eigen::Vector3d(0, 0, w);
  const Eigen::Vector2d level = track_command(los, Eigen::Vector3d::UnitX(), Eigen::Matrix3d::Identity(), 50, kNoLimit);
  EXPECT_NEAR(level(0), 0.0, 1e-15);
  EXPECT_NEAR(level(1), w, 1e-15);
  const Eigen::Vector2d on_side = track_command(los, Eigen::Vector3d::UnitX(), rolled(M_PI / 2), 50, kNoLimit);
  EXPECT_NEAR(on_side(0), w, 1e-15);
  EXPECT_NEAR(on_side(1), 0.0, 1e-15);
}

TEST(TrackCommand, EachAxisIsHeldWithinItsRateLimit) {
  LineOfSight los;
  los.direction = Eigen::Vector3d(std::cos(0.3), -std::sin(0.3), 0).normalized();
  los.rate_rad_s = Eigen::Vector3d(0, 0.5, 0);
  const Eigen::Vector2d cmd =
      track_command(los, Eigen::Vector3d::UnitX(), Eigen::Matrix3d::Identity(), 100, Eigen::Vector2d(0.25, 0.75));
  EXPECT_EQ(cmd(0), 0.25);  // the LOS rate about earth y is a pitch rate of 0.5
  EXPECT_EQ(cmd(1), -0.75);
}

TEST(LineOfSight, ACrossingTargetsRateIsItsAngleDifferentiated) {
  // Abeam at 1000 m, crossing at 100 m/s: the LOS angle is atan(100 t / 1000) about earth z.
  LineOfSightSpec spec;
  spec.source = LineOfSightSpec::Source::kTargetGeometry;
  spec.target_position_m = Eigen::Vector3d(1000, 0, 0);
  spec.target_velocity_m_s = Eigen::Vector3d(0, 100, 0);
  for (double t : {0.0, 2.0, 5.0}) {
    const LineOfSight los = line_of_sight_at(spec, t);
    const double angle = std::atan(0.1 * t), rate = 0.1 / (1 + 0.01 * t * t);
    EXPECT_NEAR(los.direction(0), std::cos(angle), 1e-15) << t;
    EXPECT_NEAR(los.direction(1), std::sin(angle), 1e-15) << t;
    EXPECT_NEAR(los.rate_rad_s(2), rate, 1e-15) << t;
    EXPECT_NEAR(los.rate_rad_s.head<2>().norm(), 0.0, 1e-15) << t;
  }
  EXPECT_NEAR(closest_range_m(spec, 10), 1000.0, 1e-12);
  spec.target_velocity_m_s = Eigen::Vector3d(-100, 10, 0);  // passes at t = 9.9 s
  EXPECT_NEAR(closest_range_m(spec, 20), 1000 * 10 / std::hypot(100.0, 10.0), 1e-9);
  EXPECT_NEAR(closest_range_m(spec, 1), (Eigen::Vector3d(900, 10, 0)).norm(), 1e-9);
}

TEST(LineOfSight, AnInertialLosMovesAtItsRateNormalToIt) {
  // A rate with a part along the LOS: only the normal part moves it (central differences).
  LineOfSightSpec spec;
  spec.direction = Eigen::Vector3d(1, 0, 0);
  spec.rate_rad_s = Eigen::Vector3d(0.3, -0.1, 0.5);
  const double h = 1e-5;
  for (double t : {0.0, 0.7, 3.0}) {
    const LineOfSight los = line_of_sight_at(spec, t);
    const Eigen::Vector3d du =
        (line_of_sight_at(spec, t + h).direction - line_of_sight_at(spec, t - h).direction) / (2 * h);
    EXPECT_NEAR(los.direction.norm(), 1.0, 1e-15);
    EXPECT_NEAR(los.rate_rad_s.dot(los.direction), 0.0, 1e-15);
    EXPECT_NEAR((los.direction.cross(du) - los.rate_rad_s).norm(), 0.0, 1e-9) << t;
  }
}

TEST(LineOfSight, AnglesBetweenUnitVectorsAreExactNearZeroAndPi) {
  EXPECT_NEAR(angle_between(Eigen::Vector3d::UnitX(), Eigen::Vector3d(std::cos(1e-9), std::sin(1e-9), 0)), 1e-9, 1e-24);
  EXPECT_NEAR(angle_between(Eigen::Vector3d::UnitX(), Eigen::Vector3d(-1, 1e-9, 0).normalized()), M_PI - 1e-9, 1e-15);
}

}  // namespace
}  // namespace gyro::sil::los_tracking_test
