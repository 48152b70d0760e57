// The summary a reviewer reads (summary.md), made from the per-run table alone, so that a
// campaign run in one process, over MPI ranks, or in shards merged afterwards gives the same
// bytes: the outcome and every criterion as rates with 95 % Wilson intervals, fault
// detection per fault kind (detection rate, false alarms, latency percentiles), percentiles
// of every metric, the range of every dispersed value, the failed runs, and the plots.
// Nothing in it depends on the output directory, the parallelism or the clock.
#pragma once

#include <string>
#include <vector>

#include "campaign_file.hpp"
#include "run_table.hpp"

namespace gyro::campaign {

// Markdown. `plots` are the image files (relative to the summary) to show at the end.
[[nodiscard]] std::string make_summary(const Campaign& c, const RunTable& t, const std::vector<std::string>& plots);

// "12.3" style numbers for the summary: `digits` significant digits, no locale.
[[nodiscard]] std::string format_significant(double v, int digits);

}  // namespace gyro::campaign
