// The mode logic (gyro/mode_logic.hpp): each mode's transitions for each request, refusals
// flagged, safe mode latched by a fault and left by caging only.
#include <gtest/gtest.h>

#include "gyro/mode_logic.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace mode_logic_test {

constexpr std::uint32_t kSettle = 3;
constexpr std::uint32_t kRefused = kRequestRefused;

ModeTransition next(GyroMode mode, ModeRequest request, bool measurable = true, bool fault = false,
                    std::uint32_t settled = 0) {
  return next_mode(mode, ModeConditions{request, measurable, fault, settled, kSettle});
}

TEST(ModeLogic, CagedUncagesOnRequestAndStartsTheEstimator) {
  GYRO_VERIFIES("MODE-1", "EST-1");
  const ModeTransition t = next(GyroMode::kCaged, ModeRequest::kUncage, true, false, 7);
  EXPECT_EQ(t.mode, GyroMode::kUncaging);
  EXPECT_EQ(t.estimator, EstimatorAction::kStart);
  EXPECT_EQ(t.settle_ticks, 0u) << "a new uncaging counts from zero";
  EXPECT_EQ(t.flags, 0u);
}

TEST(ModeLogic, UncagingWithoutAMeasurementIsRefused) {
  GYRO_VERIFIES("MODE-1");
  const ModeTransition t = next(GyroMode::kCaged, ModeRequest::kUncage, false);
  EXPECT_EQ(t.mode, GyroMode::kCaged);
  EXPECT_EQ(t.estimator, EstimatorAction::kKeep);
  EXPECT_EQ(t.flags, kRefused);
}

TEST(ModeLogic, UncagingFreesTheGyroAfterTheSettleTicks) {
  GYRO_VERIFIES("MODE-2");
  ModeTransition t{GyroMode::kUncaging, 0, EstimatorAction::kKeep, 0};
  for (std::uint32_t k = 1; k < kSettle; ++k) {
    t = next(t.mode, ModeRequest::kNone, false, false, t.settle_ticks);
    EXPECT_EQ(t.mode, GyroMode::kUncaging) << k;
  }
  t = next(t.mode, ModeRequest::kNone, false, false, t.settle_ticks);
  EXPECT_EQ(t.mode, GyroMode::kFree);
  EXPECT_EQ(t.settle_ticks, kSettle);
}

TEST(ModeLogic, ACageRequestCagesFromUncagingAndFree) {
  GYRO_VERIFIES("MODE-3");
  EXPECT_EQ(next(GyroMode::kUncaging, ModeRequest::kCage).mode, GyroMode::kCaged);
  EXPECT_EQ(next(GyroMode::kFree, ModeRequest::kCage).mode, GyroMode::kCaged);
  EXPECT_EQ(next(GyroMode::kFree, ModeRequest::kNone).mode, GyroMode::kFree);
  EXPECT_EQ(next(GyroMode::kFree, ModeRequest::kUncage).mode, GyroMode::kFree);
  EXPECT_EQ(next(GyroMode::kCaged, ModeRequest::kCage).mode, GyroMode::kCaged);
}

TEST(ModeLogic, AFaultLatchesSafeModeFromEveryMode) {
  GYRO_VERIFIES("MODE-4");
  for (const GyroMode m : {GyroMode::kCaged, GyroMode::kUncaging, GyroMode::kFree, GyroMode::kFault}) {
    const ModeTransition t = next(m, ModeRequest::kNone, true, true);
    EXPECT_EQ(t.mode, GyroMode::kFault);
    EXPECT_EQ(t.flags, 0u);
  }
}

TEST(ModeLogic, ARequestAsAFaultLatchesIsRefused) {
  GYRO_VERIFIES("MODE-5");
  EXPECT_EQ(next(GyroMode::kFree, ModeRequest::kCage, true, true).flags, kRefused);
  EXPECT_EQ(next(GyroMode::kFault, ModeRequest::kCage, true, true).mode, GyroMode::kFault);
}

TEST(ModeLogic, SafeModeIsLeftByCagingOnly) {
  GYRO_VERIFIES("MODE-5");
  const ModeTransition cage = next(GyroMode::kFault, ModeRequest::kCage);
  EXPECT_EQ(cage.mode, GyroMode::kCaged);
  EXPECT_EQ(cage.estimator, EstimatorAction::kRestart);
  const ModeTransition uncage = next(GyroMode::kFault, ModeRequest::kUncage);
  EXPECT_EQ(uncage.mode, GyroMode::kFault);
  EXPECT_EQ(uncage.flags, kRefused);
  EXPECT_EQ(next(GyroMode::kFault, ModeRequest::kNone).mode, GyroMode::kFault);
}

TEST(ModeLogic, IdleStaysIdle) {
  GYRO_VERIFIES("MODE-7");
  EXPECT_EQ(next(GyroMode::kIdle, ModeRequest::kUncage).mode, GyroMode::kIdle);
}

}  // namespace mode_logic_test
}  // namespace gyro
