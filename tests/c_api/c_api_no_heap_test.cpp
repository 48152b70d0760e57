// The C API's flight part never touches the heap: the exact step, GyroModel configured,
// uncaged and stepped in storage of the caller's, readings and refusals, in double and float
// (tests/support/heap_guard.hpp counts operator new and, linked with --wrap, malloc).
#define GYRO_HEAP_GUARD_IMPLEMENTATION  // this executable's operator new replacement
#include "support/heap_guard.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "gyro/gyro.h"

namespace gyro {
namespace {

using test::HeapUse;
using test::measure_heap;

TEST(CApiNoHeap, GivenTheCanaryThenAModelOnTheHeapIsCounted) {
  gyro_model_d* m = nullptr;
  const HeapUse use = measure_heap([&] { m = gyro_model_d_create(); });
  EXPECT_EQ(use.allocations, 1u);
  gyro_model_d_destroy(m);
}

TEST(CApiNoHeap, GivenTheFlightPartThenNoAllocation) {
  gyro_report_sample s{};
  gyro_model_config config{};
  gyro_model_d_storage sd;
  gyro_model_f_storage sf;
  int failed = 0;
  double gimbal[2] = {0, 0};
  char text[128];
  const HeapUse use = measure_heap([&] {
    failed += gyro_report_sample_get(&s, &config) != GYRO_OK;
    gyro_model_d* md = gyro_model_d_init(&sd, sizeof sd);
    gyro_model_f* mf = gyro_model_f_init(&sf, sizeof sf);
    gyro_refusal r;
    failed += gyro_model_d_configure(md, &config, &r) != GYRO_OK;
    failed += gyro_model_f_configure(mf, &config, &r) != GYRO_OK;
    gyro_step_input_d in{};
    gyro_step_input_f inf{};
    in.dt_s = s.initg_step_s;
    in.spin_hz = s.spin_hz;
    inf.dt_s = static_cast<float>(in.dt_s);
    inf.spin_hz = static_cast<float>(in.spin_hz);
    for (int i = 0; i < 9; i += 4) in.R_earth_to_body[i] = 1.0, inf.R_earth_to_body[i] = 1.0f;
    const float rate_f[2] = {0.1f, 0.2f};
    failed += gyro_model_d_uncage(md, in.R_earth_to_body, s.body_rate_rad_s, nullptr) != GYRO_OK;
    failed += gyro_model_f_uncage(mf, inf.R_earth_to_body, rate_f, rate_f) != GYRO_OK;
    for (int k = 0; k < 100; ++k) {
      failed += gyro_model_d_step_slew(md, &in, s.slew_rate_rad_s) != GYRO_OK;
      failed += gyro_model_f_step_torque(mf, &inf, rate_f) != GYRO_OK;
    }
    gyro_model_d_gimbal(md, gimbal);
    double roteg[9];
    gyro_model_d_R_earth_to_gyro(md, roteg);
    failed += gyro_nearest_rotation_d(roteg, roteg) != GYRO_OK;
    gyro_model_config bad = config;
    bad.friction = -1.0;
    failed += gyro_model_d_configure(md, &bad, &r) != GYRO_NEGATIVE_FRICTION;
    failed += gyro_refusal_text(&r, text, sizeof text) <= 0;
    failed += gyro_config_set_choice(GYRO_MODEL_CONFIG, &bad, "torquer_axes", "gimbal") != GYRO_OK;
    gyro_transition_d tr;
    const gyro_rotor_parameters_d p{2.25, 2.0, 5.0, gyro_angular_momentum_d(100.0, 3.0)};
    failed += gyro_make_transition_d(&p, 1e-3, &tr) != GYRO_OK;
    double states[8] = {0, 0, 1, 1, 0, 0, -1, 1};
    failed += gyro_advance_batch_d(&tr, states, 2, s.slew_rate_rad_s, 0, nullptr) != GYRO_OK;
  });
  EXPECT_EQ(failed, 0);
  EXPECT_NE(gimbal[0], 0.0);
  EXPECT_EQ(use.allocations, 0u);
  EXPECT_EQ(use.releases, 0u);
}

}  // namespace
}  // namespace gyro
