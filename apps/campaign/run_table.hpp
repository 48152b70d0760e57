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

// The largest runs.csv merge reads (1 GiB, checked before reading): kMaxRuns rows of about
// 1 kB, the size of the seeker campaigns' rows.
inline constexpr std::uint64_t kMaxRunTableBytes = 1u << 30;

// The rows of a campaign's table, each kept as its line of CSV with the offsets of its cells
// (about 1 kB a run for the seeker campaigns: a million runs fit in memory).
class RunTable {
 public:
  // From rows (lines of CSV, each with or without its '\n'), taken over. Throws
  // CampaignError(file, "line N", reason) for broken quoting, a row of the wrong width, or a
  // first cell that is not a run index of the campaign.
  RunTable(const Campaign& c, std::vector<std::string> rows, const std::string& file, std::size_t first_line = 2);

  [[nodiscard]] const std::vector<std::string>& header() const noexcept { return header_; }
  [[nodiscard]] std::size_t size() const noexcept { return lines_.size(); }
  [[nodiscard]] std::optional<std::size_t> column(std::string_view name) const;
  // A cell as written (quotes included, if it has them); a cell's text without them.
  [[nodiscard]] std::string_view cell(std::size_t row, std::size_t col) const;
  [[nodiscard]] std::string text(std::size_t row, std::size_t col) const;
  // The row's line, without its newline.
  [[nodiscard]] const std::string& line(std::size_t row) const { return lines_[row]; }

  // One row's cells as written: row[col].
  class Row {
   public:
    Row(const RunTable& t, std::size_t i) noexcept : t_(&t), i_(i) {}
    [[nodiscard]] std::string_view operator[](std::size_t col) const { return t_->cell(i_, col); }
    [[nodiscard]] std::size_t index() const noexcept { return i_; }

   private:
    const RunTable* t_;
    std::size_t i_;
  };
  [[nodiscard]] Row row(std::size_t i) const noexcept { return Row(*this, i); }

 private:
  std::vector<std::string> header_;
  std::vector<std::string> lines_;
  std::vector<std::uint32_t> starts_;  // per row: the start of each cell, then the line's length
};

// Parses runs.csv text (header checked against the campaign's); `file` names it in errors.
[[nodiscard]] RunTable parse_run_table(std::string_view text, const Campaign& c, const std::string& file);

// The run index of a row's text (its first cell); nullopt if it is not one.
[[nodiscard]] std::optional<std::uint64_t> row_run_index(std::string_view row);

}  // namespace gyro::campaign
