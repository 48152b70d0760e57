/* gyro_mex: gyro's C API (gyro/gyro.h) for MATLAB and Octave, one MEX gateway in C:
 *
 *   mex gyro_mex.c -I<include> -L<lib> -lgyro             (MATLAB)
 *   mkoctfile --mex gyro_mex.c -I<include> -L<lib> -lgyro  (Octave)
 *
 * Commands (docs/embedding.md):
 *   v = gyro_mex('version')                            struct: version, abi
 *   [S, st] = gyro_mex('advance', p, dt, S, T)         the exact step of every column of S (4 x n:
 *                                                      theta, psi, theta', psi') under T (2 x 1 or
 *                                                      2 x n); p = [J1 J2 f H]; single S: in float.
 *                                                      st (uint8 1 x n) the statuses; without it a
 *                                                      refused column is an error
 *   h = gyro_mex('model_new', config, 'double'|'single')   GyroModel, kept until model_delete
 *   gyro_mex('model_uncage', h, R_earth_to_body, body_rate [, offset])
 *   gyro_mex('model_step_slew', h, dt, slew, spin_hz, R_earth_to_body [, body_accel [, body_rate]])
 *   gyro_mex('model_step_torque', h, dt, torque, spin_hz, R_earth_to_body [, body_accel [, body_rate]])
 *   s = gyro_mex('model_state', h)                     gimbal, rate, isaf_angle, ..., flags
 *   gyro_mex('model_delete', h)
 *   [cols, tm] = gyro_mex('sil_run', scenario [, 'precision', p] [, 'ticks', n]
 *                         [, 'max_output_bytes', b])   a SIL run: a struct of columns (gyro_sil's
 *                                                      CSV) and the telemetry
 *   s = gyro_mex('report_sample')                      the report's sample: config, spin, ...
 *   R = gyro_mex('frame_rotation', 'y'|'z', angle)     a body's turn about its own axis
 *   names = gyro_mex('config_fields', 'model'|'plant') the configuration's field names
 *
 * A configuration is a struct of gyro.h's field names (nested structs for "errors.pitch...");
 * choices as text. Errors are MATLAB errors with identifiers "gyro:<status name>" naming the
 * argument or the field. Matrices are MATLAB's R(i, j). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "gyro/gyro.h"
#include "mex.h"

/* ------------------------------------------------------------------------------------------- */
/* Errors */

static void fail(const char* status_name, const char* message) {
  char id[96];
  snprintf(id, sizeof id, "gyro:%s", status_name);
  mexErrMsgIdAndTxt(id, "%s", message);
}

static void check(int status, const char* what) {
  char message[600];
  if (status == GYRO_OK) return;
  snprintf(message, sizeof message, "%s: %s", what, gyro_status_text(status));
  fail(gyro_status_name(status), message);
}

static void refused(int status, const gyro_refusal* r) {
  char message[600];
  if (status == GYRO_OK) return;
  gyro_refusal_text(r, message, sizeof message);
  fail(gyro_status_name(status), message);
}

/* ------------------------------------------------------------------------------------------- */
/* Arguments */

static const mxArray* arg(int nrhs, const mxArray* prhs[], int i, const char* name) {
  char message[128];
  if (i >= nrhs) {
    snprintf(message, sizeof message, "missing argument: %s", name);
    fail("missing_argument", message);
  }
  return prhs[i];
}

static int has_arg(int nrhs, const mxArray* prhs[], int i) { return i < nrhs && !mxIsEmpty(prhs[i]); }

static void require_real(const mxArray* a, const char* name) {
  char message[160];
  if (!(mxIsDouble(a) || mxIsSingle(a)) || mxIsComplex(a) || mxIsSparse(a)) {
    snprintf(message, sizeof message, "%s: expected real numbers (double or single)", name);
    fail("wrong_type", message);
  }
}

