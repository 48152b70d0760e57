/* gyro.h from C (built as C99 with -pedantic): every part of the C API called as a C program
 * calls it, against facts worked out here rather than by the library: the report's steady
 * precession (eq 11), the layout of matrices (the gimbal angles from ROTEG and ROTEB), and the
 * statuses, refusals and names the header promises. Prints each failed check; exit status 1 if
 * any failed. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gyro/gyro.h"

static int failures = 0;
#define CHECK(cond)                                                   \
  do {                                                                \
    if (!(cond)) {                                                    \
      fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                     \
    }                                                                 \
  } while (0)

/* Each enumerator's name, lower-cased without GYRO_, is the name gyro_status_name gives. */
static void check_status_name(int status, const char* enumerator) {
  char expected[64];
  size_t i;
  const char* name = enumerator + strlen("GYRO_");
  for (i = 0; name[i] != '\0' && i + 1 < sizeof expected; ++i) {
    expected[i] = (char)(name[i] >= 'A' && name[i] <= 'Z' ? name[i] - 'A' + 'a' : name[i]);
  }
  expected[i] = '\0';
  if (strcmp(gyro_status_name(status), expected) != 0) {
    fprintf(stderr, "status %d: name %s, expected %s\n", status, gyro_status_name(status), expected);
    ++failures;
  }
  CHECK(gyro_status_text(status) != NULL && strlen(gyro_status_text(status)) > 0);
}
#define CHECK_STATUS_NAME(s) check_status_name(s, #s)

static void test_version_and_statuses(void) {
  char version[32];
  CHECK(gyro_abi_version() == GYRO_ABI_VERSION);
  sprintf(version, "%d.%d.%d", GYRO_VERSION_MAJOR, GYRO_VERSION_MINOR, GYRO_VERSION_PATCH);
  CHECK(strcmp(gyro_version_string(), version) == 0);
  CHECK_STATUS_NAME(GYRO_OK);
  CHECK_STATUS_NAME(GYRO_NON_FINITE_INPUT);
  CHECK_STATUS_NAME(GYRO_NON_POSITIVE_INERTIA);
  CHECK_STATUS_NAME(GYRO_NEGATIVE_FRICTION);
  CHECK_STATUS_NAME(GYRO_NEGATIVE_ANGULAR_MOMENTUM);
  CHECK_STATUS_NAME(GYRO_NON_POSITIVE_STEP);
  CHECK_STATUS_NAME(GYRO_NO_STEADY_STATE);
  CHECK_STATUS_NAME(GYRO_OUT_OF_RANGE);
  CHECK_STATUS_NAME(GYRO_NUMERICAL_OVERFLOW);
  CHECK_STATUS_NAME(GYRO_NOT_CONFIGURED);
  CHECK_STATUS_NAME(GYRO_INVALID_ROTATION);
  CHECK_STATUS_NAME(GYRO_WRONG_MODE);
  CHECK_STATUS_NAME(GYRO_INPUT_IGNORED);
  CHECK_STATUS_NAME(GYRO_NULL_ARGUMENT);
  CHECK_STATUS_NAME(GYRO_STORAGE_TOO_SMALL);
  CHECK_STATUS_NAME(GYRO_UNKNOWN_FIELD);
  CHECK_STATUS_NAME(GYRO_SCENARIO_ERROR);
  CHECK_STATUS_NAME(GYRO_RUN_ERROR);
  CHECK_STATUS_NAME(GYRO_OUT_OF_MEMORY);
  CHECK_STATUS_NAME(GYRO_INTERNAL_ERROR);
  CHECK(strcmp(gyro_status_name(13), "unknown") == 0);
}

/* The report's gyro (J1 2.25, J2 2, f 5, 100 Hz on J0 3) under a constant torque settles to the
 * steady precession of eq 11: theta' = (f T1 - H T2)/(f^2 + H^2), psi' = (H T1 + f T2)/(f^2 + H^2). */
