// The report's sample run (its driver GYMAIN, every error fixed) from C++: GyroModel itself,
// header-only. Prints the gimbal angles after the last step.
//   find_package(gyro CONFIG REQUIRED)  target_link_libraries(app PRIVATE gyro::examples)
#include <cstdio>

#include <gyro/gyro_model.hpp>
#include <gyro/report_sample.hpp>

int main() {
  using Sample = gyro::ReportSample<double>;
  gyro::GyroModel<double> model;
  const gyro::ConfigCheck check = model.configure(Sample::config());
  if (!check.ok()) {
    char why[256];
    gyro::format_refusal(check, "configuration refused: ", why, sizeof why);
    std::fprintf(stderr, "%s\n", why);
    return 1;
  }
  gyro::GyroStepInput<double> in;
  in.dt_s = Sample::initg_step();
  in.spin_hz = Sample::kSpinHz;
  // The body turns about its own pitch axis, then its yaw axis, every step.
  const gyro::Matrix3<double> turn = gyro::frame_rotation_z(Sample::kBodyYawRate * in.dt_s) *
                                     gyro::frame_rotation_y(Sample::kBodyPitchRate * in.dt_s);
  gyro::Status status =
      model.uncage(in.R_earth_to_body, gyro::Vector2<double>(Sample::kBodyPitchRate, Sample::kBodyYawRate));
  int steps = 0;
  while (status == gyro::Status::kOk && steps < Sample::kSteps && model.flags() == 0) {
    in.R_earth_to_body = turn * in.R_earth_to_body;  // the body's attitude at the step's end
    status = model.step_slew(in, Sample::slew_command());
    steps += status == gyro::Status::kOk ? 1 : 0;
  }
  if (status != gyro::Status::kOk) {
    std::fprintf(stderr, "step %d refused: %s\n", steps + 1, gyro::to_string(status));
    return 1;
  }
  std::printf("report sample: %d steps, gimbal pitch %.12e yaw %.12e rad\n", steps, model.gimbal_pitch_rad(),
              model.gimbal_yaw_rad());
  return 0;
}