/* The i-th number of a real array, as a double. */
static double number_at(const mxArray* a, size_t i) {
  return mxIsSingle(a) ? (double)((const float*)mxGetData(a))[i] : ((const double*)mxGetData(a))[i];
}

/* Exactly n numbers (any shape). */
static void numbers(const mxArray* a, const char* name, size_t n, double* out) {
  char message[160];
  size_t i;
  require_real(a, name);
  if (mxGetNumberOfElements(a) != n) {
    snprintf(message, sizeof message, "%s: expected %u numbers, got %u", name, (unsigned)n,
             (unsigned)mxGetNumberOfElements(a));
    fail("wrong_size", message);
  }
  for (i = 0; i < n; ++i) out[i] = number_at(a, i);
}

static double scalar(const mxArray* a, const char* name) {
  double v;
  numbers(a, name, 1, &v);
  return v;
}

/* A 3 x 3 matrix R(i, j) into gyro.h's rows. */
static void matrix3(const mxArray* a, const char* name, double rows[9]) {
  char message[160];
  double m[9];
  int i, j;
  if (mxGetM(a) != 3 || mxGetN(a) != 3) {
    snprintf(message, sizeof message, "%s: expected a 3 x 3 matrix", name);
    fail("wrong_size", message);
  }
  numbers(a, name, 9, m);
  for (i = 0; i < 3; ++i) {
    for (j = 0; j < 3; ++j) rows[3 * i + j] = m[i + 3 * j];
  }
}

static void text(const mxArray* a, const char* name, char* out, size_t n) {
  char message[160];
  if (!mxIsChar(a) || mxGetString(a, out, (mwSize)n) != 0) {
    snprintf(message, sizeof message, "%s: expected text", name);
    fail("wrong_type", message);
  }
}

/* ------------------------------------------------------------------------------------------- */
/* Results */

static mxArray* column(const double* v, size_t n, int single) {
  size_t i;
  mxArray* a = mxCreateNumericMatrix((mwSize)n, 1, single ? mxSINGLE_CLASS : mxDOUBLE_CLASS, mxREAL);
  for (i = 0; i < n; ++i) {
    if (single) {
      ((float*)mxGetData(a))[i] = (float)v[i];
    } else {
      ((double*)mxGetData(a))[i] = v[i];
    }
  }
  return a;
}

/* gyro.h's rows as R(i, j). */
static mxArray* matrix_of_rows(const double rows[9], int single) {
  double m[9];
  int i, j;
  mxArray* a;
  for (i = 0; i < 3; ++i) {
    for (j = 0; j < 3; ++j) m[i + 3 * j] = rows[3 * i + j];
  }
  a = column(m, 9, single);
  mxSetM(a, 3);
  mxSetN(a, 3);
  return a;
}

static void set(mxArray* s, const char* field, mxArray* value) {
  if (mxGetFieldNumber(s, field) < 0) mxAddField(s, field);
  mxSetField(s, 0, field, value);
}

/* ------------------------------------------------------------------------------------------- */
/* Configurations: a struct of gyro.h's field names <-> the C API's by-name fields. */

static void config_from_struct(int kind, void* config, const mxArray* s, const char* prefix) {
  char name[160], message[300], choice[64];
  double values[3];
  int i, n = mxGetNumberOfFields(s);
  if (!mxIsStruct(s) || mxGetNumberOfElements(s) != 1) fail("wrong_type", "config: expected a struct");
  for (i = 0; i < n; ++i) {
    const mxArray* v = mxGetFieldByNumber(s, 0, i);
    size_t len;
    int status;
    snprintf(name, sizeof name, "%s%s", prefix, mxGetFieldNameByNumber(s, i));
    if (v != NULL && mxIsStruct(v)) {
      strncat(name, ".", sizeof name - strlen(name) - 1);
      config_from_struct(kind, config, v, name);
      continue;
    }
    if (v != NULL && mxIsChar(v)) {
      text(v, name, choice, sizeof choice);
      status = gyro_config_set_choice(kind, config, name, choice);
      if (status != GYRO_OK) {
        snprintf(message, sizeof message, "config.%s: no such choice field, or no choice \"%s\"", name, choice);
        fail(gyro_status_name(status), message);
      }
      continue;
    }
    len = gyro_config_field_length(kind, name);
    if (len == 0 && gyro_config_choice_name(kind, name, 0) == NULL) {
      snprintf(message, sizeof message, "config.%s: unknown field", name);
      fail("unknown_field", message);
    }
    if (v == NULL) fail("wrong_type", "config: an empty field");
    snprintf(message, sizeof message, "config.%s", name);
    numbers(v, message, len == 0 ? 1 : len, values);
    check(gyro_config_set(kind, config, name, values, len == 0 ? 1 : len), message);
  }
}

