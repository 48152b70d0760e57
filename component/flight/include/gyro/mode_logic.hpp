// The mode logic: a pure function of the mode, this tick's request and conditions.
//
// A request lasts one tick: one that cannot be carried out is refused (kRequestRefused) and
// dropped, never kept for later. A fault condition that has persisted latches safe mode from
// any mode; only a cage request leaves it, and only once no fault condition holds.
#pragma once

#include <cstdint>

#include "gyro/component_types.hpp"

namespace gyro {

struct ModeConditions {
  ModeRequest request{ModeRequest::kNone};
  bool measurable{false};  // a reading accepted and navigation usable this tick
  bool fault{false};       // a fault condition has persisted (gyro/fault_monitors.hpp)
  std::uint32_t settle_ticks{0};        // ticks uncaging so far
  std::uint32_t uncage_settle_ticks{0};  // ticks before the gyro is free
};

// What the component is to do: the next mode, and the estimator's part in it.
enum class EstimatorAction : std::uint8_t {
  kKeep,
  kStart,    // uncaging: the report's uncaging of the estimator at the measured gimbal angles;
             // if it fails, the request is refused and the gyro stays caged
  kRestart,  // leaving safe mode: the estimator restarts from the next good reading
};

struct ModeTransition {
  GyroMode mode{GyroMode::kIdle};
  std::uint32_t settle_ticks{0};
  EstimatorAction estimator{EstimatorAction::kKeep};
  std::uint32_t flags{0};  // kRequestRefused
};

[[nodiscard]] inline ModeTransition next_mode(GyroMode mode, const ModeConditions& c) noexcept {
  ModeTransition t{mode, c.settle_ticks, EstimatorAction::kKeep, 0u};
  if (c.fault) {
    t.mode = GyroMode::kFault;
    if (c.request != ModeRequest::kNone) t.flags |= kRequestRefused;
    return t;
  }
  switch (mode) {
    case GyroMode::kCaged:
      if (c.request == ModeRequest::kUncage) {
        // The report's uncaging: rates from the body, attitude from the body plus the measured
        // gimbal offset. (The torque shaper keeps the cage loop's torques from leaving a
        // nutation this start cannot know.)
        if (!c.measurable) {
          t.flags |= kRequestRefused;
        } else {
          t.mode = GyroMode::kUncaging;
          t.settle_ticks = 0;
          t.estimator = EstimatorAction::kStart;
        }
      }
      break;
    case GyroMode::kUncaging:
      if (c.request == ModeRequest::kCage) {
        t.mode = GyroMode::kCaged;
      } else {
        t.settle_ticks = c.settle_ticks + 1u;
        if (t.settle_ticks >= c.uncage_settle_ticks) t.mode = GyroMode::kFree;
      }
      break;
    case GyroMode::kFree:
      if (c.request == ModeRequest::kCage) t.mode = GyroMode::kCaged;
      break;
    case GyroMode::kFault:
      if (c.request == ModeRequest::kUncage) {
        t.flags |= kRequestRefused;  // safe mode is left by caging only
      } else if (c.request == ModeRequest::kCage) {
        t.mode = GyroMode::kCaged;
        t.estimator = EstimatorAction::kRestart;
      }
      break;
    case GyroMode::kIdle:
      break;
  }
  return t;
}

}  // namespace gyro
