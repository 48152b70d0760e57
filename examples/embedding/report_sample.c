/* The report's sample run (its driver GYMAIN, every error fixed) from C: GyroModel in storage
 * of the program's own, no heap. Prints the gimbal angles after the last step.
 *   cc -std=c99 report_sample.c $(pkg-config --cflags --libs gyro) -o report_sample */
#include <stdio.h>
#include <string.h>

#include <gyro/gyro.h>

/* c = a b, 3x3 matrices row by row */
static void multiply(const double a[9], const double b[9], double c[9]) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      c[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
    }
  }
}

int main(void) {
  gyro_report_sample sample;
  gyro_model_config config;
  gyro_model_d_storage storage;
  gyro_model_d* model = gyro_model_d_init(&storage, sizeof storage);
  gyro_refusal refusal;
  if (gyro_abi_version() != GYRO_ABI_VERSION || gyro_report_sample_get(&sample, &config) != GYRO_OK) return 1;
  if (gyro_model_d_configure(model, &config, &refusal) != GYRO_OK) {
    char why[256];
    gyro_refusal_text(&refusal, why, sizeof why);
    fprintf(stderr, "configuration refused: %s\n", why);
    return 1;
  }
  /* The body turns about its own pitch axis, then its yaw axis, every step. */
  gyro_step_input_d in = {.dt_s = sample.initg_step_s, .spin_hz = sample.spin_hz};
  double pitch[9], yaw[9], turn[9], body[9];
  gyro_frame_rotation_d(1, sample.body_rate_rad_s[0] * in.dt_s, pitch);
  gyro_frame_rotation_d(2, sample.body_rate_rad_s[1] * in.dt_s, yaw);
  multiply(yaw, pitch, turn);
  gyro_frame_rotation_d(1, 0.0, in.R_earth_to_body); /* level: the identity */
  int status = gyro_model_d_uncage(model, in.R_earth_to_body, sample.body_rate_rad_s, NULL);
  int steps = 0;
  while (status == GYRO_OK && steps < sample.steps && gyro_model_d_flags(model) == 0) {
    multiply(turn, in.R_earth_to_body, body); /* the body's attitude at the step's end */
    memcpy(in.R_earth_to_body, body, sizeof body);
    status = gyro_model_d_step_slew(model, &in, sample.slew_rate_rad_s);
    steps += status == GYRO_OK;
  }
  if (status != GYRO_OK) {
    fprintf(stderr, "step %d refused: %s\n", steps + 1, gyro_status_text(status));
    return 1;
  }
  double gimbal[2];
  gyro_model_d_gimbal(model, gimbal);
  printf("report sample: %d steps, gimbal pitch %.12e yaw %.12e rad\n", steps, gimbal[0], gimbal[1]);
  return 0;
}
