#include "sim/membrane/crack/criterion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace ligsim::membrane {
namespace {

using Vec2 = Eigen::Vector2d;

Vec2 unit_at(double degrees)
{
  return {std::cos(degrees * M_PI / 180.0), std::sin(degrees * M_PI / 180.0)};
}

TEST(TearCriterion, Eq5IsTheNormalStressOfTheRotatedTensor)
{
  std::mt19937 random(1);
  std::uniform_real_distribution<double> value(-5.0, 5.0), angle(-180.0, 180.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d stress(value(random), value(random), value(random));
    Eigen::Matrix2d tensor;
    tensor << stress[0], stress[2], stress[2], stress[1];
    const Vec2 u = unit_at(angle(random));
    // u^T sigma u: the (1, 1) entry of the tensor in a frame whose first axis is u.
    EXPECT_NEAR(normal_stress_along(stress, u), u.dot(tensor * u), 1e-12);
    // The trace is invariant: sigma_u + sigma_{u perp} = sigma_x + sigma_y.
    EXPECT_NEAR(normal_stress_along(stress, u) + normal_stress_along(stress, Vec2(-u.y(), u.x())),
                stress[0] + stress[1], 1e-12);
  }
  const Eigen::Vector3d stress(3.0, -1.0, 0.5);
  EXPECT_DOUBLE_EQ(normal_stress_along(stress, unit_at(0.0)), 3.0);
  EXPECT_NEAR(normal_stress_along(stress, unit_at(90.0)), -1.0, 1e-15);
  EXPECT_NEAR(normal_stress_along(stress, unit_at(45.0)), 0.5 * (3.0 - 1.0) + 0.5, 1e-15);
}

TEST(TearCriterion, Eq6GivesTheFiberThresholdAlongAndTheTransverseAcross)
{
  const TearThresholds thresholds{2.0, 0.2, 1.0, M_PI / 2.0};
  for (double fiber_deg : {0.0, 30.0, 90.0, 135.0}) {
    const Vec2 f = unit_at(fiber_deg);
    EXPECT_NEAR(threshold_along(thresholds, f, f), 2.0, 1e-12);
    EXPECT_NEAR(threshold_along(thresholds, -f, f), 2.0, 1e-12);
    EXPECT_NEAR(threshold_along(thresholds, unit_at(fiber_deg + 90.0), f), 0.2, 1e-12);
    // alpha = 1: linear in the angle, so halfway at 45 degrees.
    EXPECT_NEAR(threshold_along(thresholds, unit_at(fiber_deg + 45.0), f), 1.1, 1e-12);
  }
  // A steeper peak (larger alpha) keeps the threshold near sigma_T further from the fiber.
  const TearThresholds steep{2.0, 0.2, 4.0, M_PI / 2.0};
  const Vec2 f = unit_at(0.0);
  EXPECT_LT(threshold_along(steep, unit_at(30.0), f),
            threshold_along(thresholds, unit_at(30.0), f));
  EXPECT_NEAR(threshold_along(steep, f, f), 2.0, 1e-12);
}

TEST(TearCriterion, Eq4UsesTheStressAcrossTheCrackLine)
{
  // Uniaxial pull along x, fibers along y: a crack along y (along the fibers) is opened by
  // sigma_x, against the transverse threshold; a crack along x is not opened at all.
  const TearThresholds thresholds{1.0, 0.1, 1.0, M_PI / 2.0};
  const Eigen::Vector3d pull(0.05, 0.0, 0.0);
  const Vec2 fiber = unit_at(90.0);
  EXPECT_NEAR(criterion_value(thresholds, pull, fiber, unit_at(90.0)), 0.5, 1e-12);
  EXPECT_NEAR(criterion_value(thresholds, pull, fiber, unit_at(0.0)), 0.0, 1e-12);
  // Fibers along x: the same crack must break them, against sigma_F.
  EXPECT_NEAR(criterion_value(thresholds, pull, unit_at(0.0), unit_at(90.0)), 0.05, 1e-12);
}

TEST(TearCriterion, GateAllowsTurnsUpToThetaP)
{
  const TearThresholds thresholds{1.0, 0.1, 1.0, 30.0 * M_PI / 180.0};
  const Vec2 previous = unit_at(10.0);
  EXPECT_TRUE(within_turn(thresholds, unit_at(39.999), previous));
  EXPECT_TRUE(within_turn(thresholds, unit_at(40.0), previous));
  EXPECT_FALSE(within_turn(thresholds, unit_at(40.01), previous));
  EXPECT_FALSE(within_turn(thresholds, unit_at(190.0), previous));
}

} // namespace
} // namespace ligsim::membrane
