// The promise of the stop protection on a small grid of docs/stop-protection.md's cases (the
// runs are the tool's, tools/stop_envelope.hpp): against the gimbal plant's truth, no case
// within the torquer's authority touches the stop, in any mode, and every case beyond it that
// does was flagged stop_beyond_authority before the contact.
#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

#include "stop_envelope.hpp"

namespace gyro::stop_envelope {
namespace {

struct Grid {
  const char* gyro;
  Mode mode;
};

void PrintTo(const Grid& g, std::ostream* os) { *os << g.gyro << ", " << mode_key(g.mode); }

const Gyro& gyro_named(const std::string& name) {
  static const Gyro seeker = seeker_gyro(GYRO_SOURCE_DIR "/scenarios/seeker_slew.json");
  static const Gyro report = report_gyro(GYRO_SOURCE_DIR "/scenarios/report_sample.json");
  return name == "report" ? report : seeker;
}

std::string describe(const Gyro& g, const Case& k, const Authority& a, const Result& r) {
  char b[512];
  std::snprintf(b, sizeof b,
                "%s %s, turn %g rad/s %s, roll %g rad/s, cone %g deg (demand %.2f): contact at %.3f s (%llu ticks), "
                "beyond_authority at %.3f s, stop_protect at %.3f s, safe mode at %.3f s; flags before contact: %s",
                g.name.c_str(), mode_key(k.mode), k.turn_rad_s, direction_key(k.direction), k.roll_rad_s, k.cone_deg,
                a.demand, r.first_contact_s, static_cast<unsigned long long>(r.contact_ticks), r.first_beyond_s,
                r.first_protect_s, r.first_fault_s, flag_names(r.flags_at_contact).c_str());
  return b;
}

class StopEnvelope : public ::testing::TestWithParam<Grid> {};

TEST_P(StopEnvelope, GIVEN_a_body_turning_the_gimbal_out_THEN_no_contact_within_authority_and_warned_beyond) {
  const Gyro& g = gyro_named(GetParam().gyro);
  const bool seeker = g.name == "seeker";
  // Within authority, near it, and beyond it (docs/stop-protection.md: the seeker holds about
  // 0.54 rad/s about one axis, the report's gyro its 0.17 rad/s slew-rate limit).
  const std::vector<double> turns = seeker ? std::vector<double>{0.35, 0.5, 1.0} : std::vector<double>{0.15, 0.2, 0.5};
  int within = 0, beyond = 0, beyond_contacts = 0;
  for (double b : turns) {
    for (Direction d : {Direction::kPitch, Direction::kDiagonal, Direction::kRotating}) {
      for (double p : {0.0, 10.0}) {
        for (double c : {0.0, 20.0}) {
          const Case k{b, d, p, c, GetParam().mode};
          const Authority a = authority(g, k);
          const Result r = run_case(g, k);
          ASSERT_TRUE(r.ok) << r.error;
          EXPECT_TRUE(r.reached_mode) << describe(g, k, a, r);  // the mode under test was flown
          if (a.demand <= 1.0) {
            ++within;
            EXPECT_EQ(r.contact_ticks, 0u) << describe(g, k, a, r);
          } else {
            ++beyond;
            if (r.contact_ticks > 0) {
              ++beyond_contacts;
              EXPECT_TRUE(r.first_beyond_s >= 0.0 && r.first_beyond_s < r.first_contact_s) << describe(g, k, a, r);
            }
          }
        }
      }
    }
  }
  // The grid holds both kinds, and the measurement sees the beyond-authority cases reach it.
  EXPECT_GT(within, 0);
  EXPECT_GT(beyond, 0);
  EXPECT_GT(beyond_contacts, 0);
}

std::string grid_name(const ::testing::TestParamInfo<Grid>& info) {
  return std::string(info.param.gyro) + "_" + mode_key(info.param.mode);
}

INSTANTIATE_TEST_SUITE_P(Modes, StopEnvelope,
                         ::testing::Values(Grid{"seeker", Mode::kFreeZero}, Grid{"seeker", Mode::kFreeInward},
                                           Grid{"seeker", Mode::kFreeOutward}, Grid{"seeker", Mode::kUncaging},
                                           Grid{"seeker", Mode::kCaged}, Grid{"report", Mode::kFreeZero},
                                           Grid{"report", Mode::kFreeInward}, Grid{"report", Mode::kFreeOutward},
                                           Grid{"report", Mode::kUncaging}, Grid{"report", Mode::kCaged}),
                         grid_name);

}  // namespace
}  // namespace gyro::stop_envelope
