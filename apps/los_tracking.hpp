// Line-of-sight tracking in the software-in-the-loop run (docs/scenarios.md, guidance.track):
// the line of sight (LOS) to a target over time, and the tracker's slew command that points the
// spin axis along it, as a seeker's track loop does through the component.
//
// The LOS is either an inertial direction turning at a constant inertial rate, or the direction
// from the own position to a target's, both moving at constant velocity in the earth frame. Its
// inertial rate is omega_L = u x u' (normal to the LOS u).
//
// The command each tick is the LOS rate plus gain times the pointing error seen through the
// component: the rotation vector from the spin axis the component estimates to the LOS,
//   omega_cmd = omega_L + K * angle(x_est, u) * unit(x_est x u),
// given on the inner gimbal axes (y_I, z_I) of the estimated spin axis at the body's current
// attitude (the axes the component flies slew commands on, gyro/component_types.hpp), and held
// within the component's slew-rate limits per axis, as the component's torque law limits them.
// Truth and command are computed in double whatever scalar the run uses.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace gyro::sil {

struct LineOfSightSpec {
  enum class Source : std::uint8_t { kInertial, kTargetGeometry };
  Source source{Source::kInertial};
  // kInertial: the unit direction at t = 0 (earth axes) and the constant inertial rate.
  Eigen::Vector3d direction{1, 0, 0};
  Eigen::Vector3d rate_rad_s{Eigen::Vector3d::Zero()};
  // kTargetGeometry: positions at t = 0 and constant velocities, earth axes.
  Eigen::Vector3d target_position_m{Eigen::Vector3d::Zero()};
  Eigen::Vector3d target_velocity_m_s{Eigen::Vector3d::Zero()};
  Eigen::Vector3d own_position_m{Eigen::Vector3d::Zero()};
  Eigen::Vector3d own_velocity_m_s{Eigen::Vector3d::Zero()};
};

// The largest tracker gain accepted, as a fraction of 1 / tick: with the estimate one tick old,
// the loop's pointing error obeys e[k+1] = e[k] - K dt e[k-1], whose roots stay real (no
// overshoot) up to K dt = 1/4.
inline constexpr double kMaxTrackGainTicks = 0.25;
// The largest inertial rate of an inertial LOS (rad/s), and the closest range a target may come
// to the own position over the run (m): beyond them the LOS turns faster than any seeker slews.
inline constexpr double kMaxLosRateRadS = 100.0;
inline constexpr double kMinTrackRangeM = 1.0;

struct TrackSpec {
  double start_s{0};
  std::uint64_t start_tick{0};  // round(start_s / tick_s): the first tick the tracker commands
  double gain_1_s{0};
  LineOfSightSpec los{};
};

// The LOS at time t: its unit direction and its inertial rate (normal to it), earth axes.
struct LineOfSight {
  Eigen::Vector3d direction{1, 0, 0};
  Eigen::Vector3d rate_rad_s{Eigen::Vector3d::Zero()};
};

[[nodiscard]] LineOfSight line_of_sight_at(const LineOfSightSpec& spec, double t_s);

// The target's closest range to the own position over [0, duration_s] (kTargetGeometry).
[[nodiscard]] double closest_range_m(const LineOfSightSpec& spec, double duration_s);

// The angle between two unit vectors (rad), accurate near 0 and pi.
[[nodiscard]] double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

// The spin axis in earth axes at the gimbal angles (pitch, yaw) on a body at R_earth_to_body.
[[nodiscard]] Eigen::Vector3d spin_axis_earth(const Eigen::Vector2d& gimbal_rad, const Eigen::Matrix3d& R_earth_to_body);

// The spin axis's inertial angular velocity in body axes from its rate on the inner gimbal axes
// (pitch about y_I, yaw about z_I) at the gimbal angles.
[[nodiscard]] Eigen::Vector3d spin_axis_rate_body(const Eigen::Vector2d& gimbal_rad, const Eigen::Vector2d& rate_rad_s);

// The slew command (pitch about y_I, yaw about z_I; rad/s) that flies the spin axis from its
// estimate `spin_axis_est_earth` onto `los` at gain `gain_1_s`, on the gimbal axes at the body's
// attitude R_earth_to_body, each axis within +-limit_rad_s.
[[nodiscard]] Eigen::Vector2d track_command(const LineOfSight& los, const Eigen::Vector3d& spin_axis_est_earth,
                                            const Eigen::Matrix3d& R_earth_to_body, double gain_1_s,
                                            const Eigen::Vector2d& limit_rad_s);

}  // namespace gyro::sil