static void test_exact_step(void) {
  gyro_rotor_parameters_d p;
  gyro_transition_d tr;
  gyro_rotor_modes_d modes;
  const double torque[2] = {40.0, -25.0};
  double state[4] = {0.0, 0.0, 0.3, -0.2}, batch[3 * 4], h, den;
  const double per_row[3 * 2] = {40.0, -25.0, 1.0, 2.0, HUGE_VAL, 0.0};
  uint8_t statuses[3];
  int k, i;
  p.pitch_inertia = 2.25;
  p.yaw_inertia = 2.0;
  p.friction = 5.0;
  p.angular_momentum = gyro_angular_momentum_d(100.0, 3.0);
  h = p.angular_momentum;
  CHECK(fabs(h - 2.0 * 3.14159265358979323846 * 100.0 * 3.0) < 1e-9);
  CHECK(gyro_make_transition_d(&p, 1e-3, &tr) == GYRO_OK);
  CHECK(tr.coefficients[16] == 1e-3);
  for (k = 0; k < 20000; ++k) CHECK(gyro_advance_d(&tr, torque, state) == GYRO_OK);
  den = p.friction * p.friction + h * h;
  CHECK(fabs(state[2] - (p.friction * torque[0] - h * torque[1]) / den) < 1e-12);
  CHECK(fabs(state[3] - (h * torque[0] + p.friction * torque[1]) / den) < 1e-12);

  /* A batch row by row is the single step; a non-finite torque refuses its row only. */
  for (i = 0; i < 3; ++i) {
    batch[4 * i + 0] = 0.1 * i;
    batch[4 * i + 1] = -0.1;
    batch[4 * i + 2] = 0.2;
    batch[4 * i + 3] = 0.3 * i;
  }
  CHECK(gyro_advance_batch_d(&tr, batch, 3, per_row, 2, statuses) == GYRO_NON_FINITE_INPUT);
  CHECK(statuses[0] == GYRO_OK && statuses[1] == GYRO_OK && statuses[2] == GYRO_NON_FINITE_INPUT);
  CHECK(batch[8] == 0.2 && batch[9] == -0.1 && batch[10] == 0.2 && batch[11] == 0.6);
  state[0] = 0.1, state[1] = -0.1, state[2] = 0.2, state[3] = 0.3;
  CHECK(gyro_advance_d(&tr, per_row + 2, state) == GYRO_OK);
  CHECK(memcmp(state, batch + 4, sizeof state) == 0);
  CHECK(gyro_advance_batch_d(&tr, batch, 3, torque, 1, NULL) == GYRO_OUT_OF_RANGE);

  CHECK(gyro_make_transition_d(&p, 0.0, &tr) == GYRO_NON_POSITIVE_STEP);
  CHECK(gyro_make_transition_d(NULL, 1e-3, &tr) == GYRO_NULL_ARGUMENT);
  CHECK(gyro_compute_modes_d(&p, &modes) == GYRO_OK);
  CHECK(modes.regime == 0 && fabs(modes.nutation_hz - 141.42) < 0.01);
  CHECK(gyro_initg_step_d(&p, &h) == GYRO_OK && h == 1.0 / floor(20.0 * modes.nutation_hz));
  p.friction = 40.0; /* overdamped: no nutation, no step */
  p.angular_momentum = 0.0;
  CHECK(gyro_initg_step_d(&p, &h) == GYRO_OUT_OF_RANGE && h == 1.0 / floor(20.0 * modes.nutation_hz));
  p.friction = -1.0;
  CHECK(gyro_make_transition_d(&p, 1e-3, &tr) == GYRO_NEGATIVE_FRICTION);
}

