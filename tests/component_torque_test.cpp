// The torque the component writes, against the SIL stub and a scripted port: the slew flown in
// closed loop (the rate achieved, friction's cross-coupling removed, the rate limits and the
// torquer's saturation), and the nutation shaper between the torque law and the torquers
// (designed for the spin flown, emptied by safe mode).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "support/requirements.hpp"
#include "support/scripted_bench.hpp"
#include "support/sil_fixture.hpp"

namespace gyro {
namespace component_torque_test {

using testing::Bench;
using testing::SeekerGyro;
using testing::Sil;

const GyroComponentConfig<double> kSeeker = SeekerGyro<double>::component();

// ---- the slew in closed loop --------------------------------------------------------------------

// Mean true precession rate over `ticks` ticks of slewing at `cmd`.
Vector2<double> mean_true_rate(Sil<double>& sil, const Vector2<double>& cmd, int settle, int ticks) {
  sil.guidance.slew_rate_cmd_rad_s = cmd;
  sil.run(settle);
  Vector2<double> sum = Vector2<double>::Zero();
  for (int k = 0; k < ticks; ++k) {
    (void)sil.step();
    sum += sil.gyro.spin_axis_rate_rad_s();
  }
  return sum / ticks;
}

// With friction f the report's torque law T = (H w2, -H w1) precesses at k5, k6 instead of
// the command: the error is (f/H)(w2, -w1) to first order. The exact inverse removes it.
TEST(ComponentSlew, FlownAtTheRateWithoutFrictionCoupling) {
  GYRO_VERIFIES("TORQ-6");
  const Vector2<double> cmd(0.3, -0.2);
  const double h = angular_momentum(400.0, 3e-5), f = 4e-4;
  for (bool compensate : {true, false}) {
    GyroComponentConfig<double> c = kSeeker;
    c.friction_compensation = compensate;
    Sil<double> sil;
    ASSERT_TRUE(sil.start(c));
    ASSERT_TRUE(sil.uncage());
    // Settle 0.3 s (6 time constants of nutation decay), then average over 0.2 s.
    const Vector2<double> w = mean_true_rate(sil, cmd, 600, 400);
    const Vector2<double> err = w - cmd;
    const Vector2<double> coupling((f * h * cmd(1) - f * f * cmd(0)) / (f * f + h * h),
                                   (-f * h * cmd(0) - f * f * cmd(1)) / (f * f + h * h));
    std::printf("friction compensation %s: slew error pitch %.3e yaw %.3e rad/s (theory of the uncompensated "
                "coupling %.3e %.3e)\n",
                compensate ? "on " : "off", err(0), err(1), coupling(0), coupling(1));
    if (compensate) {
      // Bound: the nutation left after 6 time constants, averaged over 75 periods: < 1e-4 of the command.
      EXPECT_LT(err.cwiseAbs().maxCoeff(), 1e-4 * cmd.norm());
    } else {
      EXPECT_NEAR(err(0), coupling(0), 0.02 * std::abs(coupling(0)) + 1e-4 * cmd.norm());
      EXPECT_NEAR(err(1), coupling(1), 0.02 * std::abs(coupling(1)) + 1e-4 * cmd.norm());
      EXPECT_GT(err.cwiseAbs().maxCoeff(), 1e-3);  // 1.6e-3 rad/s of cross rate: visible
    }
    EXPECT_EQ(sil.component.mode(), GyroMode::kFree);
    EXPECT_EQ(sil.tm().counters[6], 0u) << "no residual fault on a healthy gyro";
  }
}

TEST(ComponentSlew, ClampedPerAxisAndSaturatedInDirection) {
  GYRO_VERIFIES("TORQ-3", "TORQ-5");
  GyroComponentConfig<double> c = kSeeker;
  c.max_pitch_rate_rad_s = 0.2;
  c.max_yaw_rate_rad_s = 0.5;
  c.max_torque = 0.02;  // 0.27 rad/s at H = 0.0754
  Sil<double> sil;
  ASSERT_TRUE(sil.start(c));
  ASSERT_TRUE(sil.uncage());
  sil.guidance.slew_rate_cmd_rad_s = Vector2<double>(-0.9, 0.9);
  ASSERT_EQ(sil.step(), Status::kOk);
  EXPECT_EQ(sil.tm().rate_cmd_rad_s, Vector2<double>(-0.2, 0.5));
  EXPECT_NE(sil.tm().flags & kSlewRateLimited, 0u);
  EXPECT_NE(sil.tm().flags & kTorquerSaturated, 0u);
  // The torque shaper (one tick of spacing at this rotor) reaches the law's torque on the
  // third tick of the same command.
  ASSERT_EQ(sil.step(), Status::kOk);
  ASSERT_EQ(sil.step(), Status::kOk);
  EXPECT_NEAR(sil.tm().torque_cmd.cwiseAbs().maxCoeff(), 0.02, 1e-15);
  // Direction kept: torque proportional to the unsaturated law's (f w1 + H w2, f w2 - H w1).
  const double h = angular_momentum(400.0, 3e-5), f = 4e-4;
  const Vector2<double> full(f * -0.2 + h * 0.5, f * 0.5 - h * -0.2);
  // (Three ticks on, the gimbal has moved by 1e-9 rad: a per-axis clip would be off by 1e-4.)
  EXPECT_NEAR(sil.tm().torque_cmd(0) * full(1) - sil.tm().torque_cmd(1) * full(0), 0.0, 1e-12);
}

// ---- the nutation shaper ------------------------------------------------------------------------

// The torque written is shaped with the design for the spin flown: its taps are spaced by the
// fewest ticks m with m beta dt >= pi/2, up to 15 ticks; beyond, it is off. For J1 = J2 = J the
// nutation is beta = H / J exactly (the friction terms cancel in beta^2 = (f^2 + H^2) / J^2 -
// (f / J)^2), so a spin readback picks beta dt = pi/29 (m = 15: on, its first tap a = 1 / (2 (1
// - cos(15 pi/29))) = 0.4730) or pi/31 (m would be 16: off, a step of the law passes at once).
// The step: a gimbal reading that appears while caged, whose loop asks a constant rate from
// then on.
TEST(ComponentShaper, ShapesAtFifteenTicksAndNotBeyond) {
  GYRO_VERIFIES("SHAPE-1");
  GyroComponentConfig<double> c = kSeeker;
  c.min_spin_hz = 1.0;
  const double j = c.pitch_inertia;
  for (const int steps_per_half_turn : {29, 31}) {
    SCOPED_TRACE(steps_per_half_turn);
    const double beta_dt = kPi<double> / steps_per_half_turn;
    Bench b(c);
    ASSERT_TRUE(b.ok);
    b.port.reading.spin_hz = beta_dt / c.tick_s * j / (2 * kPi<double> * c.spin_inertia);
    b.run(40);
    ASSERT_EQ(b.port.torque_written, Vector2<double>::Zero());
    b.port.reading.gimbal_angle_rad = Vector2<double>(2e-3, 0.0);
    ASSERT_EQ(b.step(), Status::kOk);
    const double first = b.port.torque_written(1);
    b.run(35);  // beyond two spacings of 15
    ASSERT_EQ(b.component.mode(), GyroMode::kCaged);
    const double steady = b.port.torque_written(1);
    ASSERT_GT(std::abs(steady), 1e-4);
    if (steps_per_half_turn == 29) {
      EXPECT_NEAR(first / steady, 1 / (2 * (1 - std::cos(15 * beta_dt))), 1e-3) << "shaped, taps 15 ticks apart";
    } else {
      EXPECT_NEAR(first / steady, 1.0, 1e-3) << "not shaped";
    }
  }
}

// Safe mode writes zero torque at once and empties the shaper: leaving it starts from rest.
// Here the fault latches while the cage loop is pulling (an input fault: a request no
// enumerator has, every tick, with the readings still accepted), so the shaper's taps hold
// the cage loop's torques; caged again at a zero reading with the body at rest, the law asks
// for nothing, and nothing from before the fault may be blended in.
TEST(ComponentShaper, LeavingSafeModeStartsFromRest) {
  GYRO_VERIFIES("SHAPE-4");
  GyroComponentConfig<double> c = kSeeker;
  c.min_spin_hz = 10.0;
  const double beta_dt = kPi<double> / 7.5;  // taps 4 ticks apart
  Bench b(c);
  ASSERT_TRUE(b.ok);
  b.port.reading.spin_hz = beta_dt / c.tick_s * c.pitch_inertia / (2 * kPi<double> * c.spin_inertia);
  b.run(20);
  ASSERT_EQ(b.port.torque_written, Vector2<double>::Zero());
  b.port.reading.gimbal_angle_rad = Vector2<double>(2e-3, -1e-3);
  b.run(12);  // beyond two spacings: every tap holds the cage loop's torque
  ASSERT_GT(b.port.torque_written.cwiseAbs().minCoeff(), 1e-5);
  const auto unknown_request = static_cast<ModeRequest>(7);
  for (std::uint32_t k = 0; k < c.input_persistence_ticks && b.component.mode() != GyroMode::kFault; ++k) {
    ASSERT_EQ(b.step(unknown_request), Status::kInputIgnored);
  }
  ASSERT_EQ(b.component.mode(), GyroMode::kFault);
  EXPECT_EQ(b.port.torque_written, Vector2<double>::Zero()) << "safe mode cuts at once";
  b.port.reading.gimbal_angle_rad = Vector2<double>::Zero();
  for (int k = 0; k < 200 && b.component.mode() == GyroMode::kFault; ++k) ASSERT_EQ(b.step(ModeRequest::kCage), Status::kOk);
  ASSERT_EQ(b.component.mode(), GyroMode::kCaged);
  for (int k = 0; k < 12; ++k) {
    EXPECT_EQ(b.port.torque_written, Vector2<double>::Zero()) << k << " ticks after leaving safe mode";
    ASSERT_EQ(b.step(), Status::kOk);
  }
}

}  // namespace component_torque_test
}  // namespace gyro
