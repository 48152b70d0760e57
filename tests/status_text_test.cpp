// The texts of Status: each enumerator has its own, and a value no enumerator has (a corrupted
// field) is named, never read out of bounds. GyroMode and PortStatus are named by their
// enum_names tables (config_fields_test, EnumNames).
#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <string>

#include "gyro/status.hpp"
#include "support/requirements.hpp"

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
  GYRO_VERIFIES("TLM-5");
  expect_distinct_texts<Status>(static_cast<int>(Status::kInputIgnored) + 1, "Status");
  EXPECT_STREQ(to_string(Status::kOk), "ok");
  EXPECT_STREQ(to_string(Status::kNumericalOverflow), "result not representable");
  EXPECT_STREQ(to_string(static_cast<Status>(200)), "unknown status");
}

}  // namespace status_text_test
}  // namespace gyro
