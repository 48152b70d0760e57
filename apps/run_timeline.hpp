// What happened in a run, on its time axis, for the plot that explains it: the mode, each
// flag the component raised, the gimbal at its stop and each fault the stub injected, as
// spans; and the events a reader looks for first (the uncage request, the fault latched, the
// first stop contact), as instants. Spans less than `resolution_s` apart join: a flag that
// flickers every tick is one bar at the plot's resolution, and a row holds at most about
// run length / resolution bars whatever the run's length.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "sil_runner.hpp"

namespace gyro::sil {

struct TimeSpan {
  double from_s{0}, to_s{0};
};

struct ModeSpan {
  GyroMode mode{GyroMode::kIdle};
  TimeSpan span{};
};

struct RunTimeline {
  double end_s{0};  // the end of the last tick
  std::vector<ModeSpan> modes;
  std::array<std::vector<TimeSpan>, kComponentFlagCount> flags{};  // by flag bit
  std::vector<TimeSpan> at_stop;                                   // the true gimbal on its stop
  std::array<std::vector<TimeSpan>, kFaultKindCount> faults{};     // by FaultKind, as injected
  std::optional<double> uncage_s;        // the first uncage request
  std::optional<double> latched_s;       // the first tick in mode fault
  std::optional<double> stop_contact_s;  // the first tick on the stop
};

// Builds the timeline of a run tick by tick. A tick at t covers [t, t + tick_s).
class TimelineObserver final : public TickObserver {
 public:
  TimelineObserver(double tick_s, double resolution_s) noexcept : tick_s_(tick_s), resolution_s_(resolution_s) {}
  void on_tick(const TickRecord& r) override;
  [[nodiscard]] const RunTimeline& timeline() const noexcept { return t_; }

 private:
  // Extends the last span of `spans` to cover [from, to), or starts a new one.
  void cover(std::vector<TimeSpan>& spans, double from, double to) const;

  double tick_s_;
  double resolution_s_;
  RunTimeline t_;
};

// The resolution a run's plot needs: a two-thousandth of its length, at least a tick.
[[nodiscard]] double timeline_resolution_s(const Scenario& s) noexcept;

}  // namespace gyro::sil
