// Trajectory CSV -> table -> checked trajectory, each refusal naming the row and the column.
#include "body_trajectory.hpp"

#include <array>
#include <charconv>
#include <filesystem>
#include <string_view>

#include "body_motion.hpp"
#include "bounded_read.hpp"
#include "scenario.hpp"

namespace gyro::sil {

namespace {

std::string format(double v) {
  std::array<char, 32> buf{};
  const std::to_chars_result r = std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, 10);
  return std::string(buf.data(), r.ptr);
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return cells;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ",") + n;
  return out;
}

}  // namespace

std::vector<std::string> trajectory_columns(TrajectoryAttitude form) {
  std::vector<std::string> c{"t_s"};
  if (form == TrajectoryAttitude::kQuaternion) {
    c.insert(c.end(), {"qw", "qx", "qy", "qz"});
  } else {
    c.insert(c.end(), {"roll_rad", "pitch_rad", "yaw_rad"});
  }
  c.insert(c.end(), {"p_rad_s", "q_rad_s", "r_rad_s", "fx", "fy", "fz"});
  return c;
}

namespace {

std::string row_field(bool from_file, std::size_t first_line, std::size_t row, const std::string& column) {
  if (from_file) return column + " (line " + std::to_string(row + first_line) + ")";
  return column + "[" + std::to_string(row) + "]";
}

}  // namespace

std::string trajectory_field(const TrajectoryTable& table, std::size_t row, const std::string& column) {
  return row_field(table.from_file, table.first_line, row, column);
}

std::string trajectory_field(const BodyTrajectory& tr, std::size_t row, const std::string& column) {
  return row_field(tr.from_file, tr.first_line, row, column);
}

TrajectoryTable parse_trajectory_csv(const std::string& text, const std::string& source, TrajectoryAttitude form) {
  const std::vector<std::string> names = trajectory_columns(form);
  TrajectoryTable table;
  table.source = source;
  table.columns.assign(names.size(), {});
  std::size_t line_no = 0, pos = 0;
  while (pos < text.size()) {
    const std::size_t end = text.find('\n', pos);
    const std::string_view line(text.data() + pos, (end == std::string::npos ? text.size() : end) - pos);
    pos = end == std::string::npos ? text.size() : end + 1;
    ++line_no;
    const std::string where = "line " + std::to_string(line_no);
    if (line_no == 1) {
      if (trim(line) != joined(names)) {
        throw ScenarioError(source, "(header)",
                            "the first line must name the columns \"" + joined(names) + "\", got \"" +
                                std::string(trim(line).substr(0, 200)) + "\"");
      }
      continue;
    }
    if (trim(line).empty() && pos >= text.size()) break;  // a final newline
    if (table.columns[0].size() >= kMaxTrajectoryRows) {
      throw ScenarioError(source, "(" + where + ")",
                          "more than the limit of " + std::to_string(kMaxTrajectoryRows) + " rows");
    }
    const std::vector<std::string_view> cells = split(line);
    if (cells.size() != names.size()) {
      throw ScenarioError(source, "(" + where + ")",
                          "expected " + std::to_string(names.size()) + " values, got " + std::to_string(cells.size()));
    }
    for (std::size_t c = 0; c < cells.size(); ++c) {
      double v = 0;
      const std::string_view cell = cells[c];
      const std::from_chars_result r = std::from_chars(cell.data(), cell.data() + cell.size(), v);
      if (cell.empty() || r.ec != std::errc() || r.ptr != cell.data() + cell.size()) {
        throw ScenarioError(source, names[c] + " (" + where + ")",
                            "expected a number, got \"" + std::string(cell.substr(0, 40)) + "\"");
      }
      table.columns[c].push_back(v);
    }
  }
  if (line_no == 0) throw ScenarioError(source, "(header)", "the file is empty: expected \"" + joined(names) + "\"");
  return table;
}

TrajectoryTable read_trajectory_csv(const std::string& path, TrajectoryAttitude form) {
  // A regular file only: a device or a pipe could block the open or feed bytes without end.
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (!ec && std::filesystem::exists(st) && !std::filesystem::is_regular_file(st)) {
    throw ScenarioError(path, "(file)", "not a regular file (a trajectory is read from a file on disk)");
  }
  std::string why;
  const std::optional<std::string> text = read_bounded(path, kMaxTrajectoryBytes, "a trajectory", why);
  if (!text) throw ScenarioError(path, "(file)", why);
  return parse_trajectory_csv(*text, path, form);
}

namespace {

// The table's columns in the order of `names`, each named once.
std::vector<const std::vector<double>*> ordered_columns(const TrajectoryTable& table,
                                                        const std::vector<std::string>& names) {
  const std::string form = names[1] == "qw" ? "quaternion" : "euler_321";
  std::vector<const std::vector<double>*> cols(names.size(), nullptr);
  if (table.names.empty()) {
    if (table.columns.size() != names.size()) {
      throw ScenarioError(table.source, "(columns)",
                          "expected the " + std::to_string(names.size()) + " columns " + joined(names) + ", got " +
                              std::to_string(table.columns.size()));
    }
    for (std::size_t c = 0; c < names.size(); ++c) cols[c] = &table.columns[c];
    return cols;
  }
  for (std::size_t k = 0; k < table.names.size(); ++k) {
    std::size_t c = 0;
    while (c < names.size() && names[c] != table.names[k]) ++c;
    if (c == names.size()) {
      throw ScenarioError(table.source, table.names[k],
                          "unknown column (attitude \"" + form + "\" takes " + joined(names) + ")");
    }
    cols[c] = &table.columns[k];
  }
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (cols[c] == nullptr) {
      throw ScenarioError(table.source, names[c],
                          "missing column (attitude \"" + form + "\" takes " + joined(names) + ")");
    }
  }
  return cols;
}

}  // namespace

