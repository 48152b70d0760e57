// A recorded body trajectory: time, attitude, body rates and specific force sampled in a table
// (a CSV file, or columns handed in from Python), checked once on the host and interpolated at
// the ticks without allocating. The interpolation is a cubic Hermite curve on the rotation
// group through the sampled attitudes with the sampled rates as its end derivatives;
// docs/scenarios.md ("body.trajectory") gives the derivation and the checks.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace gyro::sil {

// Largest trajectory file read (64 MiB) and most rows taken (each sample is 120 bytes in memory).
inline constexpr std::uint64_t kMaxTrajectoryBytes = std::uint64_t{64} << 20;
inline constexpr std::size_t kMaxTrajectoryRows = 500'000;

// A quaternion's norm may differ from 1 by this much (it is then normalised).
inline constexpr double kTrajectoryUnitTolerance = 1e-6;

// Attitude columns: a unit quaternion body to earth (qw, qx, qy, qz; scalar first), or 3-2-1
// Euler angles earth to body (roll_rad, pitch_rad, yaw_rad), as body.attitude_rad.
enum class TrajectoryAttitude : std::uint8_t { kQuaternion, kEuler321 };
[[nodiscard]] constexpr std::array<const char*, 2> enum_names(TrajectoryAttitude /*tag*/) noexcept {
  return {"quaternion", "euler_321"};
}

// The columns of a trajectory, in order, for its attitude form.
[[nodiscard]] std::vector<std::string> trajectory_columns(TrajectoryAttitude form);

// The trajectory as read: column-major values (columns[c][i]), named by `names` in any order
// (empty: in the order of trajectory_columns). Row i is named "line (i + first_line)" in a
// file, "[i]" for arrays.
struct TrajectoryTable {
  std::string source;  // the file, or "<trajectory arrays>"
  bool from_file{true};
  std::size_t first_line{2};  // the file's line of row 0 (after the header)
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
};

// One interval's data, precomputed at load: attitude at its start, the rotation vector to its
// end, the end derivative of the curve, rates and forces at both ends.
struct TrajectorySample {
  double t_s{0};
  Eigen::Quaterniond q_body_to_earth{Eigen::Quaterniond::Identity()};
  Eigen::Vector3d rate_rad_s{Eigen::Vector3d::Zero()};
  Eigen::Vector3d specific_force{Eigen::Vector3d::Zero()};
  Eigen::Vector3d delta{Eigen::Vector3d::Zero()};      // Log(q_i^-1 q_{i+1}) (0 at the last row)
  Eigen::Vector3d end_slope{Eigen::Vector3d::Zero()};  // h Jr^-1(delta) w_{i+1}
};

struct BodyTrajectory {
  std::string source;
  bool from_file{true};
  std::size_t first_line{2};
  std::vector<std::string> columns;       // trajectory_columns of its attitude form
  std::vector<TrajectorySample> samples;  // at least 2, time increasing from 0
  [[nodiscard]] double end_s() const { return samples.back().t_s; }
};

// What the scenario's body.trajectory says about the table.
struct TrajectorySpec {
  TrajectoryAttitude attitude{TrajectoryAttitude::kQuaternion};
  double tolerance_rad{1e-6};  // attitudes against the rates, per interval
  std::string file;            // resolved against the scenario's directory; empty: arrays given later
  std::string file_field{"body.trajectory.file"};
};

// The file's rows (bounded before reading: kMaxTrajectoryBytes, kMaxTrajectoryRows); throws
// ScenarioError naming the line and column.
[[nodiscard]] TrajectoryTable read_trajectory_csv(const std::string& path, TrajectoryAttitude form);
[[nodiscard]] TrajectoryTable parse_trajectory_csv(const std::string& text, const std::string& source,
                                                   TrajectoryAttitude form);

// The checked trajectory: times increasing from 0, values finite, quaternions unit within
// kTrajectoryUnitTolerance, each interval's rotation within spec.tolerance_rad of the one its
// rates give (h (w0 + w1) / 2 + h^2 / 12 w0 x w1) and below pi. Throws ScenarioError naming
// the row, the column, the value and the bound.
[[nodiscard]] BodyTrajectory build_trajectory(const TrajectoryTable& table, const TrajectorySpec& spec);