/* Puts value at the dotted name below s, creating the structs on the way. */
static void put_dotted(mxArray* s, const char* dotted, mxArray* value) {
  char head[96];
  const char* dot = strchr(dotted, '.');
  mxArray* child;
  if (dot == NULL) {
    set(s, dotted, value);
    return;
  }
  snprintf(head, sizeof head, "%.*s", (int)(dot - dotted), dotted);
  child = mxGetField(s, 0, head);
  if (child == NULL) {
    child = mxCreateStructMatrix(1, 1, 0, NULL);
    set(s, head, child);
  }
  put_dotted(child, dot + 1, value);
}

static mxArray* struct_from_config(int kind, const void* config) {
  mxArray* s = mxCreateStructMatrix(1, 1, 0, NULL);
  size_t i, n = gyro_config_field_count(kind);
  double values[3];
  for (i = 0; i < n; ++i) {
    const char* name = gyro_config_field_name(kind, i);
    const size_t len = gyro_config_field_length(kind, name);
    if (len == 0) {
      put_dotted(s, name, mxCreateString(gyro_config_choice(kind, config, name)));
    } else {
      check(gyro_config_get(kind, config, name, values, len), name);
      put_dotted(s, name, column(values, len, 0));
    }
  }
  return s;
}

/* ------------------------------------------------------------------------------------------- */
/* Models kept between calls, by number. */

#define GYRO_MEX_MODELS 256
typedef struct {
  double id; /* 0: free */
  int single;
  void* model;
} Slot;
static Slot slots[GYRO_MEX_MODELS];
static double last_id = 0;

static void destroy(Slot* s) {
  if (s->single) {
    gyro_model_f_destroy((gyro_model_f*)s->model);
  } else {
    gyro_model_d_destroy((gyro_model_d*)s->model);
  }
  s->id = 0;
  s->model = NULL;
}

static void destroy_all(void) {
  int i;
  for (i = 0; i < GYRO_MEX_MODELS; ++i) {
    if (slots[i].id != 0) destroy(&slots[i]);
  }
}

static Slot* model_of(const mxArray* a) {
  const double id = scalar(a, "model");
  int i;
  for (i = 0; i < GYRO_MEX_MODELS; ++i) {
    if (id != 0 && slots[i].id == id) return &slots[i];
  }
  fail("not_configured", "model: no such model (deleted, or never made by model_new)");
  return NULL;
}

