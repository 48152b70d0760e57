#include "run_metrics.hpp"

#include <algorithm>
#include <cmath>

namespace gyro::campaign {

std::string safe_mode_cause(std::uint32_t flags) {
  struct Monitor {
    std::uint32_t flags;
    const char* name;
  };
  constexpr Monitor kMonitors[] = {{kResidualFault, "residual"},
                                   {kPickoffInvalid | kPickoffStale | kPickoffJump, "pickoff"},
                                   {kSpinLow, "spin"},
                                   {kInputFault, "input"},
                                   {kTorquerWriteFailed, "torquer"}};
  std::string out;
  for (const Monitor& m : kMonitors) {
    if ((flags & m.flags) != 0u) out += (out.empty() ? "" : "+") + std::string(m.name);
  }
  return out.empty() ? "other" : out;
}

MetricsObserver::MetricsObserver(const sil::Scenario& s, const MetricSet& m)
    : tick_s_(s.run.tick_s),
      slew_window_(ticks_of(m.slew_rate_error, s.run.tick_s)),
      pointing_window_(ticks_of(m.pointing_error, s.run.tick_s)),
      tracking_window_(ticks_of(m.tracking, s.run.tick_s)),
      half_limit_rad_(0.5 * s.component.residual_limit_rad) {
  for (std::size_t i = 0; i < s.fault_count; ++i) {
    const std::uint64_t start = s.gyro.faults[i].start_tick;
    fault_tick_ = fault_tick_ ? std::min(*fault_tick_, start) : start;
  }
}

std::optional<MetricsObserver::TickWindow> MetricsObserver::ticks_of(const std::optional<Window>& w, double tick_s) {
  if (!w) return std::nullopt;
  return TickWindow{static_cast<std::uint64_t>(std::llround(w->from_s / tick_s)),
                    static_cast<std::uint64_t>(std::llround(w->to_s / tick_s))};
}

void MetricsObserver::on_tick(const sil::TickRecord& r) {
  const bool free = r.mode == GyroMode::kFree;
  const bool healthy = !fault_tick_ || r.tick < *fault_tick_;
  if (free && healthy) {
    const double residual = r.residual_rad.cwiseAbs().maxCoeff();
    raise(m_.max_residual_healthy_rad, residual);
    // The cap (2 N) is out of reach: 2^31 ticks is longer than any run.
    (void)half_limit_monitor_.update(residual > half_limit_rad_, 1u << 30);
    raise(m_.half_limit_persistence_ticks, static_cast<double>(half_limit_monitor_.fill()) / 2.0);
  }
  m_.max_cone_rad = std::max(m_.max_cone_rad, r.cone_true_rad);
  if (healthy && last_gimbal_rad_) raise(m_.max_gimbal_step_rad, (r.gimbal_true_rad - *last_gimbal_rad_).cwiseAbs().maxCoeff());
  last_gimbal_rad_ = r.gimbal_true_rad;
  if (r.at_gimbal_stop && !stop_tick_) stop_tick_ = r.tick;
  if (r.mode == GyroMode::kFault && !safe_tick_) {
    safe_tick_ = r.tick;
    m_.safe_mode_cause = safe_mode_cause(r.flags);
  }
  const auto within = [&](const std::optional<TickWindow>& w) { return w && r.tick >= w->from && r.tick <= w->to; };
  if (free && within(slew_window_)) {
    slew_error_sum_ += r.rate_true_rad_s - r.slew_cmd_rad_s;
    ++slew_ticks_;
  }
  if (free && within(pointing_window_)) {
    raise(m_.max_pointing_error_rad, (r.gimbal_predicted_rad - r.gimbal_true_rad).cwiseAbs().maxCoeff());
  }
  if (free && r.tracking && within(tracking_window_)) {
    raise(m_.max_track_pointing_error_rad, r.pointing_error_true_rad);
    raise(m_.max_los_rate_error_rad_s, r.los_rate_error_rad_s);
  }
  if (r.at_gimbal_stop) ++stop_ticks_;
}

RunMetrics MetricsObserver::finish(const sil::RunSummary& summary) const {
  RunMetrics out = m_;
  if (safe_tick_) out.safe_mode_s = static_cast<double>(*safe_tick_) * tick_s_;
  if (fault_tick_) {
    out.detected = safe_tick_ && *safe_tick_ >= *fault_tick_;
    if (*out.detected) out.latency_s = static_cast<double>(*safe_tick_ - *fault_tick_) * tick_s_;
  }
  if (slew_ticks_ > 0) {
    out.slew_rate_error_rad_s = (slew_error_sum_ / static_cast<double>(slew_ticks_)).cwiseAbs().maxCoeff();
  }
  const bool before_fault = safe_tick_ && (!fault_tick_ || *safe_tick_ < *fault_tick_);
  const bool after_stop = stop_tick_ && safe_tick_ && *stop_tick_ <= *safe_tick_;
  out.false_alarm = before_fault && !after_stop;
  out.safe_mode_after_stop = before_fault && after_stop;
  if (stop_tick_) out.stop_contact_s = static_cast<double>(*stop_tick_) * tick_s_;
  out.final_mode = summary.final_mode;
  out.counters = summary.counters;
  out.time_at_stop_s = static_cast<double>(stop_ticks_) * tick_s_;
  return out;
}

}  // namespace gyro::campaign
