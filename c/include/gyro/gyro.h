/* gyro's C API (C99): the exact rotor step, the report's gyro model (GyroModel) in double and
 * float, the nonlinear gimbal plant and a software-in-the-loop run, for C and for any language
 * with a C foreign-function interface (Fortran, MATLAB/Octave, Python ctypes, ...).
 * docs/embedding.md shows each in use.
 *
 * - Statuses are integers (gyro_status); gyro_status_text() says what one means. A call that
 *   returns anything but GYRO_OK leaves its object as it was.
 * - Handles are opaque. The flight parts (exact step, GyroModel) live in storage the caller
 *   owns: gyro_model_d_init(storage, bytes) places a model in it, no heap is ever used, and
 *   nothing needs freeing. The host parts (gimbal plant, SIL run) and the *_create functions
 *   allocate; each has its *_destroy / *_free.
 * - A refused configuration names its field (gyro_refusal.field) with the value and the bound.
 * - No C++ exception crosses this boundary: the flight parts are built without exceptions and
 *   the host parts catch everything and return a status.
 * - Matrices are row by row: r[3*i + j] is R(i, j) (C's double r[3][3] has that layout).
 * - ABI: see GYRO_ABI_VERSION below.
 */
#ifndef GYRO_GYRO_H
#define GYRO_GYRO_H

#include <stddef.h>
#include <stdint.h>

#include "gyro/gyro_version.h" /* GYRO_VERSION_MAJOR, _MINOR, _PATCH, GYRO_VERSION_STRING */

