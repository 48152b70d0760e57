#include "los_tracking.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "gyro/attitude.hpp"
#include "gyro/gimbal_geometry.hpp"
#include "gyro/saturate.hpp"

namespace gyro::sil {

LineOfSight line_of_sight_at(const LineOfSightSpec& spec, double t_s) {
  LineOfSight los;
  if (spec.source == LineOfSightSpec::Source::kInertial) {
    const double w = spec.rate_rad_s.norm();
    los.direction = w > 0 ? Eigen::Vector3d(Eigen::AngleAxisd(w * t_s, spec.rate_rad_s / w) * spec.direction)
                          : spec.direction;
    los.direction.normalize();
    // The part of the rotation about the LOS itself does not move it.
    los.rate_rad_s = spec.rate_rad_s - spec.rate_rad_s.dot(los.direction) * los.direction;
    return los;
  }
  const Eigen::Vector3d v = spec.target_velocity_m_s - spec.own_velocity_m_s;
  const Eigen::Vector3d r = spec.target_position_m - spec.own_position_m + v * t_s;
  const double r2 = r.squaredNorm();
  los.direction = r / std::sqrt(r2);
  los.rate_rad_s = r.cross(v) / r2;
  return los;
}

double closest_range_m(const LineOfSightSpec& spec, double duration_s) {
  const Eigen::Vector3d v = spec.target_velocity_m_s - spec.own_velocity_m_s;
  const Eigen::Vector3d r0 = spec.target_position_m - spec.own_position_m;
  const double v2 = v.squaredNorm();
  const double t = v2 > 0 ? std::clamp(-r0.dot(v) / v2, 0.0, duration_s) : 0.0;
  return (r0 + v * t).norm();
}

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

Eigen::Vector3d spin_axis_earth(const Eigen::Vector2d& gimbal_rad, const Eigen::Matrix3d& R_earth_to_body) {
  return R_earth_to_body.transpose() * gimbal_frame_at<double>(gimbal_rad).spin_axis_body;
}

Eigen::Vector3d spin_axis_rate_body(const Eigen::Vector2d& gimbal_rad, const Eigen::Vector2d& rate_rad_s) {
  const GimbalFrame<double> f = gimbal_frame_at<double>(gimbal_rad);
  return f.y_inner_body * rate_rad_s(0) + f.z_inner_body * rate_rad_s(1);
}

Eigen::Vector2d track_command(const LineOfSight& los, const Eigen::Vector3d& spin_axis_est_earth,
                              const Eigen::Matrix3d& R_earth_to_body, double gain_1_s,
                              const Eigen::Vector2d& limit_rad_s) {
  const Eigen::Vector3d normal = spin_axis_est_earth.cross(los.direction);
  const double s = normal.norm();
  Eigen::Vector3d w = los.rate_rad_s;
  if (s > 0) w += gain_1_s * angle_between(spin_axis_est_earth, los.direction) / s * normal;
  // The inner gimbal axes of the estimated spin axis, now: the body has turned since the estimate.
  const Eigen::Vector3d x_body = R_earth_to_body * spin_axis_est_earth;
  const GimbalAngles<double> g = gimbal_angles<double>(x_body);
  const GimbalFrame<double> f = gimbal_frame_at<double>(Eigen::Vector2d(g.pitch_rad, g.yaw_rad));
  const Eigen::Vector3d w_body = R_earth_to_body * w;
  return Eigen::Vector2d(saturate(f.y_inner_body.dot(w_body), limit_rad_s(0)),
                         saturate(f.z_inner_body.dot(w_body), limit_rad_s(1)));
}

}  // namespace gyro::sil
