// The component's full tick (gyro/gyro_model.hpp: exact dynamics, attitude update, gimbal
// angles, flags): the report's sample gyro at a 1 kHz tick, the body held level, slewing at
// the report's commanded rates with the command reversed every second, so the gimbal angles
// sweep back and forth inside the gimbal cone for as many ticks as are run.
#pragma once

#if __has_include("gyro/gyro_model.hpp")
#define GYRO_BENCH_HAVE_MODEL 1
#include "gyro/gyro_model.hpp"
#include "gyro/report_sample.hpp"
#include "bench_problem.hpp"

namespace gyro::bench {

template <typename T>
class ModelWorkload {
 public:
  ModelWorkload() {
    if (!model_.configure(ReportSample<T>::config()).ok()) fail("GyroModel::configure");
    if (model_.uncage(Matrix3<T>::Identity(), Vector2<T>::Zero()) != Status::kOk) {
      fail("GyroModel::uncage");
    }
    in_.dt_s = T(1e-3);
    in_.spin_hz = ReportSample<T>::kSpinHz;
    const Case c = find_case("report");
    torque_[0] = Vector2<T>(static_cast<T>(c.torque(0)), static_cast<T>(c.torque(1)));
    torque_[1] = -torque_[0];
  }

  // One tick; the torque reverses every 1000 ticks.
  [[nodiscard]] Status step() noexcept {
    const Vector2<T>& torque = torque_[(tick_ / 1000) & 1];
    ++tick_;
    return model_.step_torque(in_, torque);
  }

  [[nodiscard]] T output() const noexcept { return model_.gimbal_pitch_rad(); }

 private:
  GyroModel<T> model_;
  GyroStepInput<T> in_;
  Vector2<T> torque_[2]{Vector2<T>::Zero(), Vector2<T>::Zero()};
  unsigned long tick_{0};
};

}  // namespace gyro::bench
#endif
