#include "core/arap/arap_stopping_rule.h"

#include <gtest/gtest.h>

#include <optional>

namespace sd {
namespace {

IterationStats iteration(double energy, double step = 1.0, int fallbacks = 0) {
  IterationStats s;
  s.energy = energy;
  s.step = step;
  s.fallbacks = fallbacks;
  return s;
}

const ArapStopTolerances kPlain{1e-6, 1e-5, false};
const ArapStopTolerances kAccelerated{1e-6, 1e-5, true};

TEST(ArapStoppingRule, AStepBelowTheToleranceStopsAtOnce) {
  ArapStoppingRule rule;
  EXPECT_EQ(rule.after_iteration(iteration(1.0, 1e-7), kPlain), StopCode::StepTolerance);
}

TEST(ArapStoppingRule, PlainStopsAtTheFirstSmallDecreaseAndNotBeforeAnEnergyToCompareWith) {
  ArapStoppingRule rule;
  EXPECT_EQ(rule.after_iteration(iteration(1.0), kPlain), std::nullopt);  // nothing to compare with yet
  EXPECT_EQ(rule.after_iteration(iteration(0.5), kPlain), std::nullopt);  // a large decrease
  EXPECT_EQ(rule.after_iteration(iteration(0.5 * (1 - 1e-6)), kPlain), StopCode::ArapEnergy);
}

TEST(ArapStoppingRule, AcceleratedNeedsTwoSmallDecreasesInARowAndFallbacksDoNotCount) {
  ArapStoppingRule rule;
  EXPECT_EQ(rule.after_iteration(iteration(1.0), kAccelerated), std::nullopt);
  EXPECT_EQ(rule.after_iteration(iteration(1.0 - 1e-7), kAccelerated), std::nullopt);          // one
  EXPECT_EQ(rule.after_iteration(iteration(1.0 - 2e-7, 1.0, 1), kAccelerated), std::nullopt);  // a fallback: again
  EXPECT_EQ(rule.after_iteration(iteration(1.0 - 3e-7), kAccelerated), std::nullopt);          // one
  EXPECT_EQ(rule.after_iteration(iteration(1.0 - 4e-7), kAccelerated), StopCode::ArapEnergy);  // two in a row
}

TEST(ArapStoppingRule, AnIncreaseIsNoSmallDecrease) {
  ArapStoppingRule rule;
  EXPECT_EQ(rule.after_iteration(iteration(1.0), kPlain), std::nullopt);
  EXPECT_EQ(rule.after_iteration(iteration(1.0 + 1e-9), kPlain), std::nullopt);
}

TEST(ArapStoppingRule, ResetForgetsTheLastEnergy) {
  ArapStoppingRule rule;
  EXPECT_EQ(rule.after_iteration(iteration(1.0), kPlain), std::nullopt);
  rule.reset();  // e.g. new targets: the next energy is not comparable
  EXPECT_EQ(rule.after_iteration(iteration(1.0), kPlain), std::nullopt);
  EXPECT_EQ(rule.after_iteration(iteration(1.0), kPlain), StopCode::ArapEnergy);  // no decrease at all is small
}

}  // namespace
}  // namespace sd
