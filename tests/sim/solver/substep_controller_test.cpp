#include "sim/solver/substep_controller.hpp"

#include <gtest/gtest.h>

using namespace ligsim::sim;

TEST(SubstepController, GrowsAfterEasyStepsAndShrinksAfterHardOnes)
{
  SubstepController control(0.25);
  control.accepted(SubstepController::easy_iterations);
  EXPECT_DOUBLE_EQ(control.size(), 0.5);
  control.accepted(SubstepController::easy_iterations + 1); // moderate: kept
  EXPECT_DOUBLE_EQ(control.size(), 0.5);
  control.accepted(SubstepController::hard_iterations + 1);
  EXPECT_DOUBLE_EQ(control.size(), 0.25);
  for (int i = 0; i < 5; ++i)
    control.accepted(1);
  EXPECT_DOUBLE_EQ(control.size(), 1.0); // never beyond the whole load
}

TEST(SubstepController, AFailedStepHalvesWhatWasTried)
{
  SubstepController control(1.0);
  // The output step has 0.3 left: the full size ends it; failing that tries 0.15 next.
  EXPECT_DOUBLE_EQ(control.next_target(0.7, 1.0), 1.0);
  control.rejected(0.3);
  EXPECT_DOUBLE_EQ(control.size(), 0.15);
  EXPECT_DOUBLE_EQ(control.next_target(0.7, 1.0), 0.85);
}

TEST(SubstepController, NeverOvershootsAndMergesASliverOfAStep)
{
  SubstepController control(0.3);
  EXPECT_DOUBLE_EQ(control.next_target(0.0, 1.0), 0.3);
  EXPECT_DOUBLE_EQ(control.next_target(0.0, 0.2), 0.2);
  EXPECT_DOUBLE_EQ(control.next_target(0.0, 0.32), 0.32); // 0.02 left would be a sliver
}