// Where row i of a table is, and the field naming its column c: "p_rad_s (line 12)", "p_rad_s[10]".
[[nodiscard]] std::string trajectory_field(const TrajectoryTable& table, std::size_t row, const std::string& column);
[[nodiscard]] std::string trajectory_field(const BodyTrajectory& tr, std::size_t row, const std::string& column);

// The rotation group's exponential and its right Jacobian (docs/scenarios.md).
[[nodiscard]] inline Eigen::Quaterniond so3_exp(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  if (!(angle > 0)) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, phi / angle));
}

[[nodiscard]] inline Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v(2), v(1), v(2), 0, -v(0), -v(1), v(0), 0;
  return m;
}

// Jr(phi) = I - (1 - cos a) / a^2 [phi]x + (a - sin a) / a^3 [phi]x^2, a = |phi|.
[[nodiscard]] inline Eigen::Matrix3d so3_right_jacobian(const Eigen::Vector3d& phi) {
  const double a2 = phi.squaredNorm(), a = std::sqrt(a2);
  // Below 1e-4 rad the series' next terms are under 1e-18.
  const double c1 = a < 1e-4 ? 0.5 - a2 / 24 : (1 - std::cos(a)) / a2;
  const double c2 = a < 1e-4 ? 1.0 / 6 - a2 / 120 : (a - std::sin(a)) / (a2 * a);
  const Eigen::Matrix3d k = skew(phi);
  return Eigen::Matrix3d::Identity() - c1 * k + c2 * k * k;
}

// Jr^-1(phi) = I + [phi]x / 2 + (1 / a^2 - (1 + cos a) / (2 a sin a)) [phi]x^2.
[[nodiscard]] inline Eigen::Matrix3d so3_right_jacobian_inverse(const Eigen::Vector3d& phi) {
  const double a2 = phi.squaredNorm(), a = std::sqrt(a2);
  const double c = a < 1e-4 ? 1.0 / 12 + a2 / 720 : 1 / a2 - (1 + std::cos(a)) / (2 * a * std::sin(a));
  const Eigen::Matrix3d k = skew(phi);
  return Eigen::Matrix3d::Identity() + 0.5 * k + c * k * k;
}

// The trajectory's state at time t: attitude, rates (the curve's own angular velocity) and
// specific force (linear between samples).
struct TrajectoryPoint {
  Eigen::Quaterniond q_body_to_earth;
  Eigen::Vector3d rate_rad_s;
  Eigen::Vector3d specific_force;
};

// Evaluates the curve at t, moving `cursor` (the interval last used) forward or back; t is
// clamped to [0, end] (a run past the end is refused before it starts).
[[nodiscard]] inline TrajectoryPoint trajectory_at(const BodyTrajectory& tr, double t, std::size_t& cursor) {
  const std::vector<TrajectorySample>& s = tr.samples;
  const std::size_t last = s.size() - 1;
  t = std::min(std::max(t, 0.0), s[last].t_s);
  if (cursor >= last) cursor = last - 1;
  while (cursor + 1 < last && t > s[cursor + 1].t_s) ++cursor;
  while (cursor > 0 && t < s[cursor].t_s) --cursor;
  const TrajectorySample& a = s[cursor];
  const TrajectorySample& b = s[cursor + 1];
  const double h = b.t_s - a.t_s;
  const double u = (t - a.t_s) / h;
  const double u2 = u * u, u3 = u2 * u;
  // Hermite basis (value and d/du) for the start slope h w0, the end point delta, the end slope.
  const double h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
  const double d10 = 3 * u2 - 4 * u + 1, d01 = -6 * u2 + 6 * u, d11 = 3 * u2 - 2 * u;
  const Eigen::Vector3d start_slope = h * a.rate_rad_s;
  const Eigen::Vector3d phi = h10 * start_slope + h01 * a.delta + h11 * a.end_slope;
  const Eigen::Vector3d dphi = d10 * start_slope + d01 * a.delta + d11 * a.end_slope;
  TrajectoryPoint p;
  p.q_body_to_earth = (a.q_body_to_earth * so3_exp(phi)).normalized();
  p.rate_rad_s = so3_right_jacobian(phi) * dphi / h;
  p.specific_force = (1 - u) * a.specific_force + u * b.specific_force;
  return p;
}

}  // namespace gyro::sil
