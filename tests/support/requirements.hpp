// The requirements a test verifies (docs/requirements.md), named at the top of the test:
//
//   TEST(ModeLogic, CagedUncagesOnRequestAndStartsTheEstimator) {
//     GYRO_VERIFIES("MODE-1", "EST-1");
//     ...
//
// The run reports them twice: as the GoogleTest property "requirements" (--gtest_output=xml)
// and as the line "[ VERIFIES ] MODE-1 EST-1" of the test's output, which ctest's JUnit file
// carries (it keeps the start of a passing test's output: name them first). scripts/trace.py
// reads that file, checks every identifier against docs/requirements.md and writes
// docs/traceability.md.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <initializer_list>
#include <string>

namespace gyro::test {

inline void verifies(std::initializer_list<const char*> ids) {
  std::string line;
  for (const char* id : ids) {
    if (!line.empty()) line += ' ';
    line += id;
  }
  ::testing::Test::RecordProperty("requirements", line);
  std::printf("[ VERIFIES ] %s\n", line.c_str());
  std::fflush(stdout);
}

}  // namespace gyro::test

#define GYRO_VERIFIES(...) ::gyro::test::verifies({__VA_ARGS__})
