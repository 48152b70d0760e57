// The texts of the status enumerations (Status, GyroMode, PortStatus): each enumerator has its
// own, and a value no enumerator has (a corrupted telemetry field) is named, never read out of
// bounds.
#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <string>

#include "gyro/component_types.hpp"
#include "gyro/gyro_port.hpp"
#include "gyro/status.hpp"

namespace gyro {
namespace status_text_test {

// Texts of `count` enumerators 0..count-1: each non-empty and distinct from the others.
template <typename E>
void expect_distinct_texts(int count, const char* what) {
  std::set<std::string> seen;
  for (int i = 0; i < count; ++i) {
    const char* s = to_string(static_cast<E>(i));
    ASSERT_NE(s, nullptr) << what << " " << i;
    EXPECT_GT(std::strlen(s), 0U) << what << " " << i;
    EXPECT_TRUE(seen.insert(s).second) << what << " " << i << " repeats \"" << s << "\"";
  }
}

TEST(StatusText, EachStatusHasItsOwnText) {
  expect_distinct_texts<Status>(static_cast<int>(Status::kWrongMode) + 1, "Status");
  EXPECT_STREQ(to_string(Status::kOk), "ok");
  EXPECT_STREQ(to_string(Status::kNumericalOverflow), "result not representable");
  EXPECT_STREQ(to_string(static_cast<Status>(200)), "unknown status");
}

TEST(StatusText, EachModeHasItsOwnText) {
  expect_distinct_texts<GyroMode>(static_cast<int>(GyroMode::kFault) + 1, "GyroMode");
  EXPECT_STREQ(to_string(GyroMode::kIdle), "idle");
  EXPECT_STREQ(to_string(GyroMode::kFault), "fault");
  EXPECT_STREQ(to_string(static_cast<GyroMode>(99)), "unknown");
}

TEST(StatusText, EachPortStatusHasItsOwnText) {
  expect_distinct_texts<PortStatus>(static_cast<int>(PortStatus::kHardwareFault) + 1, "PortStatus");
  EXPECT_STREQ(to_string(PortStatus::kOk), "ok");
  EXPECT_STREQ(to_string(PortStatus::kBusError), "bus error");
  EXPECT_STREQ(to_string(static_cast<PortStatus>(77)), "unknown port status");
}

}  // namespace status_text_test
}  // namespace gyro