static void model_new(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  gyro_model_config config;
  gyro_refusal r;
  char precision[16] = "double";
  Slot* free_slot = NULL;
  int i, status;
  (void)nlhs;
  gyro_config_init(GYRO_MODEL_CONFIG, &config);
  config_from_struct(GYRO_MODEL_CONFIG, &config, arg(nrhs, prhs, 1, "config"), "");
  if (has_arg(nrhs, prhs, 2)) text(prhs[2], "precision", precision, sizeof precision);
  if (strcmp(precision, "double") != 0 && strcmp(precision, "single") != 0) {
    fail("out_of_range", "precision: expected 'double' or 'single'");
  }
  for (i = 0; i < GYRO_MEX_MODELS && free_slot == NULL; ++i) {
    if (slots[i].id == 0) free_slot = &slots[i];
  }
  if (free_slot == NULL) fail("out_of_memory", "model_new: 256 models at once; delete some");
  free_slot->single = strcmp(precision, "single") == 0;
  free_slot->model = free_slot->single ? (void*)gyro_model_f_create() : (void*)gyro_model_d_create();
  if (free_slot->model == NULL) fail("out_of_memory", "model_new: out of memory");
  status = free_slot->single ? gyro_model_f_configure((gyro_model_f*)free_slot->model, &config, &r)
                             : gyro_model_d_configure((gyro_model_d*)free_slot->model, &config, &r);
  if (status != GYRO_OK) {
    destroy(free_slot);
    refused(status, &r);
  }
  free_slot->id = ++last_id;
  plhs[0] = mxCreateDoubleScalar(free_slot->id);
}

static void model_uncage(int nrhs, const mxArray* prhs[]) {
  Slot* s = model_of(arg(nrhs, prhs, 1, "model"));
  double r[9], rate[2], offset[2] = {0, 0};
  float rf[9], ratef[2], offsetf[2];
  int i;
  matrix3(arg(nrhs, prhs, 2, "R_earth_to_body"), "R_earth_to_body", r);
  numbers(arg(nrhs, prhs, 3, "body_rate"), "body_rate", 2, rate);
  if (has_arg(nrhs, prhs, 4)) numbers(prhs[4], "offset", 2, offset);
  if (!s->single) {
    check(gyro_model_d_uncage((gyro_model_d*)s->model, r, rate, offset), "model_uncage");
    return;
  }
  for (i = 0; i < 9; ++i) rf[i] = (float)r[i];
  for (i = 0; i < 2; ++i) ratef[i] = (float)rate[i], offsetf[i] = (float)offset[i];
  check(gyro_model_f_uncage((gyro_model_f*)s->model, rf, ratef, offsetf), "model_uncage");
}

/* model_step_slew / model_step_torque: the command is the slew rates or the torques. */
static void model_step(int nrhs, const mxArray* prhs[], int slew) {
  Slot* s = model_of(arg(nrhs, prhs, 1, "model"));
  const char* what = slew ? "slew_rate" : "torque";
  gyro_step_input_d in;
  gyro_step_input_f inf;
  double command[2];
  float commandf[2];
  int i, status;
  memset(&in, 0, sizeof in);
  in.dt_s = scalar(arg(nrhs, prhs, 2, "dt"), "dt");
  numbers(arg(nrhs, prhs, 3, what), what, 2, command);
  in.spin_hz = scalar(arg(nrhs, prhs, 4, "spin_hz"), "spin_hz");
  matrix3(arg(nrhs, prhs, 5, "R_earth_to_body"), "R_earth_to_body", in.R_earth_to_body);
  if (has_arg(nrhs, prhs, 6)) numbers(prhs[6], "body_accel", 2, in.body_accel);
  if (has_arg(nrhs, prhs, 7)) numbers(prhs[7], "body_rate", 3, in.body_rate_rad_s);
  if (!s->single) {
    gyro_model_d* m = (gyro_model_d*)s->model;
    status = slew ? gyro_model_d_step_slew(m, &in, command) : gyro_model_d_step_torque(m, &in, command);
  } else {
    gyro_model_f* m = (gyro_model_f*)s->model;
    inf.dt_s = (float)in.dt_s;
    inf.spin_hz = (float)in.spin_hz;
    for (i = 0; i < 9; ++i) inf.R_earth_to_body[i] = (float)in.R_earth_to_body[i];
    for (i = 0; i < 2; ++i) inf.body_accel[i] = (float)in.body_accel[i], commandf[i] = (float)command[i];
    for (i = 0; i < 3; ++i) inf.body_rate_rad_s[i] = (float)in.body_rate_rad_s[i];
    status = slew ? gyro_model_f_step_slew(m, &inf, commandf) : gyro_model_f_step_torque(m, &inf, commandf);
  }
  check(status, slew ? "model_step_slew" : "model_step_torque");
}

