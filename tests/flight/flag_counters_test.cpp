// The flag counters (gyro/flag_counters.hpp): one count per raised flag, saturating.
#include <gtest/gtest.h>

#include <limits>

#include "gyro/flag_counters.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace flag_counters_test {

TEST(FlagCounters, EachSingleFlagHasItsOwnBitNumber) {
  GYRO_VERIFIES("TLM-2");
  for (int bit = 0; bit < 32; ++bit) {
    EXPECT_EQ(flag_bit(1u << static_cast<unsigned>(bit)), static_cast<std::size_t>(bit));
  }
}

TEST(FlagCounters, EachRaisedFlagCountsOnce) {
  GYRO_VERIFIES("TLM-2");
  FlagCounts c{};
  count_flags(c, kPickoffStale | kNavInvalid | kRequestRefused);
  count_flags(c, kNavInvalid);
  for (int bit = 0; bit < kComponentFlagCount; ++bit) {
    const std::uint32_t want = bit == 4 ? 1u : bit == 10 ? 2u : bit == 20 ? 1u : 0u;
    EXPECT_EQ(c[static_cast<std::size_t>(bit)], want) << flag_name(bit);
  }
}

TEST(FlagCounters, EveryFlagAtOnceCountsEachOnce) {
  GYRO_VERIFIES("TLM-2");
  FlagCounts c{};
  count_flags(c, 0xFFFFFFFFu);
  for (const std::uint32_t n : c) EXPECT_EQ(n, 1u);
}

TEST(FlagCounters, ACleanTickCountsNothing) {
  GYRO_VERIFIES("TLM-2");
  FlagCounts c{};
  c.fill(7u);
  const FlagCounts before = c;
  count_flags(c, 0u);
  EXPECT_EQ(c, before);
  count_flags(c, 1u << static_cast<unsigned>(kComponentFlagCount));
  EXPECT_EQ(c, before) << "no counter beyond the flags";
}

TEST(FlagCounters, ACountStopsAtItsLargestValue) {
  GYRO_VERIFIES("TLM-2");
  FlagCounts c{};
  c[6] = std::numeric_limits<std::uint32_t>::max() - 1u;
  count_flags(c, kResidualFault);
  EXPECT_EQ(c[6], std::numeric_limits<std::uint32_t>::max());
  count_flags(c, kResidualFault | kGimbalLimit);
  EXPECT_EQ(c[6], std::numeric_limits<std::uint32_t>::max()) << "saturated, never wrapped";
  EXPECT_EQ(c[0], 1u);
}

}  // namespace flag_counters_test
}  // namespace gyro
