// The estimator: the report's exact-dynamics model (GyroModel, torquers and bearings on the gimbal
// axes) advanced over the elapsed ticks with the torque the torquers held, its prediction of the
// gimbal angles compared with the accepted reading, and a fraction of that residual fed back into
// its attitude (turned at the start of the next step, with its rotation). It starts by the report's
// uncaging at the measured gimbal angles; a step it cannot take (a refused input), or one that
// predicts the gimbal beyond the pickoffs' range, stops it until the next good reading starts it
// again.
#pragma once

#include <cstdint>

#include "gyro/component_config.hpp"
#include "gyro/component_types.hpp"
#include "gyro/guidance_gate.hpp"
#include "gyro/gyro_model.hpp"
#include "gyro/inline_step.hpp"

namespace gyro {

struct Prediction {
  bool compared{false};    // a reading was compared: the residual is this tick's
  std::uint32_t flags{0};  // kSmallAngleExceeded, kGimbalLimit
};

template <typename T>
class Estimator {
 public:
  // The configured rotor, its limits and the feedback gain; the estimator stops.
  [[nodiscard]] ConfigCheck configure(const GyroComponentConfig<T>& c) noexcept {
    GyroModel<T> m;
    const ConfigCheck check = m.configure(estimator_config(c));
    if (!check.ok()) return check;
    model_ = m;
    ready_ = false;
    tick_s_ = c.tick_s;
    gain_ = c.estimator_gain;
    range_rad_ = c.pickoff_range_rad;
    return check;
  }

  // The report's uncaging at the measured gimbal angles, rates from the body; on a refusal nothing
  // changes.
  [[nodiscard]] bool start(const Navigation<T>& nav, const Vector2<T>& gimbal_rad) noexcept {
    const Status s = model_.uncage_on_gimbal(nav.attitude().matrix(), nav.body_rate_rad_s(), gimbal_rad);
    if (s != Status::kOk) return false;
    ready_ = true;
    predicted_ = model_.gimbal_rad();
    residual_.setZero();  // a residual from before the start means nothing to it
    return true;
  }

  // Leaving safe mode: the estimator starts again from the next good reading.
  void restart() noexcept { ready_ = false; }

  // What the torquers hold from now on (the torque written, or the last one when a write failed).
  void hold_torque(const Vector2<T>& torque) noexcept { torque_held_ = torque; }

  // Advances over `elapsed` ticks at `spin_hz`, the body turning to the navigation's attitude at
  // its mean rate; compares with `gimbal_rad` when `measurable`. Not yet started, it starts when
  // measurable and predicts nothing this tick.
  [[nodiscard]] GYRO_INLINE_STEP Prediction predict(std::uint64_t elapsed, T spin_hz, const Navigation<T>& nav,
                                                    bool measurable, const Vector2<T>& gimbal_rad) noexcept {
    Prediction p;
    if (!ready_) {
      if (measurable) (void)start(nav, gimbal_rad);
      residual_.setZero();
      return p;
    }
    GyroStepInput<T>& s = step_input_;  // a member: its unread attitude is not rebuilt each tick
    s.dt_s = tick_s_ * static_cast<T>(elapsed);
    s.spin_hz = spin_hz;
    s.body_rate_rad_s = nav.mean_body_rate_rad_s();
    if (model_.step_torque(s, nav.attitude(), torque_held_) != Status::kOk) {
      ready_ = false;  // re-initialised from the next good reading
      return p;
    }
    predicted_ = model_.gimbal_rad();
    if (model_.small_angle_exceeded()) p.flags |= kSmallAngleExceeded;
    if (model_.gimbal_limit_exceeded()) p.flags |= kGimbalLimit;
    // Beyond the pickoffs' range the gimbal would be past its stop: the navigation and the model
    // disagree (an attitude jump), and towards gimbal lock the model no longer holds.
    if (!(predicted_.cwiseAbs().maxCoeff() <= range_rad_)) {
      ready_ = false;  // re-initialised from the next good reading
      p.flags |= kGimbalLimit;
      return p;
    }
    if (!measurable) return p;
    residual_ = gimbal_rad - predicted_;
    (void)model_.correct_gimbal_angles_at_next_step(Vector2<T>(gain_ * residual_));
    p.compared = true;
    return p;
  }

  // The gimbal frame the torque law and the stop protection resolve on: the estimator's, else the
  // pickoffs' (before the estimator runs, and without navigation, when the prediction holds the
  // last good body attitude while the body turns on). The pickoffs' is built here and kept, so
  // that either is handed out by reference: a copy a tick costs the tick 16 instructions.
  [[nodiscard]] const GimbalFrame<T>& frame(bool nav_ok, const Vector2<T>& gimbal_rad) noexcept {
    if (ready_ && nav_ok) return model_.gimbal_frame_now();
    pickoff_frame_ = gimbal_frame_at(gimbal_rad);
    return pickoff_frame_;
  }

  // The inner gimbal's roll rate about the spin axis, 0 until the estimator runs.
  [[nodiscard]] T inner_gimbal_roll_rad_s() const noexcept { return ready_ ? model_.inner_gimbal_roll_rad_s() : T(0); }

  [[nodiscard]] bool ready() const noexcept { return ready_; }
  [[nodiscard]] const Vector2<T>& predicted_rad() const noexcept { return predicted_; }  // before correction
  [[nodiscard]] const Vector2<T>& residual_rad() const noexcept { return residual_; }    // measured - predicted
  [[nodiscard]] const Vector2<T>& torque_held() const noexcept { return torque_held_; }
  [[nodiscard]] const GyroModel<T>& model() const noexcept { return model_; }

 private:
  GyroModel<T> model_{};
  bool ready_{false};
  T tick_s_{};
  T gain_{};
  T range_rad_{};  // the pickoffs' range: the gimbal is never beyond it
  GyroStepInput<T> step_input_{};  // its attitude is passed checked
  Vector2<T> predicted_{Vector2<T>::Zero()};
  Vector2<T> residual_{Vector2<T>::Zero()};
  Vector2<T> torque_held_{Vector2<T>::Zero()};
  GimbalFrame<T> pickoff_frame_{};  // the frame at the pickoffs' angles, when last asked for
};

}  // namespace gyro