/* A reading of a model in its precision, as doubles. */
typedef void (*PairD)(const gyro_model_d*, double*);
typedef void (*PairF)(const gyro_model_f*, float*);
static mxArray* pair(const Slot* s, PairD d, PairF f) {
  double v[2];
  float vf[2];
  if (s->single) {
    f((const gyro_model_f*)s->model, vf);
    v[0] = vf[0], v[1] = vf[1];
  } else {
    d((const gyro_model_d*)s->model, v);
  }
  return column(v, 2, s->single);
}

static void model_state(mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  const Slot* s = model_of(arg(nrhs, prhs, 1, "model"));
  mxArray* out = mxCreateStructMatrix(1, 1, 0, NULL);
  double r[9], q[4], cone;
  float rf[9], qf[4];
  uint32_t flags;
  int uncaged, i;
  set(out, "gimbal", pair(s, gyro_model_d_gimbal, gyro_model_f_gimbal));
  set(out, "rate", pair(s, gyro_model_d_rate, gyro_model_f_rate));
  set(out, "isaf_angle", pair(s, gyro_model_d_isaf_angle, gyro_model_f_isaf_angle));
  set(out, "nutation_amplitude", pair(s, gyro_model_d_nutation_amplitude, gyro_model_f_nutation_amplitude));
  set(out, "applied_torque", pair(s, gyro_model_d_applied_torque, gyro_model_f_applied_torque));
  if (s->single) {
    const gyro_model_f* m = (const gyro_model_f*)s->model;
    gyro_model_f_R_earth_to_gyro(m, rf);
    gyro_model_f_attitude(m, qf);
    for (i = 0; i < 9; ++i) r[i] = rf[i];
    for (i = 0; i < 4; ++i) q[i] = qf[i];
    cone = gyro_model_f_cone(m);
    flags = gyro_model_f_flags(m);
    uncaged = gyro_model_f_uncaged(m);
  } else {
    const gyro_model_d* m = (const gyro_model_d*)s->model;
    gyro_model_d_R_earth_to_gyro(m, r);
    gyro_model_d_attitude(m, q);
    cone = gyro_model_d_cone(m);
    flags = gyro_model_d_flags(m);
    uncaged = gyro_model_d_uncaged(m);
  }
  set(out, "R_earth_to_gyro", matrix_of_rows(r, s->single));
  set(out, "attitude", column(q, 4, s->single));
  set(out, "cone", column(&cone, 1, s->single));
  set(out, "flags", mxCreateDoubleScalar(flags));
  set(out, "gimbal_limit_exceeded", mxCreateLogicalScalar((flags & GYRO_FLAG_GIMBAL_LIMIT) != 0));
  set(out, "small_angle_exceeded", mxCreateLogicalScalar((flags & GYRO_FLAG_SMALL_ANGLE) != 0));
  set(out, "uncaged", mxCreateLogicalScalar(uncaged != 0));
  set(out, "precision", mxCreateString(s->single ? "single" : "double"));
  plhs[0] = out;
}

/* ------------------------------------------------------------------------------------------- */
/* The exact step, vectorised over the columns of S. */

