// The closed loop the firmware runs on the target and the host generator
// (firmware/golden/gen_sil_golden.cpp) runs on the host to produce sil_golden.hpp: the flight
// component against the SIL stub, one code path on both sides. A small SI seeker gyro at
// 2 kHz: caged, uncaged, slewing, holding; the second scenario loses a torquer mid-slew.
#pragma once

#include <cstdint>

#include "gyro/gyro_component.hpp"
#include "gyro/seeker_example.hpp"
#include "gyro/sil_loop.hpp"
#include "gyro/simulated_gyro.hpp"

namespace gyro_fw {

struct SilScenario {
  const char* name;
  int ticks;
  int dead_torquer_tick;  // 0 = no fault
};

inline constexpr SilScenario kSilScenarios[] = {
    {"seeker_slew", 3000, 0},
    {"seeker_dead_torquer", 3000, 1500},
};
inline constexpr int kSilScenarioCount = static_cast<int>(sizeof(kSilScenarios) / sizeof(kSilScenarios[0]));
inline constexpr int kSilCheckpointEvery = 250;

template <typename T>
struct SilSample {
  int scenario;
  int tick;
  int mode;
  std::uint32_t flags;
  T gimbal_pitch, gimbal_yaw;        // the stub's truth
  T predicted_pitch, predicted_yaw;  // the component's estimate
  T rate_pitch, rate_yaw;            // estimated precession
  T torque_pitch, torque_yaw;        // commanded
};

template <typename T>
gyro::GyroComponentConfig<T> sil_component_config() noexcept {
  gyro::GyroComponentConfig<T> c = gyro::SeekerExample<T>::component();
  c.estimator_gain = T(0.02);  // the fault campaign's choice
  return c;
}

// The example hardware with the imperfections a real one has.
template <typename T>
gyro::SimulatedGyroConfig<T> sil_stub_config(const SilScenario& s) noexcept {
  gyro::SimulatedGyroConfig<T> g = gyro::SeekerExample<T>::stub();
  g.pickoff.noise_rad = T(2e-5);
  g.pickoff.bias_rad = gyro::Vector2<T>(T(1e-4), T(-5e-5));
  g.pickoff.lag_s = T(2e-4);
  g.torquer.scale_factor = gyro::Vector2<T>(T(1.01), T(0.99));
  g.seed = 7;
  if (s.dead_torquer_tick > 0) {
    g.faults[0].kind = gyro::FaultKind::kDeadTorquer;
    g.faults[0].start_tick = static_cast<std::uint64_t>(s.dead_torquer_tick);
  }
  return g;
}

// Runs scenario `s` (number `index`) in T, calling sink(SilSample<T>) at every checkpoint.
// Returns the first status that is not kOk, else kOk. No heap: everything is on the stack.
template <typename T, typename Sink>
[[nodiscard]] gyro::Status run_sil_scenario(const SilScenario& s, int index, Sink&& sink) noexcept {
  gyro::SimulatedGyro<T> stub;
  gyro::GyroComponent<T> component(stub);
  gyro::SilLoop<T, gyro::GyroComponent<T>> loop(stub, component, gyro::StubBodyFeed::kAttitude);
  const gyro::Vector2<T> body_rate(T(0.1), T(-0.05));
  gyro::BodySample<T> body = gyro::turning_body(gyro::Matrix3<T>(gyro::Matrix3<T>::Identity()), body_rate);
  if (!stub.configure(sil_stub_config<T>(s)).ok()) return gyro::Status::kOutOfRange;
  if (!component.configure(sil_component_config<T>()).ok()) return gyro::Status::kOutOfRange;
  const gyro::SilStatus<gyro::Status> started = loop.start(body);
  if (started.stub != gyro::Status::kOk) return started.stub;
  if (started.component != gyro::Status::kOk) return started.component;
  const gyro::Matrix3<T> turn = gyro::pitch_then_yaw_turn(body_rate, T(5e-4));
  gyro::GuidanceCommand<T> command;
  for (int k = 1; k <= s.ticks; ++k) {
    body.R_earth_to_body = turn * body.R_earth_to_body;
    command.request = (k == 200) ? gyro::ModeRequest::kUncage : gyro::ModeRequest::kNone;
    command.slew_rate_cmd_rad_s = (k < 1000)   ? gyro::Vector2<T>::Zero()
                                  : (k < 2200) ? gyro::Vector2<T>(T(0.3), T(-0.2))
                                               : body_rate;
    const gyro::SilStatus<gyro::Status> st = loop.tick(static_cast<std::uint64_t>(k), body, command);
    if (st.stub != gyro::Status::kOk) return st.stub;
    if (st.component != gyro::Status::kOk) return st.component;
    if (k % kSilCheckpointEvery == 0 || k == s.ticks) {
      const gyro::GyroTelemetry<T>& tm = component.telemetry();
      sink(SilSample<T>{index, k, static_cast<int>(tm.mode), tm.flags, stub.gimbal_angle_rad()(0),
                        stub.gimbal_angle_rad()(1), tm.gimbal_predicted_rad(0), tm.gimbal_predicted_rad(1),
                        tm.precession_rate_rad_s(0), tm.precession_rate_rad_s(1), tm.torque_cmd(0),
                        tm.torque_cmd(1)});
    }
  }
  return gyro::Status::kOk;
}

}  // namespace gyro_fw
