// The corners of the validity envelope (docs/model-validity.md has the whole grid): the
// component closed around the gimbal plant with ideal pickoffs, the seeker example at gimbal
// cone up to 20 deg, body pitch/yaw rates up to 1 rad/s and roll up to 10 rad/s; and beyond it,
// a body turning faster than the torquer can follow.
#include <gtest/gtest.h>

#include <ostream>
#include <string>

#include "support/requirements.hpp"
#include "validity_envelope.hpp"

namespace gyro::validity {
namespace {

constexpr double kResidualGoal = 2e-4;  // rad, from the uncaging request on
constexpr double kSlewGoal = 0.01;      // of the command
constexpr double kWindow = 0.5;  // s of steady slew measured (the tool: 1 s)

struct Corner {
  double cone_deg, turn_rad_s, roll_rad_s;
};

void PrintTo(const Corner& c, std::ostream* os) {
  *os << "cone " << c.cone_deg << " deg, turn " << c.turn_rad_s << " rad/s, roll " << c.roll_rad_s << " rad/s";
}

class EnvelopeCorner : public ::testing::TestWithParam<Corner> {};

TEST_P(EnvelopeCorner, GIVEN_the_gimbal_plant_WHEN_slewing_along_the_cone_THEN_no_fault_and_residual_and_slew_within_goal) {
  GYRO_VERIFIES("EST-6");
  const Corner c = GetParam();
  const Case k{c.cone_deg * kDeg, c.turn_rad_s, c.roll_rad_s, c.cone_deg > 0 ? 0.3 : 0.0};
  const ClosedLoopResult r = run_closed_loop(k, kWindow);
  ASSERT_TRUE(r.ok);
  EXPECT_FALSE(r.residual_fault);
  EXPECT_FALSE(r.fault);
  EXPECT_EQ(r.contact_ticks, 0u);
  EXPECT_EQ(r.flags_seen & (kGimbalLimit | kTorquerSaturated), 0u);
  EXPECT_LE(r.worst_residual_window_rad, kResidualGoal);
  EXPECT_LE(r.worst_residual_rad, kResidualGoal);  // from the uncaging request on, transients included
  EXPECT_LE(r.slew_error_rel, kSlewGoal);
  // The window saw the slew: the spin axis on its cone, a command worth measuring.
  EXPECT_NEAR(0.5 * (r.cone_min_window_rad + r.cone_max_window_rad), c.cone_deg * kDeg, 0.02);
  if (c.cone_deg > 0 || c.turn_rad_s > 0) {
    EXPECT_GE(r.min_command_rad_s, kMinCommand_rad_s);
  }
}

// "cone20_turn0p5_roll10"
std::string corner_name(const ::testing::TestParamInfo<Corner>& info) {
  const Corner& c = info.param;
  return "cone" + name_number(c.cone_deg) + "_turn" + name_number(c.turn_rad_s) + "_roll" + name_number(c.roll_rad_s);
}

INSTANTIATE_TEST_SUITE_P(DoneWhenCorners, EnvelopeCorner,
                         ::testing::Values(Corner{0, 1, 0}, Corner{0, 1, 10}, Corner{20, 0, 0}, Corner{20, 0, 10},
                                           Corner{20, 1, 0}, Corner{20, 1, 10}, Corner{10, 1, 5},
                                           Corner{20, 0.5, 10}),
                         corner_name);

TEST(EnvelopeBeyond, GIVEN_a_body_turning_faster_than_the_torquer_follows_WHEN_free_THEN_the_gimbal_limit_is_flagged_before_the_stop) {
  GYRO_VERIFIES("EST-5");
  // 2 rad/s across body x (1.41 rad/s on pitch and on yaw) against 1 rad/s per axis of slew
  // limit and 1.33 rad/s of torquer authority: the body drives the gimbal onto its stop.
  const ClosedLoopResult r = run_closed_loop(Case{0.0, 2.0, 0.0, 0.0}, kWindow);
  ASSERT_TRUE(r.ok);
  ASSERT_GT(r.first_contact_tick, 0u);
  ASSERT_GT(r.first_limit_tick, 0u);
  EXPECT_LT(r.first_limit_tick, r.first_contact_tick);
  // No silent fault: safe mode comes after the flag, with the flag raised before it.
  ASSERT_GT(r.first_fault_tick, 0u);
  EXPECT_GT(r.first_fault_tick, r.first_limit_tick);
  EXPECT_NE(r.flags_before_fault & kGimbalLimit, 0u);
  // What it cannot fly is flagged from the start: the path asks more than the rate limit.
  EXPECT_NE(r.flags_before_fault & kSlewRateLimited, 0u);
}

TEST(EnvelopeOpenLoop, GIVEN_the_same_torques_WHEN_the_body_turns_and_rolls_THEN_the_corrected_model_follows_the_gimbal_and_the_report_s_does_not) {
  GYRO_VERIFIES("STUB-1", "MODEL-5");
  const OpenLoopResult r = run_open_loop(Case{20 * kDeg, 1.0, 10.0, 0.3});
  ASSERT_TRUE(r.ok);
  EXPECT_FALSE(r.plant_contact);
  EXPECT_LE(r.corrected_error_rad, 3e-4);
  EXPECT_GT(r.report_error_rad, 0.1);
}

}  // namespace
}  // namespace gyro::validity