static void advance(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  const mxArray* states = arg(nrhs, prhs, 3, "states");
  const mxArray* torques = arg(nrhs, prhs, 4, "torque");
  double p[4], dt, *torque_d;
  const int single = mxIsSingle(states);
  size_t n, stride, i;
  uint8_t* status;
  int first;
  char message[200];
  numbers(arg(nrhs, prhs, 1, "params"), "params", 4, p);
  dt = scalar(arg(nrhs, prhs, 2, "dt"), "dt");
  require_real(states, "states");
  require_real(torques, "torque");
  if (mxGetM(states) != 4) fail("wrong_size", "states: expected 4 rows (theta, psi, theta', psi'), a column a state");
  n = mxGetN(states);
  if (mxGetM(torques) != 2 || (mxGetN(torques) != 1 && mxGetN(torques) != n)) {
    fail("wrong_size", "torque: expected 2 x 1, or 2 x n for n states");
  }
  stride = mxGetN(torques) == 1 ? 0 : 2;
  plhs[0] = mxDuplicateArray(states);
  status = (uint8_t*)mxMalloc(n > 0 ? n : 1);
  torque_d = (double*)mxMalloc(2 * mxGetN(torques) * sizeof(double));
  for (i = 0; i < 2 * mxGetN(torques); ++i) torque_d[i] = number_at(torques, i);
  if (single) {
    const gyro_rotor_parameters_f pf = {(float)p[0], (float)p[1], (float)p[2], (float)p[3]};
    gyro_transition_f tr;
    float* tf = (float*)mxMalloc(2 * mxGetN(torques) * sizeof(float));
    for (i = 0; i < 2 * mxGetN(torques); ++i) tf[i] = (float)torque_d[i];
    check(gyro_make_transition_f(&pf, (float)dt, &tr), "advance: the transition");
    first = gyro_advance_batch_f(&tr, (float*)mxGetData(plhs[0]), n, tf, stride, status);
  } else {
    const gyro_rotor_parameters_d pd = {p[0], p[1], p[2], p[3]};
    gyro_transition_d tr;
    check(gyro_make_transition_d(&pd, dt, &tr), "advance: the transition");
    first = gyro_advance_batch_d(&tr, (double*)mxGetData(plhs[0]), n, torque_d, stride, status);
  }
  if (nlhs > 1) {
    plhs[1] = mxCreateNumericMatrix(1, (mwSize)n, mxUINT8_CLASS, mxREAL);
    memcpy(mxGetData(plhs[1]), status, n);
  } else if (first != GYRO_OK) {
    i = 0;
    while (status[i] == GYRO_OK) ++i;  /* the first refused column: there is one */
    snprintf(message, sizeof message, "advance: state %u (column): %s", (unsigned)(i + 1), gyro_status_text(first));
    fail(gyro_status_name(first), message);
  }
}

/* ------------------------------------------------------------------------------------------- */
/* A SIL run. */

