// The rotor scenarios that the firmware runs on the target and the host generator
// (firmware/golden/gen_rotor_golden.cpp) runs on the host to produce rotor_golden.hpp:
// one code path, so the only differences are the compiler, the FPU (fused multiply-add)
// and the C library's exp/sin/cos.
#pragma once

#include "gyro/rotor_transition.hpp"

namespace gyro_fw {

struct RotorScenario {
  const char* name;
  double pitch_inertia;     // J1
  double yaw_inertia;       // J2
  double friction;          // f
  double angular_momentum;  // H (at the start, for a spin-down)
  double dt_s;
  int steps;
  double torque_amplitude;  // T1 square wave of this amplitude; T2 = 0.4 T1
  int torque_half_period;   // steps
  double rate0_pitch;       // initial w1, rad/s
  double rate0_yaw;         // initial w2, rad/s
  bool spin_down;           // H falls linearly to 0: a new transition every step
};

// H of the report's sample gyro: 2*pi*100 Hz*3 slug*ft^2.
inline constexpr double kReportH = 1884.9555921538758;

inline constexpr RotorScenario kRotorScenarios[] = {
    // The report's sample gyro at a 100 Hz guidance rate: 141 Hz nutation, beta*dt = 8.9.
    {"report_100hz", 2.25, 2.0, 5.0, kReportH, 0.01, 4000, 0.5, 230, 0.01, -0.02, false},
    // The same gyro at 10 kHz: |eigenvalue*dt| < 1, the series path.
    {"report_10khz", 2.25, 2.0, 5.0, kReportH, 1e-4, 3000, 0.5, 700, 0.01, -0.02, false},
    // beta^2 = 0 exactly (J1 != J2, H = 0.75 f): where the report's closed form divides by 0.
    {"critical", 1.0, 4.0, 4.0, 3.0, 0.05, 3000, 0.1, 370, 0.01, 0.0, false},
    // beta^2 < 0: two real decay rates, no nutation.
    {"overdamped", 1.0, 4.0, 4.0, 1.0, 0.05, 3000, 0.1, 410, 0.01, 0.0, false},
    // f = H = 0: the torque accelerates the gimbals freely.
    {"free", 1.0, 1.0, 0.0, 0.0, 1e-3, 2000, 1e-3, 2000, 1e-3, 0.0, false},
    // The report's gyro spinning down to H = 0 over 40 s: under-, critically and
    // overdamped on the way, with make_transition every step.
    {"spin_down", 2.25, 2.0, 5.0, kReportH, 0.01, 4000, 0.5, 330, 0.01, -0.02, true},
};
inline constexpr int kRotorScenarioCount =
    static_cast<int>(sizeof(kRotorScenarios) / sizeof(kRotorScenarios[0]));

// The state is sampled every kCheckpointEvery steps and at the last step.
inline constexpr int kCheckpointEvery = 500;

template <typename T>
struct RotorSample {
  int scenario;
  int step;
  T angle_pitch, angle_yaw, rate_pitch, rate_yaw;
};

// Runs scenario `s` (number `index`) in scalar type T, calling sink(RotorSample<T>) at
// every checkpoint. Returns the first status that is not kOk (and stops there), else kOk.
template <typename T, typename Sink>
[[nodiscard]] gyro::Status run_rotor_scenario(const RotorScenario& s, int index,
                                              Sink&& sink) noexcept {
  gyro::RotorParameters<T> prm{static_cast<T>(s.pitch_inertia), static_cast<T>(s.yaw_inertia),
                               static_cast<T>(s.friction), static_cast<T>(s.angular_momentum)};
  const T h0 = prm.angular_momentum;
  const T dt = static_cast<T>(s.dt_s);
  const T amplitude = static_cast<T>(s.torque_amplitude);
  gyro::RotorState<T> state;
  state.rate_rad_s = gyro::Vector2<T>(static_cast<T>(s.rate0_pitch), static_cast<T>(s.rate0_yaw));
  gyro::RotorTransition<T> tr;
  if (!s.spin_down) {
    const gyro::Status st = gyro::make_transition(prm, dt, tr);
    if (st != gyro::Status::kOk) return st;
  }
  for (int k = 1; k <= s.steps; ++k) {
    const T t1 = ((k - 1) / s.torque_half_period) % 2 == 0 ? amplitude : -amplitude;
    const gyro::Vector2<T> torque(t1, static_cast<T>(0.4) * t1);
    gyro::Status st;
    if (s.spin_down) {
      prm.angular_momentum = h0 * (static_cast<T>(s.steps - k) / static_cast<T>(s.steps));
      st = gyro::propagate(prm, dt, torque, state);
    } else {
      st = gyro::advance(tr, torque, state);
    }
    if (st != gyro::Status::kOk) return st;
    if (k % kCheckpointEvery == 0 || k == s.steps) {
      sink(RotorSample<T>{index, k, state.angle_rad(0), state.angle_rad(1), state.rate_rad_s(0),
                          state.rate_rad_s(1)});
    }
  }
  return gyro::Status::kOk;
}

}  // namespace gyro_fw
