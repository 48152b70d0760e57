// The C API's SIL run (gyro_sil_run_*): gyro_sil's run, column for column, and every failure a
// status with a message and, where there is one, the scenario field: nothing thrown into C.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "gyro/gyro.h"
#include "sil_columns.hpp"

namespace gyro {
namespace {

const std::string kSeekerSlew = std::string(GYRO_SOURCE_DIR) + "/scenarios/seeker_slew.json";

TEST(CApiSil, GivenTheSeekerSlewThenTheColumnsAreGyroSilsRun) {
  gyro_sil_options o{"double", 200, 0};
  gyro_sil_result* run = nullptr;
  gyro_sil_error e{};
  ASSERT_EQ(gyro_sil_run_file(kSeekerSlew.c_str(), &o, &run, &e), GYRO_OK) << e.message;
  sil::ColumnRecorder expected;
  const sil::Scenario s = sil::prepare_scenario(kSeekerSlew, "", kSeekerSlew, sil::Precision::kDouble, 200);
  sil::RunOptions options;
  options.progress = false;
  const sil::RunSummary sum = sil::run_scenario(s, expected, options);
  ASSERT_EQ(gyro_sil_columns(run), expected.columns().size());
  ASSERT_EQ(gyro_sil_rows(run), 201u);
  for (std::size_t i = 0; i < expected.columns().size(); ++i) {
    const sil::SilColumn& c = expected.columns()[i];
    EXPECT_EQ(std::string(gyro_sil_column_name(run, i)), std::string(c.name));
    EXPECT_EQ(gyro_sil_column_kind(run, i), static_cast<int>(c.kind));
    for (std::size_t row = 0; row < 201; row += 50) {
      switch (c.kind) {
        case sil::SilColumn::Kind::kNumbers: EXPECT_EQ(gyro_sil_numbers(run, i)[row], c.numbers[row]) << c.name; break;
        case sil::SilColumn::Kind::kIntegers: EXPECT_EQ(gyro_sil_integers(run, i)[row], c.integers[row]) << c.name; break;
        case sil::SilColumn::Kind::kNames: EXPECT_STREQ(gyro_sil_name(run, i, row), c.names[row]) << c.name; break;
      }
    }
  }
  gyro_sil_summary summary{};
  gyro_sil_get_summary(run, &summary);
  EXPECT_EQ(summary.flags_seen, sum.flags_seen);
  EXPECT_STREQ(summary.final_mode, enum_name_or(sum.final_mode, "unknown"));
  EXPECT_EQ(summary.max_abs_gimbal_rad, sum.max_abs_gimbal_rad);
  for (std::size_t b = 0; b < gyro_component_flag_count(); ++b) EXPECT_EQ(gyro_sil_counter(run, b), sum.counters[b]);
  gyro_sil_free(run);
}

TEST(CApiSil, GivenEveryKindOfFailureThenAStatusAndAMessage) {
  gyro_sil_result* run = nullptr;
  gyro_sil_error e{};
  EXPECT_EQ(gyro_sil_run_file("/nonexistent/scenario.json", nullptr, &run, &e), GYRO_SCENARIO_ERROR);
  EXPECT_NE(std::string(e.message).find("/nonexistent/scenario.json"), std::string::npos) << e.message;
  EXPECT_EQ(gyro_sil_run_file(GYRO_SOURCE_DIR, nullptr, &run, &e), GYRO_SCENARIO_ERROR);  // a directory
  const std::string bad = std::string(GYRO_SOURCE_DIR) + "/tests/data/bad_scenarios/non_physical_inertia.json";
  EXPECT_EQ(gyro_sil_run_file(bad.c_str(), nullptr, &run, &e), GYRO_SCENARIO_ERROR);
  EXPECT_GT(std::string(e.field).size(), 0u) << e.message;
  EXPECT_EQ(gyro_sil_run_text("{\"run\": 1}", nullptr, &run, &e), GYRO_SCENARIO_ERROR);
  EXPECT_EQ(gyro_sil_run_text(nullptr, nullptr, &run, nullptr), GYRO_NULL_ARGUMENT);
  EXPECT_EQ(gyro_sil_run_file(kSeekerSlew.c_str(), nullptr, nullptr, &e), GYRO_NULL_ARGUMENT);
  gyro_sil_options o{nullptr, 1000000, 1000};
  EXPECT_EQ(gyro_sil_run_file(kSeekerSlew.c_str(), &o, &run, &e), GYRO_RUN_ERROR);
  EXPECT_EQ(std::string(e.message).rfind("max_output_bytes: the run's output could take up to ", 0), 0u) << e.message;
  EXPECT_EQ(run, nullptr);
  // A message longer than the buffer is cut, terminated.
  const std::string long_text(2000, ' ');
  EXPECT_EQ(gyro_sil_run_text(long_text.c_str(), nullptr, &run, &e), GYRO_SCENARIO_ERROR);
  EXPECT_LT(std::string(e.message).size(), sizeof e.message);
  EXPECT_EQ(gyro_sil_rows(nullptr), 0u);
  EXPECT_EQ(gyro_sil_column_kind(nullptr, 0), -1);
  gyro_sil_free(nullptr);
}

}  // namespace
}  // namespace gyro
