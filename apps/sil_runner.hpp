// The software-in-the-loop loop of gyro_sil: the flight component against the simulated
// gyro at the scenario's fixed tick, with the body's motion and the guidance schedule.
//
// Tick 0: the stub powers up aligned with the body (start), the component is activated
// (caged) and steps once on the power-up conversion. Then for k = 1 .. run.ticks:
//   body motion to tick k -> stub.advance(k, R_earth_to_body, accel)
//   -> guidance for tick k (schedule; from guidance.track.start_s the tracker's slew command,
//      los_tracking.hpp) -> component.step(k, guidance) -> CSV row
// (a tick of gyro/sil_loop.hpp, the loop every SIL user runs).
// The CSV has one row per tick, run.ticks + 1 rows after the header.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "csv_writer.hpp"
#include "gyro/status.hpp"
#include "pil_options.hpp"
#include "scenario.hpp"

namespace gyro::sil {

// The columns every gyro_sil CSV starts with, in this order.
inline constexpr std::array<std::string_view, 11> kRequiredColumns = {
    "t",          "mode",     "gimbal_pitch", "gimbal_yaw",  "gimbal_pitch_meas", "gimbal_yaw_meas",
    "theta_rate", "psi_rate", "torque_pitch", "torque_yaw", "flags"};

// What one tick of the loop produced, in double whatever the run's precision.
struct TickRecord {
  std::uint64_t tick{0};
  double t_s{0};
  GyroMode mode{GyroMode::kIdle};
  ModeRequest request{ModeRequest::kNone};      // what guidance sent this tick
  std::uint32_t flags{0};                       // the component's, this tick
  Eigen::Vector2d gimbal_true_rad{Eigen::Vector2d::Zero()};       // the stub's model
  Eigen::Vector2d gimbal_measured_rad{Eigen::Vector2d::Zero()};   // last accepted reading
  Eigen::Vector2d gimbal_predicted_rad{Eigen::Vector2d::Zero()};  // the component's estimate
  Eigen::Vector2d residual_rad{Eigen::Vector2d::Zero()};
  Eigen::Vector2d rate_est_rad_s{Eigen::Vector2d::Zero()};
  Eigen::Vector2d rate_true_rad_s{Eigen::Vector2d::Zero()};
  Eigen::Vector2d rate_cmd_rad_s{Eigen::Vector2d::Zero()};        // after limits and stop protection
  Eigen::Vector2d slew_cmd_rad_s{Eigen::Vector2d::Zero()};        // what guidance asked
  Eigen::Vector2d torque_cmd{Eigen::Vector2d::Zero()};
  Eigen::Vector2d nutation_est_rad{Eigen::Vector2d::Zero()};
  Eigen::Vector2d nutation_true_rad{Eigen::Vector2d::Zero()};
  double cone_true_rad{0};
  double spin_hz{0};
  double spin_hz_true{0};
  Eigen::Vector2d torque_applied{Eigen::Vector2d::Zero()};
  Eigen::Vector3d body_rate_rad_s{Eigen::Vector3d::Zero()};     // (p, q, r)
  std::uint32_t truth_flags{0};  // bit 2 at the stop; bits 0-1 the report plant's gimbal-limit, small-angle flags
  bool at_gimbal_stop{false};
  std::uint32_t active_faults{0};               // the stub's, bit (1 << FaultKind)
  Status step_status{Status::kOk};
  // A run that tracks a line of sight (guidance.track) has two more columns, from tick 0 on.
  bool tracking{false};
  double pointing_error_true_rad{0};  // true spin axis (the stub's) to the LOS
  double los_rate_error_rad_s{0};     // |estimated - true spin-axis inertial rate|
};

// Receives every tick of a run, tick 0 first.
class TickObserver {
 public:
  virtual ~TickObserver() = default;
  // The flight computer's own columns (a processor in the loop's pil_*), after the standard
  // ones: their names, and what writes this tick's cells. Given before on_start(); the
  // observer that writes the CSV appends them, others ignore them.
  virtual void set_extra_columns(std::span<const std::string_view> /*names*/,
                                 std::function<void(CsvWriter&)> /*write*/) {}
  // Once, after both sides were configured and before tick 0, with the scenario run.
  virtual void on_start(const Scenario& /*s*/) {}
  virtual void on_tick(const TickRecord& r) = 0;
};

// Shows every tick to several observers, in order (the extra columns go to each).
class FanOutObserver final : public TickObserver {
 public:
  explicit FanOutObserver(std::vector<TickObserver*> to) : to_(std::move(to)) {}
  void set_extra_columns(std::span<const std::string_view> names, std::function<void(CsvWriter&)> write) override {
    for (TickObserver* o : to_) o->set_extra_columns(names, write);
  }
  void on_start(const Scenario& s) override {
    for (TickObserver* o : to_) o->on_start(s);
  }
  void on_tick(const TickRecord& r) override {
    for (TickObserver* o : to_) o->on_tick(r);
  }