static void sil_run(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  const mxArray* scenario = arg(nrhs, prhs, 1, "scenario");
  gyro_sil_options options = {NULL, 0, 0};
  gyro_sil_result* run = NULL;
  gyro_sil_error error;
  gyro_sil_summary sum;
  char precision[16], option[32], message[800];
  char* source;
  mxArray *cols, *tm, *seen, *counters;
  size_t c, row, rows, b, nseen = 0;
  int i, status;
  if (!mxIsChar(scenario)) fail("wrong_type", "scenario: expected a file name or JSON text");
  for (i = 2; i < nrhs; i += 2) {
    text(prhs[i], "option name", option, sizeof option);
    if (i + 1 >= nrhs) fail("missing_argument", "sil_run: an option without its value");
    if (strcmp(option, "precision") == 0) {
      text(prhs[i + 1], "precision", precision, sizeof precision);
      options.precision = precision;
    } else if (strcmp(option, "ticks") == 0 || strcmp(option, "max_output_bytes") == 0) {
      const double v = scalar(prhs[i + 1], option);
      if (!(v >= 1 && v <= 9007199254740992.0) || v != floor(v)) {
        snprintf(message, sizeof message, "%s: expected a whole number from 1", option);
        fail("out_of_range", message);
      }
      if (option[0] == 't') {
        options.ticks = (uint64_t)v;
      } else {
        options.max_output_bytes = (uint64_t)v;
      }
    } else {
      snprintf(message, sizeof message, "sil_run: unknown option '%s' (precision, ticks, max_output_bytes)", option);
      fail("unknown_field", message);
    }
  }
  source = mxArrayToString(scenario);
  status = strspn(source, " \t\r\n") < strlen(source) && source[strspn(source, " \t\r\n")] == '{'
               ? gyro_sil_run_text(source, &options, &run, &error)
               : gyro_sil_run_file(source, &options, &run, &error);
  mxFree(source);
  if (status != GYRO_OK) {
    snprintf(message, sizeof message, "%s%s%s", error.message, error.field[0] != '\0' ? " (field: " : "",
             error.field[0] != '\0' ? error.field : "");
    if (error.field[0] != '\0') strncat(message, ")", sizeof message - strlen(message) - 1);
    fail(gyro_status_name(status), message);
  }
  rows = gyro_sil_rows(run);
  cols = mxCreateStructMatrix(1, 1, 0, NULL);
  for (c = 0; c < gyro_sil_columns(run); ++c) {
    mxArray* v = NULL;
    switch (gyro_sil_column_kind(run, c)) {
      case GYRO_SIL_NUMBERS:
        v = column(gyro_sil_numbers(run, c), rows, 0);
        break;
      case GYRO_SIL_INTEGERS:
        v = mxCreateNumericMatrix((mwSize)rows, 1, mxUINT64_CLASS, mxREAL);
        memcpy(mxGetData(v), gyro_sil_integers(run, c), rows * sizeof(uint64_t));
        break;
      default:
        v = mxCreateCellMatrix((mwSize)rows, 1);
        for (row = 0; row < rows; ++row) mxSetCell(v, (mwIndex)row, mxCreateString(gyro_sil_name(run, c, row)));
        break;
    }
    set(cols, gyro_sil_column_name(run, c), v);
  }
  gyro_sil_get_summary(run, &sum);
  tm = mxCreateStructMatrix(1, 1, 0, NULL);
  set(tm, "precision", mxCreateString(sum.precision));
  set(tm, "ticks", mxCreateDoubleScalar((double)sum.ticks));
  set(tm, "rows", mxCreateDoubleScalar((double)sum.rows));
  set(tm, "final_mode", mxCreateString(sum.final_mode));
  set(tm, "flags_seen", mxCreateDoubleScalar(sum.flags_seen));
  counters = mxCreateStructMatrix(1, 1, 0, NULL);
  for (b = 0; b < gyro_component_flag_count(); ++b) {
    set(counters, gyro_component_flag_name(b), mxCreateDoubleScalar(gyro_sil_counter(run, b)));
    nseen += (sum.flags_seen >> b) & 1u;
  }
  seen = mxCreateCellMatrix(1, (mwSize)nseen);
  for (b = 0, c = 0; b < gyro_component_flag_count(); ++b) {
    if ((sum.flags_seen >> b) & 1u) mxSetCell(seen, (mwIndex)c++, mxCreateString(gyro_component_flag_name(b)));
  }
  set(tm, "flags_seen_names", seen);
  set(tm, "counters", counters);
  set(tm, "refused_steps", mxCreateDoubleScalar((double)sum.refused_steps));
  set(tm, "nonfinite_values", mxCreateDoubleScalar((double)sum.nonfinite_values));
  set(tm, "gimbal_stop_hits", mxCreateDoubleScalar((double)sum.gimbal_stop_hits));
  set(tm, "max_abs_gimbal_rad", mxCreateDoubleScalar(sum.max_abs_gimbal_rad));
  gyro_sil_free(run);
  plhs[0] = cols;
  if (nlhs > 1) {
    plhs[1] = tm;
  } else {
    mxDestroyArray(tm);
  }
}

/* ------------------------------------------------------------------------------------------- */

