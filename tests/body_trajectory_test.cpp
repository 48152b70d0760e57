// gyro_sil's recorded body trajectory (apps/body_trajectory.hpp): the interpolation against
// the constant-rate BodyMotion and a closed-form coning motion, the refusals of bad tables
// naming row and column, and the shipped trajectory scenario flown off the stop.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "body_motion.hpp"
#include "body_trajectory.hpp"
#include "csv_writer.hpp"
#include "scenario.hpp"
#include "scenario_limits.hpp"
#include "sil_columns.hpp"
#include "sil_runner.hpp"

namespace gyro::sil {
namespace {

namespace fs = std::filesystem;

const fs::path kTrajectoryScenarios = fs::path(GYRO_SOURCE_DIR) / "scenarios";

// The rotation angle between two attitudes (R_earth_to_body).
double angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(Eigen::Matrix3d(a.transpose() * b)).angle();
}

// A quaternion table (arrays) from samples of attitude, rates and force.
struct TableBuilder {
  TrajectoryTable table;
  TableBuilder() {
    table.source = "<trajectory arrays>";
    table.from_file = false;
    table.columns.assign(11, {});
  }
  void add(double t, const Eigen::Quaterniond& q, const Eigen::Vector3d& w, const Eigen::Vector3d& f) {
    const double v[] = {t, q.w(), q.x(), q.y(), q.z(), w(0), w(1), w(2), f(0), f(1), f(2)};
    for (std::size_t c = 0; c < 11; ++c) table.columns[c].push_back(v[c]);
  }
};

BodyProfile with_trajectory(const TrajectoryTable& table, const TrajectorySpec& spec = {}) {
  BodyProfile p;
  p.trajectory_spec = spec;
  p.trajectory = std::make_shared<const BodyTrajectory>(build_trajectory(table, spec));
  return p;
}

// The constant-rate profile sampled every `every` ticks of BodyMotion, as a table.
TrajectoryTable sampled(const BodyProfile& profile, double tick, int every, int rows) {
  TableBuilder b;
  BodyMotion m(profile, tick);
  for (int k = 0; k < every * (rows - 1) + 1; ++k) {
    if (k > 0) m.advance();
    if (k % every != 0) continue;
    b.add(m.time_s(), Eigen::Quaterniond(Eigen::Matrix3d(m.R_earth_to_body().transpose())), m.rate_rad_s(),
          m.specific_force());
  }
  return b.table;
}

TEST(BodyTrajectory, ConstantRatesReproduceBodyMotionToRounding) {
  BodyProfile profile;
  profile.attitude_rad = {0.3, -0.2, 1.1};
  profile.rate_rad_s = {9.0, 0.4, -0.7};  // a spinning, turning body
  profile.specific_force = {-0.3, 2.0, -5.0};
  const double tick = 1e-3;
  // Samples every 7 ticks: six ticks of each interval are interpolated.
  const BodyProfile from_table = with_trajectory(sampled(profile, tick, 7, 200));
  BodyMotion ref(profile, tick), m(from_table, tick);
  double worst_angle = 0, worst_rate = 0, worst_force = 0;
  for (int k = 0; k <= 7 * 199; ++k) {
    if (k > 0) {
      ref.advance();
      m.advance();
    }
    worst_angle = std::max(worst_angle, angle_between(ref.R_earth_to_body(), m.R_earth_to_body()));
    worst_rate = std::max(worst_rate, (ref.rate_rad_s() - m.rate_rad_s()).cwiseAbs().maxCoeff());
    worst_force = std::max(worst_force, (ref.specific_force() - m.specific_force()).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst_angle, 1e-12);
  EXPECT_LT(worst_rate, 1e-12);
  EXPECT_LT(worst_force, 1e-15);
}

// Coning: a spin b about body x inside a precession a about earth z, R = Exp(a t) Exp(b t);
// the body rates are w(t) = Exp(b t)^T a + b (closed form, independent of the interpolation).
struct Coning {
  Eigen::Vector3d a{0, 0, 2.0};
  Eigen::Vector3d b{10.0, 0, 0.3};
  [[nodiscard]] Eigen::Quaterniond attitude(double t) const { return so3_exp(a * t) * so3_exp(b * t); }
  [[nodiscard]] Eigen::Vector3d rate(double t) const {
    return so3_exp(b * t).toRotationMatrix().transpose() * a + b;
  }
};

TEST(BodyTrajectory, ConingSampledAt500HzFollowsTheClosedFormWithin1e9) {
  const Coning c;
  TableBuilder b;
  const double h = 2e-3, tick = 1e-3;
  for (int i = 0; i <= 500; ++i) b.add(i * h, c.attitude(i * h), c.rate(i * h), Eigen::Vector3d::Zero());
  BodyMotion m(with_trajectory(b.table), tick);
  double worst_angle = 0, worst_rate = 0;
  for (int k = 0; k <= 1000; ++k) {
    if (k > 0) m.advance();
    const Eigen::Matrix3d truth = c.attitude(m.time_s()).toRotationMatrix().transpose();
    worst_angle = std::max(worst_angle, angle_between(truth, m.R_earth_to_body()));
    worst_rate = std::max(worst_rate, (c.rate(m.time_s()) - m.rate_rad_s()).norm());
  }
  std::printf("figure: coning 10 rad/s spin in a 2 rad/s precession, samples 2 ms, ticks 1 ms: attitude %.2e "
              "rad, rate %.2e rad/s\n",
              worst_angle, worst_rate);
  // The Hermite curve's error is fourth order in h |w| (0.02): about 1e-10 rad here.
  EXPECT_LT(worst_angle, 1e-9);
  EXPECT_LT(worst_rate, 1e-6);
  // And the error grows as h^4 (16x at twice the interval) when sampled coarser: a real order.
  TableBuilder coarse;
  for (int i = 0; i <= 250; ++i) coarse.add(i * 2 * h, c.attitude(i * 2 * h), c.rate(i * 2 * h), Eigen::Vector3d::Zero());
  TrajectorySpec loose;
  loose.tolerance_rad = 1e-4;
  BodyMotion mc(with_trajectory(coarse.table, loose), tick);
  double worst_coarse = 0;
  for (int k = 0; k <= 1000; ++k) {
    if (k > 0) mc.advance();
    worst_coarse = std::max(worst_coarse, angle_between(c.attitude(mc.time_s()).toRotationMatrix().transpose(),
                                                        mc.R_earth_to_body()));
  }
  EXPECT_GT(worst_coarse / worst_angle, 8.0);
  EXPECT_LT(worst_coarse / worst_angle, 32.0);
}

TEST(BodyTrajectory, EulerColumnsAreTheThreeTwoOneAttitude) {
  const std::string text =
      "t_s,roll_rad,pitch_rad,yaw_rad,p_rad_s,q_rad_s,r_rad_s,fx,fy,fz\n"
      "0,0.1,0.2,0.3,0,0,0,0,0,1\n"
      "0.5,0.1,0.2,0.3,0,0,0,0,0,1\n";
  TrajectorySpec spec;
  spec.attitude = TrajectoryAttitude::kEuler321;
  BodyMotion m(with_trajectory(parse_trajectory_csv(text, "e.csv", spec.attitude), spec), 1e-3);
  EXPECT_LT(angle_between(m.R_earth_to_body(), euler_321_to_R_earth_to_body({0.1, 0.2, 0.3})), 1e-15);
}

// ---------------------------------------------------------------------------------------
// Refusals: each names the row (the file's line) and the column, the value and the bound.

struct Refusal {
  std::string field, reason;
};

Refusal trajectory_refusal(const std::string& rows, TrajectorySpec spec = {}) {
  const std::string text = "t_s,qw,qx,qy,qz,p_rad_s,q_rad_s,r_rad_s,fx,fy,fz\n" + rows;
  try {
    (void)build_trajectory(parse_trajectory_csv(text, "bad.csv", spec.attitude), spec);
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.file(), "bad.csv");
    return {e.field(), e.reason()};
  }
  ADD_FAILURE() << "accepted:\n" << rows;
  return {};
}

constexpr const char* kRow0 = "0,1,0,0,0,0,0,0,0,0,0\n";

TEST(BodyTrajectoryRefusal, TimeNotIncreasingNamesTheLine) {
  const Refusal r = trajectory_refusal(std::string(kRow0) + "0.1,1,0,0,0,0,0,0,0,0,0\n0.1,1,0,0,0,0,0,0,0,0,0\n");
  EXPECT_EQ(r.field, "t_s (line 4)");
  EXPECT_NE(r.reason.find("0.1 s is not after the previous 0.1 s"), std::string::npos) << r.reason;
}

TEST(BodyTrajectoryRefusal, NonFiniteValueNamesItsColumn) {
  const Refusal r = trajectory_refusal(std::string(kRow0) + "0.1,1,0,0,0,0,nan,0,0,0,0\n");
  EXPECT_EQ(r.field, "q_rad_s (line 3)");
  EXPECT_NE(r.reason.find("must be finite, got nan"), std::string::npos) << r.reason;
  EXPECT_EQ(trajectory_refusal(std::string(kRow0) + "0.1,1,0,0,0,0,0,0,inf,0,0\n").field, "fx (line 3)");
}

TEST(BodyTrajectoryRefusal, NonUnitQuaternionNamesTheNormAndTolerance) {
  const Refusal r = trajectory_refusal(std::string(kRow0) + "0.1,1.001,0,0,0,0,0,0,0,0,0\n");
  EXPECT_EQ(r.field, "qw (line 3)");
  EXPECT_NE(r.reason.find("norm is 1.001, not 1 within 1e-06"), std::string::npos) << r.reason;
}

TEST(BodyTrajectoryRefusal, AttitudeDisagreeingWithRatesNamesTheTolerance) {
  // The rates say 1 rad/s about x for 0.1 s; the attitude did not turn.
  const Refusal r = trajectory_refusal("0,1,0,0,0,1,0,0,0,0,0\n0.1,1,0,0,0,1,0,0,0,0,0\n");
  EXPECT_EQ(r.field, "qw (line 3)");
  EXPECT_NE(r.reason.find("turned by 0 rad since the previous row, 0.1 rad away"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("tolerance is 1e-06 rad"), std::string::npos) << r.reason;
  // Turned the other way (the wrong quaternion convention): refused too.
  const double s = std::sin(-0.05), c = std::cos(-0.05);
  std::ostringstream row;
  row.precision(17);
  row << "0.1," << c << "," << s << ",0,0,1,0,0,0,0,0\n";
  EXPECT_EQ(trajectory_refusal("0,1,0,0,0,1,0,0,0,0,0\n" + row.str()).field, "qw (line 3)");
}

TEST(BodyTrajectoryRefusal, BadCellsHeaderAndStartAreNamed) {
  EXPECT_EQ(trajectory_refusal(std::string(kRow0) + "0.1,1,0,0,0,0,0,0,0,x,0\n").field, "fy (line 3)");
  EXPECT_EQ(trajectory_refusal(std::string(kRow0) + "0.1,1,0,0,0,0,0,0,0,0\n").field, "(line 3)");
  EXPECT_EQ(trajectory_refusal("0.5,1,0,0,0,0,0,0,0,0,0\n1,1,0,0,0,0,0,0,0,0,0\n").field, "t_s (line 2)");
  EXPECT_EQ(trajectory_refusal(kRow0).field, "(rows)");
  try {
    (void)parse_trajectory_csv("t,qw\n0,1\n", "h.csv", TrajectoryAttitude::kQuaternion);
    ADD_FAILURE();
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.field(), "(header)");
  }
}

TEST(BodyTrajectoryRefusal, TooManyRowsStopsAtTheLimit) {
  std::string text = "t_s,qw,qx,qy,qz,p_rad_s,q_rad_s,r_rad_s,fx,fy,fz\n";
  for (std::size_t i = 0; i <= kMaxTrajectoryRows; ++i) text += std::to_string(i) + ",1,0,0,0,0,0,0,0,0,0\n";
  try {
    (void)parse_trajectory_csv(text, "long.csv", TrajectoryAttitude::kQuaternion);
    ADD_FAILURE();
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.field(), "(line " + std::to_string(kMaxTrajectoryRows + 2) + ")");
    EXPECT_NE(e.reason().find("more than the limit of 500000 rows"), std::string::npos) << e.reason();
  }
}

