// One run of a campaign, executed: the planned scenario is parsed and checked like any
// scenario (a refusal is the run's result, not an error of the campaign), run through the
// SIL loop with the metrics observer, and judged against the criteria.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "campaign_file.hpp"
#include "run_metrics.hpp"
#include "run_plan.hpp"
#include "sil_runner.hpp"

namespace gyro::campaign {

enum class RunStatus : std::uint8_t {
  kOk,       // ran to the end
  kRefused,  // the dispersed scenario was refused (by the schema, the stub or the component)
  kError,    // the loop failed (a call refused at run time, or non-finite values)
};
[[nodiscard]] const char* to_string(RunStatus s) noexcept;

struct RunResult {
  RunPlan plan;
  RunStatus status{RunStatus::kOk};
  std::string reason;                 // refused / error: "field: reason"
  std::optional<RunMetrics> metrics;  // ok
};

// Plans and runs run `index`; `also` (e.g. a CSV writer) sees every tick too.
[[nodiscard]] RunResult execute_run(const Campaign& c, std::uint64_t index, sil::TickObserver* also = nullptr);

}  // namespace gyro::campaign
