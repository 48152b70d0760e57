// Runs the report's sample (GYMAIN) with the listing's errors fixed and prints its figures;
// with a path argument, also writes the time history as CSV.
#include <cstdio>

#include "gyro/report_sample.hpp"

int main(int argc, char** argv) {
  using S = gyro::ReportSample<double>;
  gyro::RotorModes<double> modes;
  if (gyro::compute_modes(S::rotor(), modes) != gyro::Status::kOk) return 1;
  const double dt = S::initg_step();
  gyro::Vector2<double> torque = gyro::torque_for_rate_frictionless(
      S::rotor().angular_momentum, gyro::Vector2<double>(-S::kDegPerSecond, 0.013));
  gyro::Vector2<double> w_ss = gyro::Vector2<double>::Zero();
  if (gyro::steady_precession_rate(S::rotor(), torque, w_ss) != gyro::Status::kOk) return 1;

  std::FILE* csv = (argc > 1) ? std::fopen(argv[1], "w") : nullptr;
  if (argc > 1 && csv == nullptr) {
    std::fprintf(stderr, "cannot write %s\n", argv[1]);
    return 1;
  }
  if (csv) std::fprintf(csv, "step,t,gimbal_pitch,gimbal_yaw,theta_rate,psi_rate,nutation_pitch,nutation_yaw\n");
  const gyro::SampleRunSummary sum = gyro::run_report_sample<double>(
      dt, S::kSteps, [&](int k, double t, const gyro::GyroModel<double>& g, const auto&) {
        if (csv) {
          std::fprintf(csv, "%d,%.9f,%.12e,%.12e,%.12e,%.12e,%.6e,%.6e\n", k, t, g.gimbal_pitch_rad(),
                       g.gimbal_yaw_rad(), g.rate_rad_s()(0), g.rate_rad_s()(1),
                       g.nutation_amplitude_rad()(0), g.nutation_amplitude_rad()(1));
        }
      });
  if (csv) std::fclose(csv);

  std::printf("gyro nutation frequency  %.5f Hz (alpha %.4f 1/s, beta %.3f rad/s)\n", modes.nutation_hz,
              modes.alpha_1_s, modes.beta_rad_s);
  std::printf("time step                %.8f s (1/%.0f)\n", dt, 1.0 / dt);
  std::printf("steady precession        theta' %.7f rad/s, psi' %.7f rad/s (friction-coupled)\n",
              w_ss(0), w_ss(1));
  std::printf("steps completed          %d of %d (%s)\n", sum.steps_completed, S::kSteps,
              sum.status != gyro::Status::kOk ? gyro::to_string(sum.status)
              : sum.stop_flags != 0u        ? "stopped on a flag"
                                            : "no flag raised");
  return (sum.status == gyro::Status::kOk && sum.steps_completed == S::kSteps) ? 0 : 2;
}
