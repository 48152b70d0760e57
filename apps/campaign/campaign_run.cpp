#include "campaign_run.hpp"

namespace gyro::campaign {

const char* to_string(RunStatus s) noexcept {
  switch (s) {
    case RunStatus::kOk: return "ok";
    case RunStatus::kRefused: return "refused";
    case RunStatus::kError: return "error";
  }
  return "unknown";
}

RunResult execute_run(const Campaign& c, std::uint64_t index, sil::TickObserver* also) {
  RunResult r;
  r.plan = plan_run(c, index);
  sil::Scenario s;
  try {
    s = sil::parse_scenario_document(r.plan.scenario, c.file + " run " + std::to_string(index));
    sil::check_configs(s);
  } catch (const sil::ScenarioError& e) {
    r.status = RunStatus::kRefused;
    r.reason = e.field() + ": " + e.reason();
    return r;
  }
  MetricsObserver metrics(s, c.metrics);
  sil::FanOutObserver fan({&metrics, also});
  sil::RunOptions quiet;
  quiet.progress = false;
  try {
    const sil::RunSummary sum = also != nullptr ? sil::run_scenario(s, fan, quiet) : sil::run_scenario(s, metrics, quiet);
    if (sum.nonfinite_values != 0) {
      r.status = RunStatus::kError;
      r.reason = std::to_string(sum.nonfinite_values) + " non-finite values in the time history";
      return r;
    }
    r.metrics = metrics.finish(sum);
  } catch (const sil::ScenarioError& e) {
    r.status = RunStatus::kRefused;
    r.reason = e.field() + ": " + e.reason();
  } catch (const sil::RunError& e) {
    r.status = RunStatus::kError;
    r.reason = e.what();
  }
  return r;
}

}  // namespace gyro::campaign
