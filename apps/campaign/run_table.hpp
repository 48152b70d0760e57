// The per-run table (runs.csv): one row per run, in run order, with the run's seed, every
// dispersed value, the injected fault, every metric and the verdict. Cells are text:
// numbers in the shortest form that reads back to the same double (std::to_chars), so a
// table read back (gyro_campaign merge) holds exactly the values that were written, and the
// summary made from it is the same byte for byte. An empty cell is "no value".
//
// Columns: run, seed, status, pass, [fault_kind, fault_start_s, fault_duration_s,
// fault_axis, fault_magnitude], <one per dispersion: its path>, <the metric columns>,
// failed (the numbers of the criteria the run failed, "1;3"), reason (why refused or failed).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "campaign_file.hpp"
#include "campaign_run.hpp"

namespace gyro::campaign {

[[nodiscard]] std::vector<std::string> table_header(const Campaign& c);

// The row of a run (criteria judged here), ending in '\n'.
[[nodiscard]] std::string format_row(const Campaign& c, const RunResult& r);

// A line of CSV cells (quoted where a cell holds a comma or a quote), without the newline.
[[nodiscard]] std::string csv_line(const std::vector<std::string>& cells);
// One line of CSV -> cells; nullopt if the quoting is broken.
[[nodiscard]] std::optional<std::vector<std::string>> split_csv_line(std::string_view line);

// Shortest round-trip text of a double.
[[nodiscard]] std::string number_cell(double v);
// A cell's number; nullopt for an empty or non-numeric cell.
[[nodiscard]] std::optional<double> cell_number(std::string_view cell);

struct RunTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // in run order, one per run
  [[nodiscard]] std::optional<std::size_t> column(std::string_view name) const;
};

// Parses runs.csv text; `file` names it in errors (CampaignError: header mismatch, a row of
// the wrong width, a run index out of order or out of range).
[[nodiscard]] RunTable parse_run_table(std::string_view text, const Campaign& c, const std::string& file);

// The run index of a row's text (its first cell); nullopt if it is not one.
[[nodiscard]] std::optional<std::uint64_t> row_run_index(std::string_view row);

}  // namespace gyro::campaign