#ifdef __cplusplus
extern "C" {
#endif

/* The ABI of this header. It changes (and the shared library's SONAME, libgyro.so.N, with it)
 * whenever a struct's layout, a storage size, an enumerator's value or a function's signature
 * changes; new functions and new enumerators at the end keep it. A program built against this
 * header runs with a library whose gyro_abi_version() equals GYRO_ABI_VERSION. */
#define GYRO_ABI_VERSION 1
unsigned gyro_abi_version(void);
const char* gyro_version_string(void); /* the library's GYRO_VERSION_STRING */

/* ---------------------------------------------------------------------------------------------
 * Statuses. 0 to 12 are the C++ library's gyro::Status (gyro/status.hpp), in its order; the C
 * API's own follow from 64. */
typedef enum gyro_status {
  GYRO_OK = 0,
  GYRO_NON_FINITE_INPUT = 1,          /* a NaN or an infinity among the inputs */
  GYRO_NON_POSITIVE_INERTIA = 2,
  GYRO_NEGATIVE_FRICTION = 3,
  GYRO_NEGATIVE_ANGULAR_MOMENTUM = 4,
  GYRO_NON_POSITIVE_STEP = 5,
  GYRO_NO_STEADY_STATE = 6,           /* f = H = 0 */
  GYRO_OUT_OF_RANGE = 7,
  GYRO_NUMERICAL_OVERFLOW = 8,
  GYRO_NOT_CONFIGURED = 9,            /* configure (and, for a model, uncage) first */
  GYRO_INVALID_ROTATION = 10,         /* a matrix that is not a rotation */
  GYRO_WRONG_MODE = 11,
  GYRO_INPUT_IGNORED = 12,
  GYRO_NULL_ARGUMENT = 64,            /* a required pointer is NULL */
  GYRO_STORAGE_TOO_SMALL = 65,        /* *_init: fewer bytes than *_storage_size() */
  GYRO_UNKNOWN_FIELD = 66,            /* gyro_config_*: no field (or choice) of that name */
  GYRO_SCENARIO_ERROR = 67,           /* gyro_sil_run_*: the scenario is refused */
  GYRO_RUN_ERROR = 68,                /* gyro_sil_run_*: the run failed (output bound, ...) */
  GYRO_OUT_OF_MEMORY = 69,
  GYRO_INTERNAL_ERROR = 70            /* a defect of gyro's: please report it */
} gyro_status;

const char* gyro_status_text(int status); /* "time step must be > 0"; never NULL */
const char* gyro_status_name(int status); /* "non_positive_step" (as gyro.Status spells it) */

/* Why a configuration was refused: the field (dotted for nested ones:
 * "errors.pitch.static_drift_rad_s"), its value and the bound it broke. The strings are
 * static. */
typedef struct gyro_refusal {
  int status;             /* GYRO_OK when accepted */
  const char* field;      /* NULL when accepted */
  double value;
  double bound;
  int relation;           /* 0 none, 1 below the bound, 2 above it, 3 not finite */
  const char* bound_name; /* what the bound is, or NULL: the field's own range */
  const char* rule;       /* why the bound is there, or NULL */
} gyro_refusal;

/* "pitch_inertia = -1 is below its lower bound (1e-12): consistent units ..." into buf
 * (always terminated when n > 0); returns the length wanted, as snprintf does. */
int gyro_refusal_text(const gyro_refusal* refusal, char* buf, size_t n);

/* ---------------------------------------------------------------------------------------------
 * The exact step (report eqs 1a/1b; docs/exact-step.md). A state is (theta, psi, theta', psi'),
 * a torque (T1, T2), in any consistent units. */
typedef struct gyro_rotor_parameters_d {
  double pitch_inertia;    /* J1 */
  double yaw_inertia;      /* J2 */
  double friction;         /* f */
  double angular_momentum; /* H = 2 pi spin_hz J0 (gyro_angular_momentum_d) */
} gyro_rotor_parameters_d;
typedef struct gyro_rotor_parameters_f {
  float pitch_inertia, yaw_inertia, friction, angular_momentum;
} gyro_rotor_parameters_f;

/* The step's coefficients: E0 (rates from rates), E1 (angles from rates), E1 J^-1 and E2 J^-1
 * (rates and angles from the torque), each 2x2 column by column, then dt. Plain data: copy it
 * freely. */
typedef struct gyro_transition_d {
  double coefficients[17];
} gyro_transition_d;
typedef struct gyro_transition_f {
  float coefficients[17];
} gyro_transition_f;

double gyro_angular_momentum_d(double spin_hz, double spin_inertia);
float gyro_angular_momentum_f(float spin_hz, float spin_inertia);

/* The exact transition of `p` over dt (every damping regime; no division by beta or H). */
int gyro_make_transition_d(const gyro_rotor_parameters_d* p, double dt_s, gyro_transition_d* out);
int gyro_make_transition_f(const gyro_rotor_parameters_f* p, float dt_s, gyro_transition_f* out);
/* One state by one step under a torque held over it (about 40 instructions of arithmetic). */
int gyro_advance_d(const gyro_transition_d* tr, const double torque[2], double state[4]);
int gyro_advance_f(const gyro_transition_f* tr, const float torque[2], float state[4]);
/* n states (4 numbers each, one after another) by one step: one torque for all
 * (torque_stride 0) or one per state (torque_stride 2). statuses (n bytes, may be NULL) gets
 * each state's status; a refused state is left as it was. Returns the first refusal, or GYRO_OK. */
int gyro_advance_batch_d(const gyro_transition_d* tr, double* states, size_t n, const double* torques,
                         size_t torque_stride, uint8_t* statuses);
int gyro_advance_batch_f(const gyro_transition_f* tr, float* states, size_t n, const float* torques,
                         size_t torque_stride, uint8_t* statuses);

/* The rotor's modes (report eq 11). regime: 0 underdamped, 1 critical, 2 overdamped, 3 free. */
typedef struct gyro_rotor_modes_d {
  double alpha_1_s, beta_squared_1_s2, beta_rad_s, natural_rate_rad_s;
  double slow_decay_rate_1_s, fast_decay_rate_1_s, nutation_hz;
  int regime;
} gyro_rotor_modes_d;
int gyro_compute_modes_d(const gyro_rotor_parameters_d* p, gyro_rotor_modes_d* out);

/* ---------------------------------------------------------------------------------------------
 * Configurations: structs of plain fields, each the fields of a C++ configuration in its
 * field table's order (names, units, bounds and rules: docs/embedding.md). A field list below
 * declares the struct: X(kind, name), kind REAL (a double), VEC3 (double[3]), CHOICE (an int:
 * the index of its name, gyro_config_choice_name) or a nested struct. Start from the defaults
 * (gyro_config_init), set what you need, and configure: the configure call checks every field. */
#define GYRO_C_TYPE_REAL double
#define GYRO_C_TYPE_VEC3 double
#define GYRO_C_TYPE_CHOICE int
#define GYRO_C_TYPE_AXIS_ERRORS gyro_axis_errors
#define GYRO_C_TYPE_ERROR_SOURCES gyro_error_sources
#define GYRO_C_DIM_REAL
#define GYRO_C_DIM_VEC3 [3]
#define GYRO_C_DIM_CHOICE
#define GYRO_C_DIM_AXIS_ERRORS
#define GYRO_C_DIM_ERROR_SOURCES
#define GYRO_C_MEMBER(kind, name) GYRO_C_TYPE_##kind name GYRO_C_DIM_##kind;

/* One axis's error sources (gyro/error_sources.hpp: AxisErrorSources), each 0 for none. */
#define GYRO_AXIS_ERRORS_FIELDS(X)  \
  X(REAL, static_drift_rad_s)       \
  X(REAL, in_plane_erection_1_s)    \
  X(REAL, cross_plane_erection_1_s) \
  X(REAL, g_sensitive_drift_rad_s)  \
  X(REAL, torquer_cross_coupling)   \
  X(REAL, coulomb_friction_rad_s)
typedef struct gyro_axis_errors {
  GYRO_AXIS_ERRORS_FIELDS(GYRO_C_MEMBER)
} gyro_axis_errors;

/* pitch drifts theta' (the report's GERROR(:,2)), yaw drifts psi' (GERROR(:,1)). */
#define GYRO_ERROR_SOURCES_FIELDS(X) \
  X(AXIS_ERRORS, pitch)              \
  X(AXIS_ERRORS, yaw)
typedef struct gyro_error_sources {
  GYRO_ERROR_SOURCES_FIELDS(GYRO_C_MEMBER)
} gyro_error_sources;

/* GyroModel's (gyro/gyro_model.hpp: GyroModelConfig). torquer_axes: "gyro" or "gimbal". */
#define GYRO_MODEL_CONFIG_FIELDS(X)  \
  X(REAL, pitch_inertia)             \
  X(REAL, yaw_inertia)               \
  X(REAL, spin_inertia)              \
  X(REAL, friction)                  \
  X(REAL, gimbal_cone_limit_rad)     \
  X(REAL, pitch_gimbal_limit_rad)    \
  X(REAL, yaw_gimbal_limit_rad)      \
  X(REAL, max_pitch_rate_rad_s)      \
  X(REAL, max_yaw_rate_rad_s)        \
  X(REAL, small_angle_limit_rad)     \
  X(REAL, gravity)                   \
  X(ERROR_SOURCES, errors)           \
  X(CHOICE, torquer_axes)
typedef struct gyro_model_config {
  GYRO_MODEL_CONFIG_FIELDS(GYRO_C_MEMBER)
} gyro_model_config;

/* The gimbal plant's (gyro/gimbal_plant_config.hpp: GimbalPlantConfig; docs/gimbal-plant.md).
 * spin_drive: "motor" or "free"; torquer_axes: "gimbal" or "gyro". */
#define GYRO_PLANT_CONFIG_FIELDS(X)    \
  X(REAL, spin_inertia)                \
  X(REAL, rotor_transverse_inertia)    \
  X(VEC3, inner_gimbal_inertia)        \
  X(VEC3, outer_gimbal_inertia)        \
  X(REAL, inner_friction)              \
  X(REAL, outer_friction)              \
  X(REAL, inner_coulomb_torque)        \
  X(REAL, outer_coulomb_torque)        \
  X(REAL, coulomb_rate_scale_rad_s)    \
  X(CHOICE, spin_drive)                \
  X(REAL, max_spin_hz)                 \
  X(REAL, motor_torque_limit)          \
  X(REAL, spin_servo_bandwidth_rad_s)  \
  X(REAL, spin_down_time_s)            \
  X(REAL, mass_unbalance)              \
  X(REAL, stop_cone_rad)               \
  X(REAL, stop_restitution)            \
  X(CHOICE, torquer_axes)              \
  X(REAL, max_body_rate_rad_s)         \
  X(REAL, max_torque)                  \
  X(REAL, max_specific_force)          \
  X(REAL, max_substep_phase_rad)       \
  X(REAL, error_target_rad)
typedef struct gyro_plant_config {
  GYRO_PLANT_CONFIG_FIELDS(GYRO_C_MEMBER)
} gyro_plant_config;

/* The same fields by name, for callers that cannot see the structs (an FFI, a MATLAB struct).
 * Names are dotted below a nested struct ("errors.yaw.coulomb_friction_rad_s"). */
typedef enum gyro_config_kind { GYRO_MODEL_CONFIG = 1, GYRO_PLANT_CONFIG = 2 } gyro_config_kind;
size_t gyro_config_size(int kind);                          /* sizeof the struct; 0: no such kind */
int gyro_config_init(int kind, void* config);               /* the C++ struct's defaults */
size_t gyro_config_field_count(int kind);                   /* leaf fields */
const char* gyro_config_field_name(int kind, size_t index); /* NULL past the end */
size_t gyro_config_field_length(int kind, const char* name); /* numbers: 1 or 3; 0: a choice or none */
int gyro_config_set(int kind, void* config, const char* name, const double* values, size_t n);
int gyro_config_get(int kind, const void* config, const char* name, double* values, size_t n);
int gyro_config_set_choice(int kind, void* config, const char* name, const char* choice);
const char* gyro_config_choice(int kind, const void* config, const char* name); /* NULL: none */
const char* gyro_config_choice_name(int kind, const char* name, size_t index); /* NULL past the end */

/* ---------------------------------------------------------------------------------------------
 * GyroModel: the report's subroutine GYRO as an object (docs/seed-errata.md lists the listing's
 * errors it fixes). configure -> uncage -> step ...; read the state after each step. */
typedef struct gyro_model_d gyro_model_d;
typedef struct gyro_model_f gyro_model_f;

/* Storage for a model: at least *_storage_size() bytes, any alignment. These sizes bound every
 * supported target's (the library checks it at build time). */
#define GYRO_MODEL_D_STORAGE_BYTES 2048
#define GYRO_MODEL_F_STORAGE_BYTES 1024
typedef struct gyro_model_d_storage {
  double bytes[GYRO_MODEL_D_STORAGE_BYTES / sizeof(double)];
} gyro_model_d_storage;
typedef struct gyro_model_f_storage {
  double bytes[GYRO_MODEL_F_STORAGE_BYTES / sizeof(double)];
} gyro_model_f_storage;
size_t gyro_model_d_storage_size(void);
size_t gyro_model_f_storage_size(void);
/* A new, unconfigured model in `storage`; NULL if storage is NULL or smaller than
 * *_storage_size(). The storage may be reused or freed at any time: nothing to release. */
gyro_model_d* gyro_model_d_init(void* storage, size_t bytes);
gyro_model_f* gyro_model_f_init(void* storage, size_t bytes);

/* Configures (the gyro stays caged). The float model takes the same struct, cast to float
 * after the double check. refusal may be NULL. */
int gyro_model_d_configure(gyro_model_d* m, const gyro_model_config* config, gyro_refusal* refusal);
int gyro_model_f_configure(gyro_model_f* m, const gyro_model_config* config, gyro_refusal* refusal);

/* Uncages: the gyro's attitude is the body's turned by the small (pitch, yaw) offset, its rates
 * the body's pitch and yaw rates. offset may be NULL (zero). */
int gyro_model_d_uncage(gyro_model_d* m, const double R_earth_to_body[9], const double body_rate_rad_s[2],
                        const double offset_rad[2]);
int gyro_model_f_uncage(gyro_model_f* m, const float R_earth_to_body[9], const float body_rate_rad_s[2],
                        const float offset_rad[2]);

/* One step's inputs. R_earth_to_body is the body's attitude at the END of the step. */
typedef struct gyro_step_input_d {
  double dt_s;
  double R_earth_to_body[9];
  double body_accel[2];      /* (lateral y, normal z), in the units of config.gravity */
  double spin_hz;            /* may change from step to step (spin-down) */
  double body_rate_rad_s[3]; /* (p, q, r), read with torquer_axes "gimbal" only */
} gyro_step_input_d;
typedef struct gyro_step_input_f {
  float dt_s;
  float R_earth_to_body[9];
  float body_accel[2];
  float spin_hz;
  float body_rate_rad_s[3];
} gyro_step_input_f;

/* The report's command: slew rates (pitch, yaw), limited per axis, turned into torque for a
 * frictionless gyro as the report's torquer does. */
int gyro_model_d_step_slew(gyro_model_d* m, const gyro_step_input_d* in, const double slew_rate_rad_s[2]);
int gyro_model_f_step_slew(gyro_model_f* m, const gyro_step_input_f* in, const float slew_rate_rad_s[2]);
/* Torquer torques (T1, T2) held over the step: about the gyro's axes, or (inner, outer) about
 * the gimbal axes with torquer_axes "gimbal". */
int gyro_model_d_step_torque(gyro_model_d* m, const gyro_step_input_d* in, const double torque[2]);
int gyro_model_f_step_torque(gyro_model_f* m, const gyro_step_input_f* in, const float torque[2]);

/* Flag bits of gyro_model_*_flags(). */
#define GYRO_FLAG_GIMBAL_LIMIT 1u /* outside the gimbal cone or a per-axis limit */
#define GYRO_FLAG_SMALL_ANGLE 2u  /* the step's angles or the nutation beyond the small-angle limit */

/* The state after the last step (or the uncaging). */
void gyro_model_d_gimbal(const gyro_model_d* m, double gimbal_rad[2]); /* (pitch, yaw) */
void gyro_model_f_gimbal(const gyro_model_f* m, float gimbal_rad[2]);
void gyro_model_d_rate(const gyro_model_d* m, double rate_rad_s[2]); /* (theta', psi'), gyro axes */
void gyro_model_f_rate(const gyro_model_f* m, float rate_rad_s[2]);
void gyro_model_d_isaf_angle(const gyro_model_d* m, double angle_rad[2]); /* the last step's */
void gyro_model_f_isaf_angle(const gyro_model_f* m, float angle_rad[2]);
void gyro_model_d_nutation_amplitude(const gyro_model_d* m, double amplitude_rad[2]);
void gyro_model_f_nutation_amplitude(const gyro_model_f* m, float amplitude_rad[2]);
void gyro_model_d_applied_torque(const gyro_model_d* m, double torque[2]); /* error sources included */
void gyro_model_f_applied_torque(const gyro_model_f* m, float torque[2]);
void gyro_model_d_R_earth_to_gyro(const gyro_model_d* m, double R[9]); /* the report's ROTEG */
void gyro_model_f_R_earth_to_gyro(const gyro_model_f* m, float R[9]);
void gyro_model_d_attitude(const gyro_model_d* m, double q_gyro_to_earth[4]); /* (w, x, y, z) */
void gyro_model_f_attitude(const gyro_model_f* m, float q_gyro_to_earth[4]);
double gyro_model_d_cone(const gyro_model_d* m); /* spin axis to body x (rad) */
float gyro_model_f_cone(const gyro_model_f* m);
uint32_t gyro_model_d_flags(const gyro_model_d* m);
uint32_t gyro_model_f_flags(const gyro_model_f* m);
int gyro_model_d_uncaged(const gyro_model_d* m);
int gyro_model_f_uncaged(const gyro_model_f* m);

/* ---------------------------------------------------------------------------------------------
 * Rotations. A body turning by `angle` about its own y or z axis (axis 1 or 2) has
 * R_new = R_axis(angle) R_old (gyro/attitude.hpp; exact, where the report's driver's ROTY and
 * ROTZ are first order). */
int gyro_frame_rotation_d(int axis, double angle_rad, double R[9]);
/* A direction-cosine matrix that has drifted from a rotation (a 6-DOF's first-order updates)
 * brought back to the nearest rotation (its orthogonal polar factor). Refused
 * (GYRO_INVALID_ROTATION) when R R^T - I has an entry beyond GYRO_ROTATION_REPAIR_LIMIT or
 * det R <= 0: such a matrix is an attitude gone wrong, not rounding. in and out may be the
 * same. */
#define GYRO_ROTATION_REPAIR_LIMIT 1e-3
int gyro_nearest_rotation_d(const double R[9], double out[9]);
int gyro_nearest_rotation_f(const float R[9], float out[9]);

/* The report's sample run (GYMAIN with INITG; gyro/report_sample.hpp): its gyro (into config),
 * spin, body rates, slew command, INITG's step and step count, as the examples use them. */
typedef struct gyro_report_sample {
  double spin_hz;
  double body_rate_rad_s[2]; /* (pitch, yaw) */
  double slew_rate_rad_s[2]; /* the command, before the limits */
  double initg_step_s;       /* INITG's step for its gyro (gyro_initg_step_d) */
  int steps;
} gyro_report_sample;
int gyro_report_sample_get(gyro_report_sample* out, gyro_model_config* config);
/* INITG's step for a rotor: 1/floor(20 x nutation Hz), at least 20 steps a nutation cycle.
 * GYRO_OUT_OF_RANGE (and *step_s untouched) when the rotor does not nutate at 0.05 Hz or more:
 * the listing divides by zero there, or takes the root of a negative number when overdamped. */
int gyro_initg_step_d(const gyro_rotor_parameters_d* p, double* step_s);

/* ---------------------------------------------------------------------------------------------
 * The host part (a libgyro built for the machine it runs on; not in a cross-compiled one):
 * models on the heap, the gimbal plant, SIL runs (where the build has its tools). */

/* A model on the heap (for callers that cannot hold storage: an FFI, a MEX file). NULL when out
 * of memory. */
gyro_model_d* gyro_model_d_create(void);
gyro_model_f* gyro_model_f_create(void);
void gyro_model_d_destroy(gyro_model_d* m); /* NULL is fine */
void gyro_model_f_destroy(gyro_model_f* m);

/* The nonlinear two-axis gimbal plant of the SIL stub (docs/gimbal-plant.md). */
typedef struct gyro_plant_d gyro_plant_d;
gyro_plant_d* gyro_plant_d_create(void);
void gyro_plant_d_destroy(gyro_plant_d* p);
/* Fixes the sub-steps of a tick of tick_s; the plant waits for start. */
int gyro_plant_d_configure(gyro_plant_d* p, const gyro_plant_config* config, double tick_s, gyro_refusal* refusal);
/* Joint angles (pitch, yaw) and their rates relative to the carriers, the spin relative to the
 * inner gimbal (Hz), the body's rate (p, q, r) and specific force at the start. NULL: zeros. */
int gyro_plant_d_start(gyro_plant_d* p, const double gimbal_angle_rad[2], const double gimbal_rate_rad_s[2],
                       double spin_hz, const double body_rate_rad_s[3], const double specific_force[3]);
/* One tick with the torques (inner/pitch, outer/yaw) held; the body's rate and specific force go
 * linearly from the last tick's to these (NULL: unchanged). */
int gyro_plant_d_step(gyro_plant_d* p, const double torque[2], const double body_rate_rad_s[3],
                      const double specific_force[3]);
void gyro_plant_d_gimbal(const gyro_plant_d* p, double angle_rad[2], double rate_rad_s[2]);
void gyro_plant_d_spin_axis_body(const gyro_plant_d* p, double axis[3]);
double gyro_plant_d_cone(const gyro_plant_d* p);
double gyro_plant_d_spin_rate(const gyro_plant_d* p); /* relative to the inner gimbal, rad/s */
int gyro_plant_d_in_contact(const gyro_plant_d* p);   /* touched its stop in the last tick */

/* A SIL run (gyro_sil's loop: the flight component against the simulated gyro, the body and
 * the guidance of a scenario; docs/scenarios.md), kept as columns of gyro_sil's CSV. */
typedef struct gyro_sil_result gyro_sil_result;
typedef struct gyro_sil_options {
  const char* precision;     /* "float", "double", or NULL: the scenario's */
  uint64_t ticks;            /* 0: the scenario's */
  uint64_t max_output_bytes; /* 0: 1 GiB; a run whose CSV could be larger is refused up front */
} gyro_sil_options;
/* What went wrong, when a run is refused: the message, and the scenario field it names ("" if
 * none). */
typedef struct gyro_sil_error {
  char message[512];
  char field[128];
} gyro_sil_error;
/* The scenario from a JSON file, or from JSON text. options and error may be NULL. On GYRO_OK,
 * *result holds the run (release it with gyro_sil_free). */
int gyro_sil_run_file(const char* path, const gyro_sil_options* options, gyro_sil_result** result,
                      gyro_sil_error* error);
int gyro_sil_run_text(const char* json, const gyro_sil_options* options, gyro_sil_result** result,
                      gyro_sil_error* error);
void gyro_sil_free(gyro_sil_result* r);

size_t gyro_sil_rows(const gyro_sil_result* r);
size_t gyro_sil_columns(const gyro_sil_result* r);
const char* gyro_sil_column_name(const gyro_sil_result* r, size_t column); /* NULL past the end */
/* A column's values: numbers, whole numbers (tick, flag words, statuses) or names (modes). */
enum { GYRO_SIL_NUMBERS = 0, GYRO_SIL_INTEGERS = 1, GYRO_SIL_NAMES = 2 };
int gyro_sil_column_kind(const gyro_sil_result* r, size_t column); /* -1 past the end */
const double* gyro_sil_numbers(const gyro_sil_result* r, size_t column);    /* NULL unless numbers */
const uint64_t* gyro_sil_integers(const gyro_sil_result* r, size_t column); /* NULL unless integers */
const char* gyro_sil_name(const gyro_sil_result* r, size_t column, size_t row); /* NULL unless names */

/* The component's telemetry at the end of the run. */
typedef struct gyro_sil_summary {
  uint64_t ticks;              /* after tick 0 */
  uint64_t rows;
  const char* precision;       /* "float" or "double" */
  const char* final_mode;
  uint32_t flags_seen;         /* OR of the component's flags over the run */
  uint64_t refused_steps;
  uint64_t nonfinite_values;
  uint64_t gimbal_stop_hits;
  double max_abs_gimbal_rad;
} gyro_sil_summary;
void gyro_sil_get_summary(const gyro_sil_result* r, gyro_sil_summary* out);
/* The component's flags: their names, bit 0 first, and how often each was raised in the run. */
size_t gyro_component_flag_count(void);
const char* gyro_component_flag_name(size_t bit); /* NULL past the end */
uint32_t gyro_sil_counter(const gyro_sil_result* r, size_t bit);

#ifdef __cplusplus
}
#endif

#endif /* GYRO_GYRO_H */
