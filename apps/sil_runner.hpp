// The software-in-the-loop loop of gyro_sil: the flight component against the simulated
// gyro at the scenario's fixed tick, with the body's motion and the guidance schedule.
//
// Tick 0: the stub powers up aligned with the body (start), the component is activated
// (caged) and steps once on the power-up conversion. Then for k = 1 .. run.ticks:
//   body motion to tick k -> stub.advance(k, R_earth_to_body, accel)
//   -> guidance for tick k (schedule) -> component.step(k, guidance) -> CSV row.
// The CSV has one row per tick, run.ticks + 1 rows after the header.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "csv_writer.hpp"
#include "pil_options.hpp"
#include "scenario.hpp"

namespace gyro::sil {

// The columns every gyro_sil CSV starts with, in this order.
inline constexpr std::array<std::string_view, 11> kRequiredColumns = {
    "t",          "mode",     "gimbal_pitch", "gimbal_yaw",  "gimbal_pitch_meas", "gimbal_yaw_meas",
    "theta_rate", "psi_rate", "torque_pitch", "torque_yaw", "flags"};

// Every column written (the required ones first); see docs/scenarios.md for their meaning.
[[nodiscard]] std::span<const std::string_view> csv_columns() noexcept;
// 1-based column number of `name` (for gnuplot); 0 if there is no such column.
[[nodiscard]] int csv_column(std::string_view name) noexcept;

// Upper bounds of a row's length (newline included) in a run of `ticks` ticks, and of the
// whole CSV of a scenario (header and run.ticks + 1 rows): each column at its widest (a
// number as "-1.234567890e-308", the flag words at every bit set, the longest name).
[[nodiscard]] std::uint64_t csv_row_bytes_bound(std::uint64_t ticks);
[[nodiscard]] std::uint64_t csv_size_bound(const Scenario& s);

// The software failed at run time (not the scenario's fault): the stub or the component
// refused a call the loop relies on.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RunOptions {
  bool progress{true};           // progress lines on `progress_out` for runs over a second
  std::FILE* progress_out{stderr};
  std::string label{"gyro_sil"};  // prefix of the progress lines
  // The run stops (RunError) once the CSV passes this many bytes: a guard behind the check
  // of csv_size_bound() up front, which should always have refused such a run first.
  std::uint64_t max_csv_bytes{std::numeric_limits<std::uint64_t>::max()};
  // Processor in the loop: the component runs on an emulated target over a serial line
  // (pil_flight.hpp) instead of in process; the CSV gains the pil_* columns.
  std::optional<PilOptions> pil;
};

struct RunSummary {
  Precision precision{Precision::kDouble};
  std::uint64_t ticks{0};            // ticks after tick 0
  std::uint64_t rows{0};             // CSV rows after the header
  GyroMode final_mode{GyroMode::kIdle};
  std::uint32_t flags_seen{0};       // OR of the component's flags over the run
  std::array<std::uint32_t, kComponentFlagCount> counters{};  // the component's, at the end
  std::uint64_t refused_steps{0};    // component.step() calls that did not return kOk
  std::uint64_t nonfinite_values{0}; // NaN or infinite numbers written to the CSV
  std::uint64_t gimbal_stop_hits{0}; // ticks in which the stub's gimbal hit its stop
  double max_abs_gimbal_rad{0};      // largest true gimbal angle, either axis
  double wall_s{0};                  // wall-clock time of the loop (not in the CSV)
  std::optional<PilSummary> pil;     // a processor-in-the-loop run's timing and link figures
};

// Checks the scenario in its precision: the range of its numbers, then configures a stub and a
// component with it (a refusal names the JSON field of what configure() refused), then what the
// run can represent (scenario_limits.hpp). Throws ScenarioError.
void check_configs(const Scenario& s);

// Reads, parses and checks the scenario; `precision` overrides the file's run.precision.
[[nodiscard]] Scenario load_scenario(const std::filesystem::path& path,
                                     std::optional<Precision> precision = std::nullopt);

// Runs the scenario, writing the header and every row to `csv`. Throws ScenarioError
// (configuration refused) or RunError.
RunSummary run_scenario(const Scenario& s, CsvWriter& csv, const RunOptions& options = {});

// Names of the flags set in `flags`, separated by '|' ("" for none).
[[nodiscard]] std::string flag_names(std::uint32_t flags);

}  // namespace gyro::sil