static void test_configuration_by_name(void) {
  gyro_model_config c;
  gyro_model_d_storage storage;
  gyro_model_d* m = gyro_model_d_init(&storage, sizeof storage);
  gyro_refusal r;
  double v[3] = {0, 0, 0};
  char text[256];
  size_t i, n;
  CHECK(m != NULL);
  CHECK(gyro_config_size(GYRO_MODEL_CONFIG) == sizeof c && gyro_config_size(GYRO_PLANT_CONFIG) == sizeof(gyro_plant_config));
  CHECK(gyro_config_init(GYRO_MODEL_CONFIG, &c) == GYRO_OK);
  CHECK(c.small_angle_limit_rad == 0.01 && c.gravity == 9.80665 && c.pitch_inertia == 0.0);
  CHECK(strcmp(gyro_config_choice(GYRO_MODEL_CONFIG, &c, "torquer_axes"), "gyro") == 0);
  n = gyro_config_field_count(GYRO_MODEL_CONFIG);
  CHECK(n == 11 + 12 + 1);
  for (i = 0; i < n; ++i) CHECK(gyro_config_field_name(GYRO_MODEL_CONFIG, i) != NULL);
  CHECK(gyro_config_field_name(GYRO_MODEL_CONFIG, n) == NULL);

  /* Set by name lands in the member of that name, nested ones too. */
  v[0] = 0.25;
  CHECK(gyro_config_set(GYRO_MODEL_CONFIG, &c, "errors.yaw.coulomb_friction_rad_s", v, 1) == GYRO_OK);
  CHECK(c.errors.yaw.coulomb_friction_rad_s == 0.25);
  CHECK(gyro_config_set(GYRO_MODEL_CONFIG, &c, "errors.yaw.coulomb", v, 1) == GYRO_UNKNOWN_FIELD);
  CHECK(gyro_config_set(GYRO_MODEL_CONFIG, &c, "pitch_inertia", v, 3) == GYRO_OUT_OF_RANGE);
  CHECK(gyro_config_set_choice(GYRO_MODEL_CONFIG, &c, "torquer_axes", "gimbal") == GYRO_OK && c.torquer_axes == 1);
  CHECK(gyro_config_set_choice(GYRO_MODEL_CONFIG, &c, "torquer_axes", "body") == GYRO_UNKNOWN_FIELD);
  CHECK(strcmp(gyro_config_choice_name(GYRO_MODEL_CONFIG, "torquer_axes", 0), "gyro") == 0);
  CHECK(gyro_config_choice_name(GYRO_MODEL_CONFIG, "torquer_axes", 2) == NULL);
  CHECK(gyro_config_get(GYRO_MODEL_CONFIG, &c, "gravity", v, 1) == GYRO_OK && v[0] == 9.80665);

  /* The plant's vectors are three numbers. */
  CHECK(gyro_config_init(GYRO_PLANT_CONFIG, &(gyro_plant_config){0}) == GYRO_OK);
  CHECK(gyro_config_field_length(GYRO_PLANT_CONFIG, "inner_gimbal_inertia") == 3);
  CHECK(gyro_config_field_length(GYRO_PLANT_CONFIG, "spin_drive") == 0);

  /* A refusal names the field, the value and the bound; the model stays unconfigured. */
  CHECK(gyro_model_d_configure(m, &c, &r) == GYRO_NON_POSITIVE_INERTIA);
  CHECK(strcmp(r.field, "pitch_inertia") == 0 && r.value == 0.0);
  CHECK(gyro_refusal_text(&r, text, sizeof text) > 0 && strstr(text, "pitch_inertia = 0") == text);
  CHECK(gyro_model_d_uncage(m, (const double[9]){1, 0, 0, 0, 1, 0, 0, 0, 1}, v, NULL) == GYRO_NOT_CONFIGURED);
  c.pitch_inertia = c.yaw_inertia = c.spin_inertia = 1.0;
  c.gimbal_cone_limit_rad = c.max_pitch_rate_rad_s = c.max_yaw_rate_rad_s = 0.5;
  c.errors.pitch.coulomb_friction_rad_s = -0.5;
  CHECK(gyro_model_d_configure(m, &c, &r) == GYRO_OUT_OF_RANGE);
  CHECK(strcmp(r.field, "errors.pitch.coulomb_friction_rad_s") == 0 && r.relation == 1);
  c.errors.pitch.coulomb_friction_rad_s = 0.0;
  c.torquer_axes = 7;
  CHECK(gyro_model_d_configure(m, &c, &r) == GYRO_OUT_OF_RANGE && strcmp(r.field, "torquer_axes") == 0);
  c.torquer_axes = 0;
  CHECK(gyro_model_d_configure(m, &c, &r) == GYRO_OK && r.field == NULL);
}

static void multiply(const double a[9], const double b[9], double c[9]) {
  int i, j, k;
  for (i = 0; i < 3; ++i) {
    for (j = 0; j < 3; ++j) {
      c[3 * i + j] = 0.0;
      for (k = 0; k < 3; ++k) c[3 * i + j] += a[3 * i + k] * b[3 * k + j];
    }
  }
}

/* The report's sample in double and float (storage of gyro.h's sizes): no flag over its 801
 * steps, the two precisions together, and the gimbal angles those of the spin axis (row 1 of
 * ROTEG) seen from the body (ROTEB): pitch = atan2(-z, |(x, y)|), yaw = atan2(y, x). */