 private:
  std::vector<TickObserver*> to_;
};

// Every column written (the required ones first); see docs/scenarios.md for their meaning. A run
// that tracks a line of sight (Scenario::track) has the tracking columns after the others.
[[nodiscard]] std::span<const std::string_view> csv_columns(bool tracking = false) noexcept;
// A row's cells as values, in csv_columns(r.tracking) order (the standard columns only): a number, an
// integer (tick, flag words, status) or a name (mode, request). What the CSV writes, before
// formatting; the Python module's time histories are made from it.
using CellValue = std::variant<double, std::uint64_t, const char*>;
void row_cells(const TickRecord& r, std::span<CellValue> out);
// 1-based column number of `name` (for gnuplot); 0 if there is no such column.
[[nodiscard]] int csv_column(std::string_view name, bool tracking = false) noexcept;

// Upper bounds of a row's length (newline included) in a run of `ticks` ticks, and of the
// whole CSV of a scenario (header and run.ticks + 1 rows): each column at its widest (a
// number as "-1.234567890e-308", the flag words at every bit set, the longest name).
[[nodiscard]] std::uint64_t csv_row_bytes_bound(std::uint64_t ticks, bool tracking = false);
[[nodiscard]] std::uint64_t csv_size_bound(const Scenario& s);

// The gyro_sil CSV as an observer: the header at the start, one row per tick. Throws
// RunError when a write fails or the CSV passes max_bytes.
class CsvObserver final : public TickObserver {
 public:
  explicit CsvObserver(CsvWriter& csv, std::uint64_t max_bytes = std::numeric_limits<std::uint64_t>::max()) noexcept
      : csv_(csv), max_bytes_(max_bytes) {}
  void set_extra_columns(std::span<const std::string_view> names, std::function<void(CsvWriter&)> write) override;
  void on_start(const Scenario& s) override;
  void on_tick(const TickRecord& r) override;

 private:
  CsvWriter& csv_;
  std::uint64_t max_bytes_;
  std::span<const std::string_view> extra_names_;
  std::function<void(CsvWriter&)> write_extras_;
};

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
  std::uint64_t rows{0};             // ticks observed (CSV rows after the header)
  GyroMode final_mode{GyroMode::kIdle};
  std::uint32_t flags_seen{0};       // OR of the component's flags over the run
  std::array<std::uint32_t, kComponentFlagCount> counters{};  // the component's, at the end
  std::uint64_t refused_steps{0};    // component.step() calls that returned neither kOk nor kInputIgnored
  std::uint64_t nonfinite_values{0}; // NaN or infinite numbers among the CSV's columns
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

// Runs the scenario, showing every tick to `observer`. Throws ScenarioError (configuration
// refused) or RunError.
RunSummary run_scenario(const Scenario& s, TickObserver& observer, const RunOptions& options = {});
// The same, writing the header and every row to `csv` (a CsvObserver).
RunSummary run_scenario(const Scenario& s, CsvWriter& csv, const RunOptions& options = {});

// Names of the flags set in `flags`, separated by '|' ("" for none).
[[nodiscard]] std::string flag_names(std::uint32_t flags);

}  // namespace gyro::sil
