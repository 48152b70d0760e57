// gyro_campaign's report (summary.md) and its metrics of safe mode: the outcome per fault
// kind, a failed run's likely cause, false alarms apart from safe mode after stop contact.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "campaign_error.hpp"
#include "campaign_file.hpp"
#include "run_metrics.hpp"
#include "run_table.hpp"
#include "summary.hpp"

namespace gyro::campaign {
namespace {

// Two options in turn (none, bias_jump at 0.6 s), safe-mode and stop metrics, three criteria.
Campaign summary_campaign() {
  return parse_campaign(R"({
    "base": "scenarios/seeker_slew.json", "runs": 6, "seed": 1,
    "fault_injection": { "faults": [ { "kind": "none" },
                                     { "kind": "bias_jump", "start_s": 0.6, "magnitude": 0.01 } ] },
    "metrics": { "safe_mode": true, "final_mode": true, "gimbal_stop": true },
    "criteria": [ { "metric": "false_alarm", "equals": false },
                  { "metric": "final_mode", "equals": "free", "runs": "fault_free" },
                  { "metric": "detected", "equals": true, "runs": "faulted" },
                  { "metric": "latency_s", "max": 0.1, "runs": "faulted" } ]
  })",
                        "c.json", GYRO_SOURCE_DIR);
}