static void test_report_sample(void) {
  gyro_report_sample s;
  gyro_model_config config;
  gyro_model_d_storage sd;
  gyro_model_f_storage sf;
  gyro_model_d* md;
  gyro_model_f* mf;
  gyro_step_input_d in;
  gyro_step_input_f inf;
  double ty[9], tz[9], turn[9], r[9], g[2], roteg[9], axis[3];
  float slew_f[2], rate_f[2], gf[2];
  int k, i, ok = 1;
  CHECK(gyro_model_d_storage_size() <= sizeof sd && gyro_model_f_storage_size() <= sizeof sf);
  CHECK(gyro_model_d_init(&sd, gyro_model_d_storage_size() - 1) == NULL);
  md = gyro_model_d_init(&sd, sizeof sd);
  mf = gyro_model_f_init(&sf, sizeof sf);
  CHECK(gyro_report_sample_get(&s, &config) == GYRO_OK && s.steps == 801);
  CHECK(gyro_model_d_configure(md, &config, NULL) == GYRO_OK && gyro_model_f_configure(mf, &config, NULL) == GYRO_OK);
  memset(&in, 0, sizeof in);
  memset(&inf, 0, sizeof inf);
  in.dt_s = s.initg_step_s;
  in.spin_hz = s.spin_hz;
  inf.dt_s = (float)in.dt_s;
  inf.spin_hz = (float)in.spin_hz;
  CHECK(gyro_frame_rotation_d(1, s.body_rate_rad_s[0] * in.dt_s, ty) == GYRO_OK);
  CHECK(gyro_frame_rotation_d(2, s.body_rate_rad_s[1] * in.dt_s, tz) == GYRO_OK);
  CHECK(gyro_frame_rotation_d(0, 0.1, ty) == GYRO_OUT_OF_RANGE);
  multiply(tz, ty, turn);
  for (i = 0; i < 9; ++i) in.R_earth_to_body[i] = i % 4 == 0 ? 1.0 : 0.0;
  for (i = 0; i < 9; ++i) inf.R_earth_to_body[i] = (float)in.R_earth_to_body[i];
  for (i = 0; i < 2; ++i) rate_f[i] = (float)s.body_rate_rad_s[i], slew_f[i] = (float)s.slew_rate_rad_s[i];
  CHECK(gyro_model_d_uncage(md, in.R_earth_to_body, s.body_rate_rad_s, NULL) == GYRO_OK);
  CHECK(gyro_model_f_uncage(mf, inf.R_earth_to_body, rate_f, NULL) == GYRO_OK);
  for (k = 0; k < s.steps; ++k) {
    multiply(turn, in.R_earth_to_body, r);
    memcpy(in.R_earth_to_body, r, sizeof r);
    for (i = 0; i < 9; ++i) inf.R_earth_to_body[i] = (float)r[i];
    ok = ok && gyro_model_d_step_slew(md, &in, s.slew_rate_rad_s) == GYRO_OK;
    ok = ok && gyro_model_f_step_slew(mf, &inf, slew_f) == GYRO_OK;
    ok = ok && gyro_model_d_flags(md) == 0 && gyro_model_f_flags(mf) == 0;
  }
  CHECK(ok);
  gyro_model_d_gimbal(md, g);
  gyro_model_f_gimbal(mf, gf);
  CHECK(fabs(g[0] - gf[0]) < 2e-5 && fabs(g[1] - gf[1]) < 2e-5);
  CHECK(g[0] < -0.1 && g[1] < -0.02); /* the body turned past a gyro slewed the other way */
  gyro_model_d_R_earth_to_gyro(md, roteg);
  for (i = 0; i < 3; ++i) axis[i] = in.R_earth_to_body[3 * i] * roteg[0] + in.R_earth_to_body[3 * i + 1] * roteg[1] +
                                    in.R_earth_to_body[3 * i + 2] * roteg[2];
  CHECK(fabs(g[0] - atan2(-axis[2], sqrt(axis[0] * axis[0] + axis[1] * axis[1]))) < 1e-12);
  CHECK(fabs(g[1] - atan2(axis[1], axis[0])) < 1e-12);
  CHECK(fabs(gyro_model_d_cone(md) - acos(axis[0])) < 1e-9);

  /* A body matrix that is no rotation is refused, and the nearest rotation repairs a drift. */
  in.R_earth_to_body[0] *= 1.0 + 1e-6;
  CHECK(gyro_model_d_step_slew(md, &in, s.slew_rate_rad_s) == GYRO_INVALID_ROTATION);
  CHECK(gyro_nearest_rotation_d(in.R_earth_to_body, in.R_earth_to_body) == GYRO_OK);
  CHECK(gyro_model_d_step_slew(md, &in, s.slew_rate_rad_s) == GYRO_OK);
  in.R_earth_to_body[0] = -in.R_earth_to_body[0];
  CHECK(gyro_nearest_rotation_d(in.R_earth_to_body, r) == GYRO_INVALID_ROTATION);
}