BodyTrajectory build_trajectory(const TrajectoryTable& table, const TrajectorySpec& spec) {
  const std::vector<std::string> names = trajectory_columns(spec.attitude);
  const auto refuse = [&](std::size_t row, std::size_t col, const std::string& reason) {
    throw ScenarioError(table.source, trajectory_field(table, row, names[col]), reason);
  };
  const std::vector<const std::vector<double>*> cols = ordered_columns(table, names);
  const std::size_t rows = cols[0]->size();
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (cols[c]->size() != rows) {
      throw ScenarioError(table.source, names[c],
                          "has " + std::to_string(cols[c]->size()) + " rows, " + names[0] + " has " +
                              std::to_string(rows));
    }
  }
  if (rows < 2) throw ScenarioError(table.source, "(rows)", "at least 2 rows needed, got " + std::to_string(rows));
  if (rows > kMaxTrajectoryRows) {
    throw ScenarioError(table.source, "(rows)",
                        std::to_string(rows) + " rows, more than the limit of " + std::to_string(kMaxTrajectoryRows));
  }

  BodyTrajectory tr;
  tr.source = table.source;
  tr.from_file = table.from_file;
  tr.first_line = table.first_line;
  tr.columns = names;
  tr.samples.resize(rows);
  const std::size_t rate_col = spec.attitude == TrajectoryAttitude::kQuaternion ? 5 : 4;
  for (std::size_t i = 0; i < rows; ++i) {
    const auto at = [&](std::size_t c) { return (*cols[c])[i]; };
    for (std::size_t c = 0; c < names.size(); ++c) {
      if (!std::isfinite(at(c))) refuse(i, c, "must be finite, got " + format(at(c)));
    }
    TrajectorySample& s = tr.samples[i];
    s.t_s = at(0);
    if (i == 0 && s.t_s != 0) refuse(i, 0, "the trajectory must start at 0 s (the run's tick 0), got " + format(s.t_s));
    if (i > 0 && !(s.t_s > tr.samples[i - 1].t_s)) {
      refuse(i, 0, "time must increase: " + format(s.t_s) + " s is not after the previous " +
                       format(tr.samples[i - 1].t_s) + " s");
    }
    if (spec.attitude == TrajectoryAttitude::kQuaternion) {
      const Eigen::Quaterniond q(at(1), at(2), at(3), at(4));
      const double n = q.norm();
      if (!(std::abs(n - 1) <= kTrajectoryUnitTolerance)) {
        refuse(i, 1, "the quaternion's norm is " + format(n) + ", not 1 within " + format(kTrajectoryUnitTolerance));
      }
      s.q_body_to_earth = q.normalized();
    } else {
      const Eigen::Matrix3d r = euler_321_to_R_earth_to_body({at(1), at(2), at(3)});
      s.q_body_to_earth = Eigen::Quaterniond(Eigen::Matrix3d(r.transpose())).normalized();
    }
    s.rate_rad_s = Eigen::Vector3d(at(rate_col), at(rate_col + 1), at(rate_col + 2));
    s.specific_force = Eigen::Vector3d(at(rate_col + 3), at(rate_col + 4), at(rate_col + 5));
  }

  // Each interval: the rotation between the attitudes against the one the rates give.
  for (std::size_t i = 0; i + 1 < rows; ++i) {
    TrajectorySample& a = tr.samples[i];
    const TrajectorySample& b = tr.samples[i + 1];
    const double h = b.t_s - a.t_s;
    Eigen::Quaterniond rel = a.q_body_to_earth.conjugate() * b.q_body_to_earth;
    if (rel.w() < 0) rel.coeffs() = -rel.coeffs();  // the shorter way round
    const Eigen::AngleAxisd aa(rel);
    a.delta = aa.angle() * aa.axis();
    const Eigen::Vector3d expected =
        0.5 * h * (a.rate_rad_s + b.rate_rad_s) + (h * h / 12) * a.rate_rad_s.cross(b.rate_rad_s);
    const double mismatch = (a.delta - expected).norm();
    if (!(mismatch <= spec.tolerance_rad)) {
      refuse(i + 1, 1,
             "the attitude turned by " + format(a.delta.norm()) + " rad since the previous row, " + format(mismatch) +
                 " rad away from the turn the rates give (" + format(expected.norm()) + " rad); the tolerance is " +
                 format(spec.tolerance_rad) + " rad (body.trajectory.tolerance_rad)");
    }
    if (!(expected.norm() < 0.5 * kTwoPi)) {
      refuse(i + 1, 0, "the body turns by " + format(expected.norm()) +
                           " rad since the previous row, pi or more: the samples cannot represent it");
    }
    a.end_slope = h * (so3_right_jacobian_inverse(a.delta) * b.rate_rad_s);
  }
  return tr;
}

}  // namespace gyro::sil
