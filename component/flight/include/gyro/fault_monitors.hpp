// The fault monitors: one persistence monitor (gyro/persistence.hpp) per fault condition, and
// whether any has lasted long enough to latch safe mode.
#pragma once

#include <cstdint>

#include "gyro/component_types.hpp"
#include "gyro/persistence.hpp"

namespace gyro {

// This tick's fault conditions.
struct FaultConditions {
  bool reading_unusable{false};  // no pickoff reading accepted
  bool spin_low{false};
  bool input_unusable{false};  // a command or tick count the tick could not use
};

struct FaultVerdict {
  bool fault{false};       // some condition has persisted: safe mode
  std::uint32_t flags{0};  // kInputFault
};

class FaultMonitors {
 public:
  // The residual test, each tick the estimator compared a reading: kResidualFault once
  // |residual| has been over its limit for long enough. In safe mode the residual is not
  // monitored: its fill is dropped (the estimator restarts when the gyro is caged again).
  template <typename T, typename Config>
  [[nodiscard]] std::uint32_t test_residual(const Vector2<T>& residual, bool safe_mode, const Config& c) noexcept {
    if (safe_mode) {
      residual_.reset();
      return 0u;
    }
    const bool over = residual.cwiseAbs().maxCoeff() > c.residual_limit_rad;
    return residual_.update(over, c.residual_persistence_ticks) ? static_cast<std::uint32_t>(kResidualFault) : 0u;
  }
  // Leaving safe mode: the residual's fill from before the fault is gone.
  void reset_residual() noexcept { residual_.reset(); }

  // The last torquer write, fed to the next tick's monitor.
  void torquer_written(bool ok) noexcept { torquer_failed_ = !ok; }

  template <typename Config>
  [[nodiscard]] FaultVerdict update(const FaultConditions& now, const Config& c) noexcept {
    FaultVerdict v;
    const bool reading = reading_.update(now.reading_unusable, c.invalid_persistence_ticks);
    const bool spin = spin_.update(now.spin_low, c.spin_low_persistence_ticks);
    const bool torquer = torquer_.update(torquer_failed_, c.torquer_fail_persistence_ticks);
    const bool input = input_.update(now.input_unusable, c.input_persistence_ticks);
    if (input) v.flags |= kInputFault;
    v.fault = reading || spin || torquer || input || residual_.tripped(c.residual_persistence_ticks);
    return v;
  }

 private:
  PersistenceMonitor reading_{};
  PersistenceMonitor residual_{};
  PersistenceMonitor spin_{};
  PersistenceMonitor torquer_{};
  PersistenceMonitor input_{};
  bool torquer_failed_{false};
};

}  // namespace gyro