#ifdef GYRO_C_TEST_HOST_PART
/* The host part: a plant on the heap, and a SIL run of a scenario given as text. */
static void test_host_part(const char* scenario_path) {
  gyro_plant_d* p = gyro_plant_d_create();
  gyro_plant_config c;
  gyro_refusal r;
  gyro_sil_result* run = NULL;
  gyro_sil_error e;
  gyro_sil_options o = {"float", 40, 0};
  gyro_sil_summary sum;
  const double torque[2] = {0.0, 0.0};
  double angle[2], rate[2];
  size_t col;
  CHECK(p != NULL);
  CHECK(gyro_config_init(GYRO_PLANT_CONFIG, &c) == GYRO_OK);
  CHECK(gyro_plant_d_configure(p, &c, 1e-3, &r) != GYRO_OK && r.field != NULL);
  CHECK(gyro_plant_d_step(p, torque, NULL, NULL) == GYRO_NOT_CONFIGURED);
  gyro_plant_d_gimbal(p, angle, rate);
  CHECK(angle[0] == 0.0 && rate[1] == 0.0);
  gyro_plant_d_destroy(p);
  gyro_plant_d_destroy(NULL);

  CHECK(gyro_sil_run_text("{", NULL, &run, &e) == GYRO_SCENARIO_ERROR && run == NULL && strlen(e.message) > 0);
  CHECK(gyro_sil_run_file(scenario_path, &o, &run, &e) == GYRO_OK && run != NULL);
  CHECK(gyro_sil_rows(run) == 41);
  CHECK(strcmp(gyro_sil_column_name(run, 0), "t") == 0 && gyro_sil_column_kind(run, 0) == GYRO_SIL_NUMBERS);
  CHECK(strcmp(gyro_sil_column_name(run, 1), "mode") == 0 && gyro_sil_column_kind(run, 1) == GYRO_SIL_NAMES);
  CHECK(gyro_sil_name(run, 1, 0) != NULL && gyro_sil_numbers(run, 1) == NULL);
  CHECK(gyro_sil_column_name(run, gyro_sil_columns(run)) == NULL);
  for (col = 0; col < gyro_sil_columns(run); ++col) {
    if (strcmp(gyro_sil_column_name(run, col), "flags") == 0) CHECK(gyro_sil_integers(run, col) != NULL);
  }
  gyro_sil_get_summary(run, &sum);
  CHECK(sum.ticks == 40 && sum.rows == 41 && strcmp(sum.precision, "float") == 0 && sum.nonfinite_values == 0);
  CHECK(gyro_component_flag_name(0) != NULL && gyro_component_flag_name(gyro_component_flag_count()) == NULL);
  gyro_sil_free(run);
  o.max_output_bytes = 100;
  CHECK(gyro_sil_run_file(scenario_path, &o, &run, &e) == GYRO_RUN_ERROR && strcmp(e.field, "max_output_bytes") == 0);
  o.precision = "half";
  CHECK(gyro_sil_run_file(scenario_path, &o, &run, &e) == GYRO_OUT_OF_RANGE && strcmp(e.field, "precision") == 0);
}
#endif

/* The flight part everywhere (cross targets under emulation too); the host part with a
 * scenario file given (a host build with the SIL runs). */
int main(int argc, char** argv) {
  test_version_and_statuses();
  test_exact_step();
  test_configuration_by_name();
  test_report_sample();
#ifdef GYRO_C_TEST_HOST_PART
  if (argc != 2) {
    fprintf(stderr, "usage: %s SCENARIO.json\n", argv[0]);
    return 2;
  }
  test_host_part(argv[1]);
#else
  (void)argc;
  (void)argv;
#endif
  if (failures != 0) {
    fprintf(stderr, "%d checks failed\n", failures);
    return 1;
  }
  printf("all checks passed\n");
  return 0;
}
