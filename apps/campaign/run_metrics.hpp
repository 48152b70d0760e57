// The metrics of one run, computed tick by tick from the SIL loop (a TickObserver) and the
// run's summary. Definitions (docs/campaigns.md):
//   fault start      the earliest start tick of the scenario's faults (none: no fault)
//   healthy residual the largest |residual| (either axis) over ticks in mode free before the
//                    fault start
//   residual persistence  over the same ticks, the largest count (in ticks) a persistence
//                    monitor as the component's (gyro/persistence.hpp) reaches when fed
//                    |residual| > half the residual limit: how long the residual of a healthy
//                    gyro dwells near the limit, for choosing residual_persistence_ticks
//   envelope         the largest true cone over the run, and the largest change of a true
//                    gimbal angle in one tick before the fault start (for max_pickoff_step_rad)
//   safe mode        the first tick in mode fault; detected = at or after the fault start;
//                    latency = safe mode - fault start when detected; before the fault start
//                    (or in a run without a fault): a false alarm, unless the gimbal had met
//                    its stop by then (safe mode after stop contact: counted on its own)
//   safe-mode cause  the monitors that latched it, from the flags of its first tick:
//                    residual, pickoff (readings unusable), spin, input, torquer
//   slew-rate error  the mean of (true precession rate - guidance's slew command) over the
//                    window's ticks in mode free, the larger magnitude of the two axes (the
//                    mean: a slew's accuracy, not the nutation riding on it)
//   pointing error   the largest |the component's estimate of the gimbal angles - the true
//                    angles| (either axis) over ticks in mode free within the window
//   tracking         in a run that tracks a line of sight (guidance.track), the largest true
//                    pointing error (the stub's spin axis to the LOS) and the largest error of
//                    the component's spin-axis inertial rate (its LOS-rate estimate) over the
//                    window's ticks in mode free
//   final mode, flag counters (the component's, at the end), the first stop contact and
//   the time at the gimbal stop
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "campaign_file.hpp"
#include "gyro/persistence.hpp"
#include "scenario.hpp"
#include "sil_runner.hpp"

namespace gyro::campaign {

struct RunMetrics {
  std::optional<double> max_residual_healthy_rad;
  std::optional<double> half_limit_persistence_ticks;
  double max_cone_rad{0};
  std::optional<double> max_gimbal_step_rad;
  std::optional<double> safe_mode_s;
  std::string safe_mode_cause;       // "residual", "pickoff+spin", ...; empty without safe mode
  std::optional<bool> detected;      // runs with a fault only
  bool false_alarm{false};
  bool safe_mode_after_stop{false};  // before the fault (or without one), after stop contact
  std::optional<double> latency_s;
  std::optional<double> slew_rate_error_rad_s;
  std::optional<double> max_pointing_error_rad;
  std::optional<double> max_track_pointing_error_rad;
  std::optional<double> max_los_rate_error_rad_s;
  GyroMode final_mode{GyroMode::kIdle};
  std::array<std::uint32_t, kComponentFlagCount> counters{};
  std::optional<double> stop_contact_s;  // the first tick on the stop
  double time_at_stop_s{0};
};

// The monitors that latched safe mode, named from the component's flags of that tick
// ("residual", "pickoff", "spin", "input", "torquer", joined by '+'; "other" for none).
[[nodiscard]] std::string safe_mode_cause(std::uint32_t flags);

class MetricsObserver final : public sil::TickObserver {
 public:
  MetricsObserver(const sil::Scenario& s, const MetricSet& m);
  void on_tick(const sil::TickRecord& r) override;
  // The metrics, once the run is over.
  [[nodiscard]] RunMetrics finish(const sil::RunSummary& summary) const;

 private:
  struct TickWindow {
    std::uint64_t from{0}, to{0};
  };
  [[nodiscard]] static std::optional<TickWindow> ticks_of(const std::optional<Window>& w, double tick_s);
  static void raise(std::optional<double>& m, double v) { m = m ? std::max(*m, v) : v; }

  double tick_s_;
  std::optional<std::uint64_t> fault_tick_;
  std::optional<TickWindow> slew_window_, pointing_window_, tracking_window_;
  std::optional<std::uint64_t> safe_tick_;
  std::optional<std::uint64_t> stop_tick_;
  Eigen::Vector2d slew_error_sum_{Eigen::Vector2d::Zero()};
  std::uint64_t slew_ticks_{0};
  std::uint64_t stop_ticks_{0};
  double half_limit_rad_;
  PersistenceMonitor half_limit_monitor_{};
  std::optional<Eigen::Vector2d> last_gimbal_rad_;
  RunMetrics m_;
};

}  // namespace gyro::campaign