TEST(BodyTrajectoryRefusal, TooLargeFileRefusedFromItsSize) {
  const fs::path p = fs::temp_directory_path() / ("gyro_trajectory_" + std::to_string(::getpid()) + ".csv");
  std::ofstream(p).put('t');
  fs::resize_file(p, kMaxTrajectoryBytes + 1);  // sparse: nothing read
  try {
    (void)read_trajectory_csv(p.string(), TrajectoryAttitude::kQuaternion);
    ADD_FAILURE();
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.field(), "(file)");
    EXPECT_NE(e.reason().find("more than the limit of 67108864 bytes for a trajectory"), std::string::npos)
        << e.reason();
  }
  fs::remove(p);
}

// ---------------------------------------------------------------------------------------
// The scenario's body.trajectory.

// The shipped trajectory scenario as it is flown (its base expanded).
nlohmann::json shipped_document() { return *read_scenario(kTrajectoryScenarios / "trajectory_spinning.json").document; }

ScenarioError scenario_refusal(const nlohmann::json& doc, const TrajectoryTable* table = nullptr,
                               std::optional<std::uint64_t> ticks = std::nullopt) {
  const std::string file = (kTrajectoryScenarios / "t.json").string();
  try {
    (void)prepare_scenario(std::nullopt, doc.dump(), file, std::nullopt, ticks, table);
  } catch (const ScenarioError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted";
  return ScenarioError("", "", "");
}

TEST(BodyTrajectoryScenario, RunPastTheTrajectoryEndIsRefused) {
  nlohmann::json doc = shipped_document();
  doc["run"]["duration_s"] = 1.7;
  const ScenarioError e = scenario_refusal(doc);
  EXPECT_EQ(e.field(), "run.duration_s");
  EXPECT_NE(e.reason().find("the run lasts 1.7 s, past the end of the body's trajectory at 1.6 s"),
            std::string::npos)
      << e.reason();
  // So is a longer run asked for after the scenario was read.
  EXPECT_EQ(scenario_refusal(shipped_document(), nullptr, 1601).field(), "run.duration_s");
}

TEST(BodyTrajectoryScenario, RatesBeyondTheGimbalEnvelopeNameTheRow) {
  nlohmann::json doc = shipped_document();
  doc["gyro"]["gimbal"]["max_body_rate_rad_s"] = 11.0;  // the file spins at 12 rad/s
  const ScenarioError e = scenario_refusal(doc);
  EXPECT_EQ(e.field(), "body.trajectory.file");
  EXPECT_NE(e.reason().find("trajectory_spinning.csv: p_rad_s (line "), std::string::npos) << e.reason();
  EXPECT_NE(e.reason().find("12.0017 rad/s is more than gyro.gimbal.max_body_rate_rad_s (11)"), std::string::npos)
      << e.reason();
  // And beyond pi per tick: 40 rad/s at 0.1 s, sampled every 0.05 s.
  // (The body's check comes first; the component would refuse this tick on its own.)
  doc = shipped_document();
  doc["body"]["trajectory"].erase("file");
  TableBuilder b;
  const Eigen::Vector3d w(40, 0, 0);
  for (int i = 0; i <= 20; ++i) b.add(0.05 * i, so3_exp(w * 0.05 * i), w, Eigen::Vector3d::Zero());
  Scenario s = parse_scenario(doc.dump(), "t.json");
  attach_trajectory(s, b.table);
  s.run.tick_s = 0.1;
  s.run.ticks = 10;
  ScenarioError fast("", "", "");
  try {
    check_run_limits(s);
    ADD_FAILURE() << "accepted";
  } catch (const ScenarioError& x) {
    fast = x;
  }
  EXPECT_EQ(fast.field(), "p_rad_s[0]");
  EXPECT_NE(fast.reason().find("turn by 4 rad in one tick at this row's rates (40 rad/s), more than pi"),
            std::string::npos)
      << fast.reason();
}

TEST(BodyTrajectoryScenario, BadFileIsNamedAsTheScenarioField) {
  nlohmann::json doc = shipped_document();
  doc["body"]["trajectory"]["attitude"] = "euler_321";  // the file has quaternion columns
  ScenarioError e = scenario_refusal(doc);
  EXPECT_EQ(e.field(), "body.trajectory.file");
  EXPECT_NE(e.reason().find("trajectory_spinning.csv: (header): the first line must name the columns"),
            std::string::npos)
      << e.reason();
  doc["body"]["trajectory"]["file"] = "/dev/zero";
  e = scenario_refusal(doc);
  EXPECT_EQ(e.field(), "body.trajectory.file");
  EXPECT_NE(e.reason().find("/dev/zero: not a regular file"), std::string::npos) << e.reason();
}

TEST(BodyTrajectoryScenario, TrajectoryAndProfileKeysTogetherAreRefused) {
  nlohmann::json doc = shipped_document();
  doc["body"]["rate_rad_s"] = {0, 0, 0};
  EXPECT_EQ(scenario_refusal(doc).field(), "body.rate_rad_s");
  doc = shipped_document();
  doc["body"]["trajectory"]["attitude"] = "euler";
  const ScenarioError form = scenario_refusal(doc);
  EXPECT_EQ(form.field(), "body.trajectory.attitude");
  EXPECT_EQ(form.reason(), "expected \"quaternion\" or \"euler_321\", got \"euler\"");
  doc = shipped_document();
  doc["body"]["trajectory"].erase("file");
  EXPECT_EQ(scenario_refusal(doc).field(), "body.trajectory.file");  // and no columns given
}

TEST(BodyTrajectoryScenario, ColumnsGivenInPlaceOfTheFileFlyTheSameRun) {
  nlohmann::json doc = shipped_document();
  const Scenario from_file = prepare_scenario(std::nullopt, doc.dump(),
                                              (kTrajectoryScenarios / "t.json").string(), std::nullopt, std::nullopt);
  const TrajectoryTable table = read_trajectory_csv((kTrajectoryScenarios / "trajectory_spinning.csv").string(),
                                                    TrajectoryAttitude::kQuaternion);
  EXPECT_EQ(scenario_refusal(doc, &table).field(), "body.trajectory.file");  // both: refused
  doc["body"]["trajectory"].erase("file");
  const Scenario from_columns = prepare_scenario(std::nullopt, doc.dump(), "t.json", std::nullopt, std::nullopt, &table);
  ColumnRecorder a, b;
  RunOptions o;
  o.progress = false;
  (void)run_scenario(from_file, a, o);
  (void)run_scenario(from_columns, b, o);
  ASSERT_EQ(a.columns().size(), b.columns().size());
  for (std::size_t i = 0; i < a.columns().size(); ++i) {
    EXPECT_EQ(a.columns()[i].numbers, b.columns()[i].numbers) << a.columns()[i].name;
  }
}

TEST(BodyTrajectoryScenario, SpinningProjectileFliesWithTheGimbalOffTheStop) {
  const Scenario s = load_scenario(kTrajectoryScenarios / "trajectory_spinning.json");
  ASSERT_TRUE(s.body.trajectory);
  EXPECT_EQ(s.body.trajectory->samples.size(), 801u);
  ColumnRecorder rec;
  RunOptions o;
  o.progress = false;
  const RunSummary sum = run_scenario(s, rec, o);
  EXPECT_EQ(sum.gimbal_stop_hits, 0u);
  EXPECT_EQ(sum.refused_steps, 0u);
  EXPECT_EQ(sum.final_mode, GyroMode::kFree);
  EXPECT_EQ(sum.flags_seen & (kFaultLatched | kGimbalLimit), 0u);
  // The body turned the gimbal by several hundredths of a radian, well inside the stop (0.4).
  EXPECT_GT(sum.max_abs_gimbal_rad, 0.02);
  EXPECT_LT(sum.max_abs_gimbal_rad, 0.5 * s.gyro.gimbal_stop_rad);
  // The rates guidance saw are the file's at its samples (every second tick).
  for (const SilColumn& c : rec.columns()) {
    if (c.name != "body_pitch_rate") continue;
    const double t = 0.5;
    const double q = 0.2 * std::pow(std::sin(kTwoPi / 2 * (t - 0.3) / 0.6), 2) * std::cos(12.0 * t);
    EXPECT_NEAR(c.numbers[500], q, 1e-9);
  }
}

}  // namespace
}  // namespace gyro::sil
