// The flight component against the SIL stub on the target: the closed loop of
// sil_scenarios.hpp (caging, uncaging, slewing, holding, a torquer lost mid-slew), checked
// against the host's run (sil_golden.hpp). Modes and flags must match exactly; angles, rates
// and torques within a tolerance for the FPU's fused multiply-adds and newlib's libm.
#include <cmath>

#include "sil_golden.hpp"
#include "sil_scenarios.hpp"
#include "tinytest.hpp"

namespace {

// Absolute tolerances: gimbal angles in rad (the loop's scale is 0.1 rad), rates in rad/s
// (scale 0.3), torques in N m (scale 0.03).
template <typename T>
struct SilTolerance;
template <>
struct SilTolerance<float> {
  static constexpr double kAngle = 2e-4, kRate = 2e-3, kTorque = 2e-4;
};
template <>
struct SilTolerance<double> {
  static constexpr double kAngle = 1e-9, kRate = 1e-8, kTorque = 1e-9;
};

double dev(double a, double b) { return std::fabs(a - b); }

template <typename T>
void check_sil_against_host(const char* type_name) {
  using Tol = SilTolerance<T>;
  constexpr int kCount = static_cast<int>(sizeof(gyro_fw::SilGolden<T>::kSamples) / sizeof(gyro_fw::SilSample<T>));
  const gyro_fw::SilSample<T>* golden = gyro_fw::SilGolden<T>::kSamples;
  int next = 0;
  double worst_angle = 0, worst_rate = 0, worst_torque = 0;
  for (int i = 0; i < gyro_fw::kSilScenarioCount; ++i) {
    const gyro::Status st =
        gyro_fw::run_sil_scenario<T>(gyro_fw::kSilScenarios[i], i, [&](const gyro_fw::SilSample<T>& s) {
          TT_CHECK(next < kCount);
          if (next >= kCount) return;
          const gyro_fw::SilSample<T>& g = golden[next++];
          TT_CHECK(g.scenario == s.scenario && g.tick == s.tick);
          TT_CHECK(g.mode == s.mode);
          TT_CHECK(g.flags == s.flags);
          const double a = std::fmax(std::fmax(dev(double(s.gimbal_pitch), double(g.gimbal_pitch)),
                                               dev(double(s.gimbal_yaw), double(g.gimbal_yaw))),
                                     std::fmax(dev(double(s.predicted_pitch), double(g.predicted_pitch)),
                                               dev(double(s.predicted_yaw), double(g.predicted_yaw))));
          const double r = std::fmax(dev(double(s.rate_pitch), double(g.rate_pitch)),
                                     dev(double(s.rate_yaw), double(g.rate_yaw)));
          const double q = std::fmax(dev(double(s.torque_pitch), double(g.torque_pitch)),
                                     dev(double(s.torque_yaw), double(g.torque_yaw)));
          worst_angle = std::fmax(worst_angle, a);
          worst_rate = std::fmax(worst_rate, r);
          worst_torque = std::fmax(worst_torque, q);
        });
    TT_CHECK(st == gyro::Status::kOk);
  }
  TT_CHECK(next == kCount);
  TT_CHECK(worst_angle <= Tol::kAngle);
  TT_CHECK(worst_rate <= Tol::kRate);
  TT_CHECK(worst_torque <= Tol::kTorque);
  gyro_fw::Line() << "sil<" << type_name << ">: " << gyro_fw::kSilScenarioCount
                  << " closed-loop runs, largest deviation from the host: angle " << worst_angle << " rad, rate "
                  << worst_rate << " rad/s, torque " << worst_torque << " N m\n";
}

// What the scenarios are for, on the target itself: free and slewing at the end of the
// healthy run; safe mode with the torquers off after the torquer is lost.
template <typename T>
void check_sil_outcome() {
  gyro_fw::SilSample<T> last[gyro_fw::kSilScenarioCount] = {};
  for (int i = 0; i < gyro_fw::kSilScenarioCount; ++i) {
    TT_CHECK((gyro_fw::run_sil_scenario<T>(gyro_fw::kSilScenarios[i], i,
                                           [&](const gyro_fw::SilSample<T>& s) { last[i] = s; })) ==
             gyro::Status::kOk);
  }
  TT_CHECK(last[0].mode == static_cast<int>(gyro::GyroMode::kFree));
  TT_CHECK((last[0].flags & gyro::kResidualFault) == 0u);
  TT_CHECK(last[1].mode == static_cast<int>(gyro::GyroMode::kFault));
  TT_CHECK(last[1].torque_pitch == T(0) && last[1].torque_yaw == T(0));
}

}  // namespace

TT_TEST(sil_float_matches_host) { check_sil_against_host<float>("float"); }
TT_TEST(sil_double_matches_host) { check_sil_against_host<double>("double"); }
TT_TEST(sil_float_outcome) { check_sil_outcome<float>(); }
TT_TEST(sil_double_outcome) { check_sil_outcome<double>(); }
