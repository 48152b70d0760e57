// The link's event counters (gyro/link/saturating_count.hpp): one more per event, stopping at the
// largest uint32 instead of wrapping to 0.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

#include "gyro/link/saturating_count.hpp"
#include "support/requirements.hpp"

namespace gyro::link {
namespace {

constexpr std::uint32_t kLargestCount = std::numeric_limits<std::uint32_t>::max();

TEST(LinkCounters, EachEventCountsOneUpToTheLargestValue) {
  GYRO_VERIFIES("LINK-4", "LINK-9");
  EXPECT_EQ(saturating_increment(0u), 1u);
  EXPECT_EQ(saturating_increment(41u), 42u);
  EXPECT_EQ(saturating_increment(kLargestCount - 1u), kLargestCount);
}

TEST(LinkCounters, AtTheLargestValueTheCountStaysThere) {
  GYRO_VERIFIES("LINK-4", "LINK-9");
  EXPECT_EQ(saturating_increment(kLargestCount), kLargestCount) << "a wrapped count would read as no events";
}

}  // namespace
}  // namespace gyro::link