static void report_sample(mxArray* plhs[]) {
  gyro_report_sample s;
  gyro_model_config config;
  mxArray* out = mxCreateStructMatrix(1, 1, 0, NULL);
  check(gyro_report_sample_get(&s, &config), "report_sample");
  set(out, "config", struct_from_config(GYRO_MODEL_CONFIG, &config));
  set(out, "spin_hz", mxCreateDoubleScalar(s.spin_hz));
  set(out, "body_rate", column(s.body_rate_rad_s, 2, 0));
  set(out, "slew", column(s.slew_rate_rad_s, 2, 0));
  set(out, "initg_step", mxCreateDoubleScalar(s.initg_step_s));
  set(out, "steps", mxCreateDoubleScalar(s.steps));
  plhs[0] = out;
}

static int config_kind(const mxArray* a) {
  char kind[16];
  text(a, "kind", kind, sizeof kind);
  if (strcmp(kind, "model") == 0) return GYRO_MODEL_CONFIG;
  if (strcmp(kind, "plant") == 0) return GYRO_PLANT_CONFIG;
  fail("out_of_range", "kind: expected 'model' or 'plant'");
  return 0;
}

void mexFunction(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  char command[32];
  static int registered = 0;
  if (!registered) {
    mexAtExit(destroy_all);
    registered = 1;
  }
  if (gyro_abi_version() != GYRO_ABI_VERSION) fail("internal_error", "libgyro's ABI is not the one gyro_mex was built for");
  text(arg(nrhs, prhs, 0, "command"), "command", command, sizeof command);
  if (strcmp(command, "version") == 0) {
    plhs[0] = mxCreateStructMatrix(1, 1, 0, NULL);
    set(plhs[0], "version", mxCreateString(gyro_version_string()));
    set(plhs[0], "abi", mxCreateDoubleScalar(gyro_abi_version()));
  } else if (strcmp(command, "advance") == 0) {
    advance(nlhs, plhs, nrhs, prhs);
  } else if (strcmp(command, "model_new") == 0) {
    model_new(nlhs, plhs, nrhs, prhs);
  } else if (strcmp(command, "model_uncage") == 0) {
    model_uncage(nrhs, prhs);
  } else if (strcmp(command, "model_step_slew") == 0) {
    model_step(nrhs, prhs, 1);
  } else if (strcmp(command, "model_step_torque") == 0) {
    model_step(nrhs, prhs, 0);
  } else if (strcmp(command, "model_state") == 0) {
    model_state(plhs, nrhs, prhs);
  } else if (strcmp(command, "model_delete") == 0) {
    destroy(model_of(arg(nrhs, prhs, 1, "model")));
  } else if (strcmp(command, "sil_run") == 0) {
    sil_run(nlhs, plhs, nrhs, prhs);
  } else if (strcmp(command, "report_sample") == 0) {
    report_sample(plhs);
  } else if (strcmp(command, "frame_rotation") == 0) {
    char axis[4];
    double r[9];
    text(arg(nrhs, prhs, 1, "axis"), "axis", axis, sizeof axis);
    if (strcmp(axis, "y") != 0 && strcmp(axis, "z") != 0) fail("out_of_range", "axis: expected 'y' or 'z'");
    check(gyro_frame_rotation_d(axis[0] == 'y' ? 1 : 2, scalar(arg(nrhs, prhs, 2, "angle"), "angle"), r),
          "frame_rotation");
    plhs[0] = matrix_of_rows(r, 0);
  } else if (strcmp(command, "config_fields") == 0) {
    const int kind = config_kind(arg(nrhs, prhs, 1, "kind"));
    const size_t n = gyro_config_field_count(kind);
    size_t i;
    plhs[0] = mxCreateCellMatrix(1, (mwSize)n);
    for (i = 0; i < n; ++i) mxSetCell(plhs[0], (mwIndex)i, mxCreateString(gyro_config_field_name(kind, i)));
  } else {
    char message[160];
    snprintf(message, sizeof message, "unknown command '%s' (see help gyro_mex)", command);
    fail("unknown_command", message);
  }
}
