// main() of the suite's GoogleTest executables: GoogleTest's, plus the line
// "[ SOURCE   ] tests/flight/mode_logic_test.cpp" as each test starts, naming the file that
// defines it. ctest runs each test alone and its JUnit file keeps the start of a passing test's
// output, so scripts/trace.py learns from it which tests are the flight code's (every one of
// which must name a requirement, tests/support/requirements.hpp).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>

namespace {

class SourceLine final : public ::testing::EmptyTestEventListener {
 public:
  void OnTestStart(const ::testing::TestInfo& info) override {
    // Relative to the repository (the build passes absolute paths).
    const char* file = info.file();
    const std::size_t root = std::strlen(GYRO_SOURCE_DIR);
    if (std::strncmp(file, GYRO_SOURCE_DIR, root) == 0) file += root;
    std::printf("[ SOURCE   ] %s\n", file);
    std::fflush(stdout);
  }
};

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ::testing::UnitTest::GetInstance()->listeners().Append(new SourceLine);  // GoogleTest owns it
  return RUN_ALL_TESTS();
}