// A row of the campaign's table from the cells given by column name (others empty).
std::string row(const Campaign& c, const std::map<std::string, std::string>& cells) {
  std::vector<std::string> out;
  for (const std::string& name : table_header(c)) {
    const auto it = cells.find(name);
    out.push_back(it == cells.end() ? "" : it->second);
  }
  return csv_line(out);
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(CampaignSummary, GivenFailedRunsThenEachHasItsLikelyCause) {
  const Campaign c = summary_campaign();
  const std::vector<std::string> rows = {
      // 0: fault-free, on the stop at 0.93 s, safe mode at 0.95 s by the residual
      row(c, {{"run", "0"}, {"seed", "1"}, {"status", "ok"}, {"pass", "false"}, {"fault_kind", "none"},
              {"safe_mode_s", "0.95"}, {"safe_mode_cause", "residual"}, {"false_alarm", "false"},
              {"safe_mode_after_stop", "true"}, {"final_mode", "fault"}, {"stop_contact_s", "0.93"},
              {"time_at_stop_s", "0.2"}, {"failed", "2"}, {"reason", "final_mode = free: fault"}}),
      // 1: bias jump at 0.6 s, detected at 0.62 s
      row(c, {{"run", "1"}, {"seed", "2"}, {"status", "ok"}, {"pass", "true"}, {"fault_kind", "bias_jump"},
              {"fault_start_s", "0.6"}, {"safe_mode_s", "0.62"}, {"safe_mode_cause", "pickoff"}, {"detected", "true"},
              {"false_alarm", "false"}, {"safe_mode_after_stop", "false"}, {"latency_s", "0.02"},
              {"final_mode", "fault"}, {"time_at_stop_s", "0"}}),
      // 2: fault-free, safe mode at 0.5 s by the spin monitor: a false alarm
      row(c, {{"run", "2"}, {"seed", "3"}, {"status", "ok"}, {"pass", "false"}, {"fault_kind", "none"},
              {"safe_mode_s", "0.5"}, {"safe_mode_cause", "spin"}, {"false_alarm", "true"},
              {"safe_mode_after_stop", "false"}, {"final_mode", "fault"}, {"time_at_stop_s", "0"},
              {"failed", "1;2"}, {"reason", "false_alarm: true"}}),
      // 3: bias jump at 0.6 s never detected
      row(c, {{"run", "3"}, {"seed", "4"}, {"status", "ok"}, {"pass", "false"}, {"fault_kind", "bias_jump"},
              {"fault_start_s", "0.6"}, {"detected", "false"}, {"false_alarm", "false"},
              {"safe_mode_after_stop", "false"}, {"final_mode", "free"}, {"time_at_stop_s", "0"}, {"failed", "3"}}),
      // 4: bias jump at 0.6 s detected at 0.9 s by the residual: late
      row(c, {{"run", "4"}, {"seed", "5"}, {"status", "ok"}, {"pass", "false"}, {"fault_kind", "bias_jump"},
              {"fault_start_s", "0.6"}, {"safe_mode_s", "0.9"}, {"safe_mode_cause", "residual"}, {"detected", "true"},
              {"false_alarm", "false"}, {"safe_mode_after_stop", "false"}, {"latency_s", "0.3"},
              {"final_mode", "fault"}, {"time_at_stop_s", "0"}, {"failed", "4"}}),
      // 5: refused
      row(c, {{"run", "5"}, {"seed", "6"}, {"status", "refused"}, {"pass", "false"}, {"fault_kind", "bias_jump"},
              {"reason", "component.estimator_gain: input out of range"}})};
  const RunTable t(c, rows, "runs.csv");
  const std::string md = make_summary(c, t, {});

  EXPECT_TRUE(has(md, "5 runs did not pass. By likely cause: late detection 1, not detected 1, refused 1, spin 1, "
                      "stop contact 1.")) << md;
  EXPECT_TRUE(has(md, "| 0 | 1 | none | ok | stop contact | stop contact at 0.93 s; safe mode at 0.95 s by residual |"))
      << md;
  EXPECT_TRUE(has(md, "| 2 | 3 | none | ok | spin | safe mode at 0.5 s by spin |")) << md;
  EXPECT_TRUE(has(md, "| 3 | 4 | bias_jump | ok | not detected | fault at 0.6 s not detected; ended free |")) << md;
  EXPECT_TRUE(has(md, "| 4 | 5 | bias_jump | ok | late detection | detected at 0.9 s by residual; latency 300 ms |"))
      << md;
  EXPECT_TRUE(has(md, "| 5 | 6 | bias_jump | refused | refused | component.estimator_gain: input out of range | – |"))
      << md;
  // The fault-free row of the detection table: one false alarm, one safe mode after stop contact.
  EXPECT_TRUE(has(md, "| none | 2 | – | – | – | 1 | 50.00 % |")) << md;
  EXPECT_TRUE(has(md, "| 1 | – | – | – | – | residual 1, spin 1 |")) << md;
  // The outcome per kind, and the metrics apart.
  EXPECT_TRUE(has(md, "| none (fault-free) | 2 | 0 | 2 | 0 | 0 | 0.00 % |")) << md;
  EXPECT_TRUE(has(md, "| bias_jump | 4 | 1 | 2 | 1 | 0 | 25.00 % |")) << md;
  EXPECT_TRUE(has(md, "| safe_mode_s (fault-free) | 2 | 0.5 |")) << md;
  EXPECT_TRUE(has(md, "| safe_mode_s (faulted) | 2 | 0.62 |")) << md;
}

sil::TickRecord tick(std::uint64_t k, GyroMode mode, std::uint32_t flags, bool at_stop) {
  sil::TickRecord r;
  r.tick = k;
  r.t_s = 0.001 * static_cast<double>(k);
  r.mode = mode;
  r.flags = flags;
  r.at_gimbal_stop = at_stop;
  return r;
}

// The metrics of ticks 0..19 of a fault-free run: on the stop from `stop_tick`, safe mode
// from `safe_tick` with `flags` on its first tick.
RunMetrics fault_free_run(std::uint64_t stop_tick, std::uint64_t safe_tick, std::uint32_t flags) {
  sil::Scenario s;
  s.run.tick_s = 0.001;
  MetricSet set;
  set.safe_mode = set.gimbal_stop = true;
  MetricsObserver m(s, set);
  for (std::uint64_t k = 0; k < 20; ++k) {
    const bool safe = k >= safe_tick;
    m.on_tick(tick(k, safe ? GyroMode::kFault : GyroMode::kFree, k == safe_tick ? flags | kFaultLatched : 0u,
                   k >= stop_tick));
  }
  return m.finish(sil::RunSummary{});
}

TEST(CampaignMetrics, GivenSafeModeAfterStopContactThenItIsNoFalseAlarm) {
  const RunMetrics m = fault_free_run(10, 12, kResidualFault);
  EXPECT_FALSE(m.false_alarm);
  EXPECT_TRUE(m.safe_mode_after_stop);
  EXPECT_EQ(m.safe_mode_cause, "residual");
  EXPECT_DOUBLE_EQ(m.stop_contact_s.value_or(-1), 0.010);
}

TEST(CampaignMetrics, GivenSafeModeBeforeStopContactThenItIsAFalseAlarm) {
  const RunMetrics m = fault_free_run(15, 12, kSpinLow | kPickoffStale);
  EXPECT_TRUE(m.false_alarm);
  EXPECT_FALSE(m.safe_mode_after_stop);
  EXPECT_EQ(m.safe_mode_cause, "pickoff+spin");
}

TEST(CampaignMetrics, GivenEachMonitorsFlagThenTheCauseNamesIt) {
  EXPECT_EQ(safe_mode_cause(kResidualFault), "residual");
  EXPECT_EQ(safe_mode_cause(kPickoffJump), "pickoff");
  EXPECT_EQ(safe_mode_cause(kInputFault | kNavInvalid), "input");
  EXPECT_EQ(safe_mode_cause(kTorquerWriteFailed), "torquer");
  EXPECT_EQ(safe_mode_cause(kFaultLatched), "other");
}

TEST(CampaignRuns, GivenTheFirstRunsThenTheCampaignSaysSoAndIsOtherwiseTheSame) {
  Campaign c = summary_campaign();
  const std::string whole = c.fingerprint;
  keep_first_runs(c, 4);
  EXPECT_EQ(c.runs, 4u);
  EXPECT_NE(c.fingerprint, whole);
  const Campaign back = parse_campaign(c.resolved_text, "campaign.json", GYRO_SOURCE_DIR);
  EXPECT_EQ(back.runs, 4u);
  EXPECT_EQ(back.fingerprint, c.fingerprint);
  EXPECT_THROW(keep_first_runs(c, 5), CampaignError);
  EXPECT_THROW(keep_first_runs(c, 0), CampaignError);
}

}  // namespace
}  // namespace gyro::campaign
