// The firmware's golden-file check: what counts as stale. Values a few ulp apart (glibc's
// libm differs by CPU) are current; a moved value, a changed mode or a changed word is stale.
#include "golden_file.hpp"

#include <gtest/gtest.h>

#include <string>

namespace {

std::size_t stale_line(const std::string& have, const std::string& want) {
  std::string what;
  return gyro_fw::first_stale_line(have, want, what);
}

TEST(GoldenFile, GivenValuesAFewUlpApartThenTheFileIsCurrent) {
  EXPECT_EQ(stale_line("{5, 2500, -6.2115884603781066e-05, 0.5},\n",
                       "{5, 2500, -6.2115884603781174e-05, 0.5},\n"),
            0U);
  EXPECT_EQ(stale_line("{0, 250, 2, 0u, -0.00264049531f},", "{0, 250, 2, 0u, -0.00264049529f},"), 0U);
}

TEST(GoldenFile, GivenADoubleMovedBeyond1em13RelativeThenStaleAtItsLine) {
  EXPECT_EQ(stale_line("// head\n{1, 0.0016138237845967028},\n", "// head\n{1, 0.0016138237846967028},\n"), 2U);
}

TEST(GoldenFile, GivenAFloatMovedBeyond1em5RelativeThenStale) {
  EXPECT_EQ(stale_line("{0.0606531911f},", "{0.0606591911f},"), 1U);
}

TEST(GoldenFile, GivenAnIntegerFieldOrAWordChangedThenStale) {
  EXPECT_EQ(stale_line("{0, 250, 2, 0u, 0.1f},", "{0, 250, 3, 0u, 0.1f},"), 1U);
  EXPECT_EQ(stale_line("{0, 250, 2, 0u, 0.1f},", "{0, 250, 2, 1u, 0.1f},"), 1U);
  EXPECT_EQ(stale_line("// seeker_slew\n", "// seeker_hold\n"), 1U);
}

TEST(GoldenFile, GivenFloatAgainstDoubleOrATruncatedFileThenStale) {
  EXPECT_EQ(stale_line("{0.5f},", "{0.5},"), 1U);
  EXPECT_EQ(stale_line("{0.5, 0.25},\n", "{0.5, 0.25},\n{1.0},\n"), 2U);
  EXPECT_EQ(stale_line("{0.5, 0.25}", "{0.5 0.25}"), 1U);
}

}  // namespace
