// The plot that explains a run (apps/run_plot.hpp, run_timeline.hpp): the timeline built tick
// by tick, and what the gnuplot script of a shipped fault scenario marks.
#include <gtest/gtest.h>

#include <filesystem>
#include <numeric>
#include <string>

#include "plot.hpp"
#include "run_plot.hpp"
#include "run_timeline.hpp"
#include "scenario.hpp"
#include "sil_runner.hpp"

namespace gyro::sil {
namespace {

const std::filesystem::path kScenarioDir = std::filesystem::path(GYRO_SOURCE_DIR) / "scenarios";

TickRecord tick(std::uint64_t k, GyroMode mode, std::uint32_t flags) {
  TickRecord r;
  r.tick = k;
  r.t_s = 0.001 * static_cast<double>(k);
  r.mode = mode;
  r.flags = flags;
  return r;
}

double total_s(const std::vector<TimeSpan>& spans) {
  return std::accumulate(spans.begin(), spans.end(), 0.0,
                         [](double a, const TimeSpan& s) { return a + (s.to_s - s.from_s); });
}

struct ScenarioRun {
  Scenario scenario;
  RunTimeline timeline;
};

ScenarioRun run_with_timeline(const std::string& name) {
  ScenarioRun out{load_scenario(kScenarioDir / name), {}};
  TimelineObserver timeline(out.scenario.run.tick_s, timeline_resolution_s(out.scenario));
  RunOptions quiet;
  quiet.progress = false;
  (void)run_scenario(out.scenario, timeline, quiet);
  out.timeline = timeline.timeline();
  return out;
}

TEST(RunTimeline, GivenFlagGapsBelowTheResolutionThenTheyJoinIntoOneBar) {
  // GIVEN a flag raised on ticks 0-1, 3 and 9 at a resolution of 2 ticks
  TimelineObserver o(0.001, 0.002);
  for (std::uint64_t k = 0; k < 10; ++k) {
    const bool raised = k <= 1 || k == 3 || k == 9;
    o.on_tick(tick(k, GyroMode::kFree, raised ? kResidualFault : 0u));
  }
  // THEN ticks 0-3 are one bar (a gap of one tick), tick 9 another (a gap of five)
  const std::vector<TimeSpan>& bars = o.timeline().flags[6];
  ASSERT_EQ(bars.size(), 2u);
  EXPECT_DOUBLE_EQ(bars[0].from_s, 0.0);
  EXPECT_DOUBLE_EQ(bars[0].to_s, 0.004);
  EXPECT_DOUBLE_EQ(bars[1].from_s, 0.009);
  EXPECT_DOUBLE_EQ(o.timeline().end_s, 0.010);
}

TEST(RunTimeline, GivenAOneTickModeThenTheBandKeepsItWhateverTheResolution) {
  TimelineObserver o(0.001, 1.0);
  o.on_tick(tick(0, GyroMode::kCaged, 0u));
  o.on_tick(tick(1, GyroMode::kUncaging, 0u));
  o.on_tick(tick(2, GyroMode::kFree, 0u));
  o.on_tick(tick(3, GyroMode::kFree, 0u));
  const std::vector<ModeSpan>& m = o.timeline().modes;
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[1].mode, GyroMode::kUncaging);
  EXPECT_DOUBLE_EQ(m[1].span.to_s - m[1].span.from_s, 0.001);
  EXPECT_DOUBLE_EQ(m[2].span.to_s, 0.004);
}

TEST(RunTimeline, GivenTheEventsThenEachIsTheFirstTickItHappened) {
  TimelineObserver o(0.001, 0.001);
  for (std::uint64_t k = 0; k < 8; ++k) {
    TickRecord r = tick(k, k >= 5 ? GyroMode::kFault : GyroMode::kFree, 0u);
    r.request = (k == 2 || k == 6) ? ModeRequest::kUncage : ModeRequest::kNone;
    r.at_gimbal_stop = k >= 4;
    r.active_faults = k >= 3 ? fault_bit(FaultKind::kDeadTorquer) : 0u;
    o.on_tick(r);
  }
  const RunTimeline& t = o.timeline();
  EXPECT_DOUBLE_EQ(t.uncage_s.value_or(-1), 0.002);
  EXPECT_DOUBLE_EQ(t.latched_s.value_or(-1), 0.005);
  EXPECT_DOUBLE_EQ(t.stop_contact_s.value_or(-1), 0.004);
  ASSERT_EQ(t.faults[static_cast<std::size_t>(FaultKind::kDeadTorquer)].size(), 1u);
  EXPECT_DOUBLE_EQ(t.faults[static_cast<std::size_t>(FaultKind::kDeadTorquer)][0].from_s, 0.003);
}

TEST(RunPlot, GivenTheDeadTorquerThenThePlotMarksTheLatchAndItsLimits) {
  // GIVEN scenarios/fault_dead_torquer.json: yaw torquer dead from 0.6 s
  const ScenarioRun run = run_with_timeline("fault_dead_torquer.json");
  // THEN the fault latches at 0.683 s, after 83 ticks
  ASSERT_TRUE(run.timeline.latched_s.has_value());
  EXPECT_NEAR(*run.timeline.latched_s, 0.683, 1e-9);
  EXPECT_FALSE(run.timeline.stop_contact_s.has_value());
  const std::string script = gnuplot_script(run_plot("run.csv", "run.png", "t", run.scenario, run.timeline));
  // AND the script names the events, shades the fault's window and draws every limit
  for (const char* text : {"'fault latched 0.683 s'", "'uncage 0.2 s'", "'dead_torquer injected at 0.6 s'",
                           "set object rect from first 0.6,", "title 'limit 0.005'", "title 'stop 0.4'",
                           "title 'max_torque 0.04'", "title 'torquer saturation 0.05'", "title 'rate limit 1'",
                           "'fault dead_torquer' ", "'fault_latched' ", "'residual_fault' ", "'mode' ",
                           "using 1:(abs($"}) {
    EXPECT_NE(script.find(text), std::string::npos) << text;
  }
  EXPECT_EQ(script.find("'at stop (true)'"), std::string::npos) << "never on the stop";
}

TEST(RunPlot, GivenTheSaturatedTorquerThenTheTimeOnTheStopIsShown) {
  const ScenarioRun run = run_with_timeline("fault_saturated_torquer.json");
  ASSERT_TRUE(run.timeline.stop_contact_s.has_value());
  EXPECT_NEAR(*run.timeline.stop_contact_s, 1.95, 1e-9);
  // 703 ticks on the stop, in bars at most one resolution (1.5 ms) apart
  EXPECT_NEAR(total_s(run.timeline.at_stop), 0.703, 2 * timeline_resolution_s(run.scenario));
  const std::string script = gnuplot_script(run_plot("run.csv", "run.png", "t", run.scenario, run.timeline));
  EXPECT_NE(script.find("'at stop (true)'"), std::string::npos);
  EXPECT_NE(script.find("'stop contact 1.95 s'"), std::string::npos);
}

TEST(RunPlot, GivenALongRunThenSeriesAreThinnedAndTheTitleSaysSo) {
  Scenario s = load_scenario(kScenarioDir / "seeker_slew.json");
  s.run.ticks = 99'999;  // 100,000 rows
  RunTimeline t;
  t.end_s = 100.0;
  const PlotRequest r = run_plot("run.csv", "run.png", "t", s, t);
  EXPECT_EQ(r.every, 5u);
  EXPECT_NE(r.title.find("one tick in 5"), std::string::npos);
  EXPECT_NE(gnuplot_script(r).find(" skip 1 every 5 using "), std::string::npos);
}

TEST(SilPlot, GivenTwoNamesCloseInTimeThenTheyGoOnSeparateLines) {
  PlotRequest r;
  r.end_s = 1.0;
  r.panels.push_back({});
  r.markers = {{0.50, "fault latched 0.5 s", "#d62728"}, {0.51, "stop contact 0.51 s", "#222222"},
               {0.90, "late", "#222222"}};
  const std::string s = gnuplot_script(r);
  EXPECT_NE(s.find("'fault latched 0.5 s' at first 0.5, graph 1 offset 0,0.7 "), std::string::npos) << s;
  EXPECT_NE(s.find("'stop contact 0.51 s' at first 0.51, graph 1 offset 0,1.7 "), std::string::npos) << s;
  EXPECT_NE(s.find("'late' at first 0.9, graph 1 offset 0,0.7 "), std::string::npos) << s;
}

}  // namespace
}  // namespace gyro::sil
