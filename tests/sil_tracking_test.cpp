// gyro_sil tracking a line of sight (guidance.track): a fixed target from a body at rest is
// acquired, a LOS turning at a constant rate is followed without a steady rate error, the
// tracking columns are there only when the run tracks, and bad track sections are refused
// naming the field, its value and the bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scenario.hpp"
#include "sil_columns.hpp"
#include "sil_runner.hpp"

namespace gyro::sil::sil_tracking_test {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const fs::path kScenarios = fs::path(GYRO_SOURCE_DIR) / "scenarios";

// A shipped scenario as it is flown (its example or base expanded).
json flown(const fs::path& p) { return *read_scenario(p).document; }

// The seeker gyro on a body at rest, uncaged at 0.2 s, tracking from 0.3 s with `track`.
json seeker_tracking(const json& track, double duration_s = 1.5) {
  json s = flown(kScenarios / "seeker_slew.json");
  s["run"]["duration_s"] = duration_s;
  s["body"] = {{"rate_rad_s", {0.0, 0.0, 0.0}}};
  s["guidance"] = {{"schedule", {{{"t_s", 0.0}, {"request", "none"}}, {{"t_s", 0.2}, {"request", "uncage"}}}},
                   {"track", track}};
  return s;
}

struct Tracked {
  std::vector<double> t, pointing, los_rate_error, slew_pitch, slew_yaw, rate_true_pitch, rate_true_yaw;
};

const SilColumn& column(const ColumnRecorder& r, std::string_view name) {
  for (const SilColumn& c : r.columns()) {
    if (c.name == name) return c;
  }
  ADD_FAILURE() << "no column " << name;
  return r.columns().front();
}

Tracked run_tracking(const json& doc) {
  Scenario s = parse_scenario_document(doc, "tracking");
  check_configs(s);
  ColumnRecorder rec;
  RunOptions quiet;
  quiet.progress = false;
  const RunSummary sum = run_scenario(s, rec, quiet);
  EXPECT_EQ(sum.nonfinite_values, 0u);
  EXPECT_EQ(sum.final_mode, GyroMode::kFree);
  return {column(rec, "t").numbers,           column(rec, "pointing_error_true").numbers,
          column(rec, "los_rate_error").numbers, column(rec, "slew_cmd_pitch").numbers,
          column(rec, "slew_cmd_yaw").numbers, column(rec, "theta_rate_true").numbers,
          column(rec, "psi_rate_true").numbers};
}

double max_from(const std::vector<double>& v, std::size_t from) {
  return *std::max_element(v.begin() + static_cast<std::ptrdiff_t>(from), v.end());
}
double mean_from(const std::vector<double>& v, std::size_t from) {
  double sum = 0;
  for (std::size_t i = from; i < v.size(); ++i) sum += v[i];
  return sum / static_cast<double>(v.size() - from);
}

TEST(SilTracking, AFixedTargetFromABodyAtRestIsAcquired) {
  // 0.1 rad up and 0.15 rad right of the boresight: 0.18 rad off at the start of tracking.
  const json track = {{"start_s", 0.3},
                      {"gain_1_s", 20.0},
                      {"line_of_sight", {{"direction", {std::cos(0.15), std::sin(0.15), -std::tan(0.1)}}}}};
  const Tracked r = run_tracking(seeker_tracking(track));
  EXPECT_GT(r.pointing[300], 0.17);
  // Within the pickoffs' bias (2e-4, -1e-4 rad) and noise after a second: the tracker sees the
  // spin axis through the component's estimate.
  EXPECT_LT(max_from(r.pointing, 1000), 5e-4);
  EXPECT_LT(max_from(r.los_rate_error, 1000), 5e-3);
}

TEST(SilTracking, AConstantRateLosIsFollowedWithoutSteadyRateError) {
  // Starting on the LOS, which turns at 0.1 rad/s about earth z (right) and 0.05 about y (up),
  // within the gimbal's cone over the run.
  const json track = {{"start_s", 0.3},
                      {"gain_1_s", 20.0},
                      {"line_of_sight", {{"direction", {1.0, 0.0, 0.0}}, {"rate_rad_s", {0.0, 0.05, 0.1}}}}};
  json doc = seeker_tracking(track);
  const Tracked r = run_tracking(doc);
  // The gyro stays put until 0.3 s, so the LOS is 0.034 rad ahead when tracking starts; over
  // the last half second the spin axis turns at the LOS rate (the mean: not the nutation).
  const std::size_t from = 1000;
  EXPECT_NEAR(mean_from(r.rate_true_pitch, from), 0.05, 2e-3);
  EXPECT_NEAR(mean_from(r.rate_true_yaw, from), 0.1, 2e-3);
  // The feedback's share of the command is the gain times a pointing error of about the
  // estimate's bias, not a lag growing with the rate.
  EXPECT_NEAR(mean_from(r.slew_pitch, from), 0.05, 20 * 5e-4);
  EXPECT_NEAR(mean_from(r.slew_yaw, from), 0.1, 20 * 5e-4);
  EXPECT_LT(max_from(r.pointing, from), 5e-4);
}

TEST(SilTracking, TheTrackingColumnsComeLastAndOnlyInTrackingRuns) {
  const std::span<const std::string_view> plain = csv_columns(), tracked = csv_columns(true);
  ASSERT_EQ(tracked.size(), plain.size() + 2);
  EXPECT_TRUE(std::equal(plain.begin(), plain.end(), tracked.begin()));
  EXPECT_EQ(tracked[plain.size()], "pointing_error_true");
  EXPECT_EQ(tracked[plain.size() + 1], "los_rate_error");
  EXPECT_EQ(std::count(plain.begin(), plain.end(), "los_rate_error"), 0);
  EXPECT_EQ(csv_column("los_rate_error"), 0);
  EXPECT_EQ(csv_column("los_rate_error", true), static_cast<int>(plain.size()) + 2);

  const Scenario tracking = load_scenario(kScenarios / "track_crossing.json");
  const Scenario slewing = load_scenario(kScenarios / "seeker_slew.json");
  EXPECT_GT(csv_size_bound(tracking) / (tracking.run.ticks + 1), csv_row_bytes_bound(tracking.run.ticks));
  for (const Scenario* s : {&tracking, &slewing}) {
    Scenario shorter = *s;
    shorter.run.ticks = 5;
    ColumnRecorder rec;
    RunOptions quiet;
    quiet.progress = false;
    (void)run_scenario(shorter, rec, quiet);
    EXPECT_EQ(rec.columns().size(), csv_columns(s->track.has_value()).size()) << s->file;
    EXPECT_EQ(rec.columns().back().numbers.size(), s->track ? 6u : 0u) << s->file;
  }
}

struct Refusal {
  const char* what;
  void (*edit)(json&);
  const char* field;
  const char* reason;
};

TEST(SilTracking, BadTrackSectionsAreRefusedNamingFieldValueAndBound) {
  const Refusal cases[] = {
      {"gain above a quarter per tick", [](json& t) { t["gain_1_s"] = 300.0; }, "guidance.track.gain_1_s",
       "must be <= 250 (0.25 / run.rate_hz: the loop sees a one-tick-old estimate), got 300"},
      {"negative gain", [](json& t) { t["gain_1_s"] = -1.0; }, "guidance.track.gain_1_s", "must be >= 0, got -1"},
      {"negative start", [](json& t) { t["start_s"] = -0.1; }, "guidance.track.start_s", "must be >= 0, got -0.1"},
      {"no line of sight", [](json& t) { t.erase("line_of_sight"); }, "guidance.track.line_of_sight",
       "give either \"line_of_sight\""},
      {"both kinds of line of sight",
       [](json& t) { t["target"] = {{"position_m", {1000.0, 0.0, 0.0}}}; }, "guidance.track.target",
       "give either \"line_of_sight\""},
      {"zero direction", [](json& t) { t["line_of_sight"]["direction"] = {0.0, 0.0, 0.0}; },
       "guidance.track.line_of_sight.direction", "must be a non-zero finite vector, got length 0"},
      {"LOS rate too high", [](json& t) { t["line_of_sight"]["rate_rad_s"] = {0.0, 0.0, 101.0}; },
       "guidance.track.line_of_sight.rate_rad_s", "its magnitude must be <= 100 rad/s, got 101"},
      {"own without target", [](json& t) { t["own"] = json::object(); }, "guidance.track.own", "only with \"target\""},
      {"target through the own position",
       [](json& t) {
         t.erase("line_of_sight");
         t["target"] = {{"position_m", {100.0, 0.5, 0.0}}, {"velocity_m_s", {-200.0, 0.0, 0.0}}};
       },
       "guidance.track.target", "the target comes within 0.5 m of the own position during the run; the range must "
                                "stay >= 1 m"},
      {"unknown key", [](json& t) { t["gain"] = 1.0; }, "guidance.track.gain", "unknown"},
  };
  const json good = {{"start_s", 0.3}, {"gain_1_s", 20.0}, {"line_of_sight", {{"direction", {1.0, 0.0, 0.0}}}}};
  ASSERT_NO_THROW((void)parse_scenario_document(seeker_tracking(good), "good"));
  for (const Refusal& c : cases) {
    SCOPED_TRACE(c.what);
    json track = good;
    c.edit(track);
    try {
      (void)parse_scenario_document(seeker_tracking(track), "bad");
      ADD_FAILURE() << "accepted";
    } catch (const ScenarioError& e) {
      EXPECT_EQ(e.field(), c.field) << e.what();
      EXPECT_NE(e.reason().find(c.reason), std::string::npos) << e.what();
    }
  }
}

TEST(SilTracking, ASlewCommandTheTrackerWouldOverrideIsRefused) {
  json doc = seeker_tracking({{"start_s", 0.3}, {"line_of_sight", {{"direction", {1.0, 0.0, 0.0}}}}});
  doc["guidance"]["schedule"].push_back({{"t_s", 0.5}, {"slew_rate_rad_s", {0.1, 0.0}}});
  try {
    (void)parse_scenario_document(doc, "bad");
    ADD_FAILURE() << "accepted";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.field(), "guidance.schedule[2].slew_rate_rad_s");
    EXPECT_NE(e.reason().find("the tracker commands the slew from guidance.track.start_s = 0.3 s on"),
              std::string::npos)
        << e.what();
  }
  doc["guidance"]["schedule"][2]["t_s"] = 0.25;  // before the tracker starts: flown
  EXPECT_NO_THROW((void)parse_scenario_document(doc, "good"));
}

}  // namespace
}  // namespace gyro::sil::sil_tracking_test
