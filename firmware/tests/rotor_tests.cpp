// The exact rotor dynamics on the target: thousands of steps in every damping regime,
// checked against the host's results (rotor_golden.hpp), bit-identical on a rerun, and
// refusing bad input without touching the state.
#include <cmath>
#include <cstring>
#include <limits>

#include "gyro/rotor_transition.hpp"
#include "rotor_golden.hpp"
#include "rotor_scenarios.hpp"
#include "tinytest.hpp"

namespace {

// Largest allowed deviation from the host, relative to the scale of the quantity (the
// largest |angle| or |rate| of the scenario). The target's FPU fuses multiply-adds (the
// host's generator does not) and newlib's exp/sin/cos differ from glibc's in the last bit;
// the damped dynamics keep those differences from growing.
template <typename T>
constexpr double kTolerance = 0.0;
template <>
constexpr double kTolerance<float> = 5e-5;
template <>
constexpr double kTolerance<double> = 1e-12;

template <typename T>
double abs_d(T v) {
  return std::fabs(static_cast<double>(v));
}

// Runs every scenario and compares each checkpoint with the host's golden sample.
template <typename T>
void check_against_host(const char* type_name) {
  constexpr int kCount =
      static_cast<int>(sizeof(gyro_fw::RotorGolden<T>::kSamples) / sizeof(gyro_fw::RotorSample<T>));
  const gyro_fw::RotorSample<T>* golden = gyro_fw::RotorGolden<T>::kSamples;
  int next = 0;
  long steps = 0;
  double worst = 0.0;
  const char* worst_name = "-";
  for (int i = 0; i < gyro_fw::kRotorScenarioCount; ++i) {
    double angle_scale = 0.0, rate_scale = 0.0;
    for (int k = 0; k < kCount; ++k) {
      if (golden[k].scenario != i) continue;
      angle_scale = std::fmax(angle_scale, std::fmax(abs_d(golden[k].angle_pitch), abs_d(golden[k].angle_yaw)));
      rate_scale = std::fmax(rate_scale, std::fmax(abs_d(golden[k].rate_pitch), abs_d(golden[k].rate_yaw)));
    }
    TT_CHECK(angle_scale > 0.0 && rate_scale > 0.0);
    double scenario_worst = 0.0;
    const gyro::Status st = gyro_fw::run_rotor_scenario<T>(
        gyro_fw::kRotorScenarios[i], i, [&](const gyro_fw::RotorSample<T>& s) {
          TT_CHECK(next < kCount);
          if (next >= kCount) return;
          const gyro_fw::RotorSample<T>& g = golden[next++];
          TT_CHECK(g.scenario == s.scenario && g.step == s.step);
          const double dev[4] = {abs_d(s.angle_pitch - g.angle_pitch) / angle_scale,
                                 abs_d(s.angle_yaw - g.angle_yaw) / angle_scale,
                                 abs_d(s.rate_pitch - g.rate_pitch) / rate_scale,
                                 abs_d(s.rate_yaw - g.rate_yaw) / rate_scale};
          for (double d : dev) scenario_worst = std::fmax(scenario_worst, d);
        });
    TT_CHECK(st == gyro::Status::kOk);
    steps += gyro_fw::kRotorScenarios[i].steps;
    if (scenario_worst > worst) {
      worst = scenario_worst;
      worst_name = gyro_fw::kRotorScenarios[i].name;
    }
    TT_CHECK(scenario_worst <= kTolerance<T>);
    if (!(scenario_worst <= kTolerance<T>)) {
      gyro_fw::Line() << "  " << gyro_fw::kRotorScenarios[i].name << " <" << type_name
                      << ">: deviation " << scenario_worst << '\n';
    }
  }
  TT_CHECK(next == kCount);
  gyro_fw::Line() << "rotor<" << type_name << ">: " << gyro_fw::kRotorScenarioCount
                  << " scenarios, " << steps << " steps, largest deviation from the host "
                  << worst << " (" << worst_name << "; tolerance " << kTolerance<T> << ")\n";
}

// The same scenario run twice gives the same bits (no uninitialised state, no drift).
template <typename T>
void check_bit_identical_rerun() {
  for (int i = 0; i < gyro_fw::kRotorScenarioCount; ++i) {
    gyro_fw::RotorSample<T> first{}, second{};
    const gyro_fw::RotorScenario& s = gyro_fw::kRotorScenarios[i];
    TT_CHECK((gyro_fw::run_rotor_scenario<T>(s, i, [&](const gyro_fw::RotorSample<T>& r) { first = r; })) ==
             gyro::Status::kOk);
    TT_CHECK((gyro_fw::run_rotor_scenario<T>(s, i, [&](const gyro_fw::RotorSample<T>& r) { second = r; })) ==
             gyro::Status::kOk);
    TT_CHECK(first.step == s.steps);
    TT_CHECK(std::memcmp(&first, &second, sizeof first) == 0);
  }
}

// The regimes the scenarios are meant to cover are the ones the target computes.
template <typename T>
void check_regimes() {
  const gyro::DampingRegime expected[] = {
      gyro::DampingRegime::kUnderdamped, gyro::DampingRegime::kUnderdamped,
      gyro::DampingRegime::kCritical,    gyro::DampingRegime::kOverdamped,
      gyro::DampingRegime::kFree,        gyro::DampingRegime::kUnderdamped};
  static_assert(sizeof expected / sizeof expected[0] == gyro_fw::kRotorScenarioCount);
  for (int i = 0; i < gyro_fw::kRotorScenarioCount; ++i) {
    const gyro_fw::RotorScenario& s = gyro_fw::kRotorScenarios[i];
    const gyro::RotorParameters<T> prm{static_cast<T>(s.pitch_inertia), static_cast<T>(s.yaw_inertia),
                                       static_cast<T>(s.friction), static_cast<T>(s.angular_momentum)};
    gyro::RotorModes<T> modes;
    TT_CHECK(gyro::compute_modes(prm, modes) == gyro::Status::kOk);
    TT_CHECK(modes.regime == expected[i]);
  }
}

// Non-finite torque is refused and the state is left exactly as it was.
template <typename T>
void check_rejects_non_finite() {
  const gyro::RotorParameters<T> prm{static_cast<T>(2.25), static_cast<T>(2.0), static_cast<T>(5.0),
                                     static_cast<T>(gyro_fw::kReportH)};
  gyro::RotorTransition<T> tr;
  TT_CHECK(gyro::make_transition(prm, static_cast<T>(0.01), tr) == gyro::Status::kOk);
  gyro::RotorState<T> state;
  state.rate_rad_s = gyro::Vector2<T>(static_cast<T>(0.01), static_cast<T>(-0.02));
  const gyro::RotorState<T> before = state;
  const T nan = std::numeric_limits<T>::quiet_NaN();
  TT_CHECK(gyro::advance(tr, gyro::Vector2<T>(nan, T(0)), state) == gyro::Status::kNonFiniteInput);
  TT_CHECK(std::memcmp(&before, &state, sizeof state) == 0);
  TT_CHECK(gyro::make_transition(prm, T(0), tr) == gyro::Status::kNonPositiveStep);
}

}  // namespace

TT_TEST(rotor_float_matches_host) { check_against_host<float>("float"); }
TT_TEST(rotor_float_rerun_is_bit_identical) { check_bit_identical_rerun<float>(); }
TT_TEST(rotor_float_regimes) { check_regimes<float>(); }
TT_TEST(rotor_float_rejects_non_finite_torque) { check_rejects_non_finite<float>(); }

// Double precision where the FPU has it (Cortex-M7 FPv5-D16); the M4F's FPU is single
// precision only, and its flight code runs in float.
#if !defined(__ARM_FP) || (__ARM_FP & 0x8)
TT_TEST(rotor_double_matches_host) { check_against_host<double>("double"); }
TT_TEST(rotor_double_rerun_is_bit_identical) { check_bit_identical_rerun<double>(); }
TT_TEST(rotor_double_regimes) { check_regimes<double>(); }
TT_TEST(rotor_double_rejects_non_finite_torque) { check_rejects_non_finite<double>(); }
#endif
