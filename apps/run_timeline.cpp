#include "run_timeline.hpp"

#include <algorithm>

namespace gyro::sil {

void TimelineObserver::cover(std::vector<TimeSpan>& spans, double from, double to) const {
  if (!spans.empty() && from <= spans.back().to_s + resolution_s_) {
    spans.back().to_s = std::max(spans.back().to_s, to);
  } else {
    spans.push_back({from, to});
  }
}

void TimelineObserver::on_tick(const TickRecord& r) {
  const double from = r.t_s, to = r.t_s + tick_s_;
  t_.end_s = std::max(t_.end_s, to);
  // Modes are never joined across a change: a mode band shows every mode it went through,
  // however short (a span below the resolution is drawn at its true width).
  if (t_.modes.empty() || t_.modes.back().mode != r.mode) {
    t_.modes.push_back({r.mode, {from, to}});
  } else {
    t_.modes.back().span.to_s = to;
  }
  for (int b = 0; b < kComponentFlagCount; ++b) {
    if ((r.flags & (1u << static_cast<unsigned>(b))) != 0u) cover(t_.flags[static_cast<std::size_t>(b)], from, to);
  }
  for (int k = 1; k < kFaultKindCount; ++k) {
    if ((r.active_faults & fault_bit(static_cast<FaultKind>(k))) != 0u) cover(t_.faults[static_cast<std::size_t>(k)], from, to);
  }
  if (r.at_gimbal_stop) {
    cover(t_.at_stop, from, to);
    if (!t_.stop_contact_s) t_.stop_contact_s = from;
  }
  if (r.request == ModeRequest::kUncage && !t_.uncage_s) t_.uncage_s = from;
  if (r.mode == GyroMode::kFault && !t_.latched_s) t_.latched_s = from;
}

double timeline_resolution_s(const Scenario& s) noexcept {
  return std::max(s.run.tick_s, static_cast<double>(s.run.ticks + 1) * s.run.tick_s / 2000.0);
}

}  // namespace gyro::sil
