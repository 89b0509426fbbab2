#include "sim/membrane/crack/direction_search.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace ligsim::membrane {
namespace {

using Vec2 = Eigen::Vector2d;

constexpr double kDegree = M_PI / 180.0;

Vec2 unit_at(double radians)
{
  return {std::cos(radians), std::sin(radians)};
}

/// The angle between two undirected lines, degrees in [0, 90].
double line_angle_deg(const Vec2& a, const Vec2& b)
{
  return std::acos(std::min(1.0, std::abs(a.normalized().dot(b.normalized())))) / kDegree;
}

TEST(TearDirection, IsotropicCriterionIsTheMaximumPrincipalStressCriterion)
{
  const TearThresholds isotropic{0.7, 0.7, 1.0, 90.0 * kDegree};
  std::mt19937 random(11);
  std::uniform_real_distribution<double> value(-10.0, 10.0), angle(-M_PI, M_PI);
  for (int trial = 0; trial < 1000; ++trial) {
    const Eigen::Vector3d stress(value(random), value(random), value(random));
    const Vec2 fiber = unit_at(angle(random));
    const auto [largest, principal] = largest_principal_stress(stress);
    // The crack runs perpendicular to the largest principal stress, with c = sigma_1 / threshold.
    for (const std::optional<Vec2>& previous :
         {std::optional<Vec2>(), std::optional<Vec2>(unit_at(angle(random)))}) {
      const TearDirection best = best_tear_direction(isotropic, stress, fiber, previous);
      EXPECT_NEAR(best.direction.dot(principal), 0.0, 1e-8) << "trial " << trial;
      EXPECT_NEAR(best.value, largest / 0.7, 1e-10 * (1.0 + std::abs(largest)));
      if (previous) {
        EXPECT_GE(best.direction.dot(*previous), -1e-12);
      }
    }
  }
}

TEST(TearDirection, PrincipalStressAgreesWithAnEigendecomposition)
{
  const Eigen::Vector3d stress(2.0, -1.0, 1.5);
  Eigen::Matrix2d tensor;
  tensor << 2.0, 1.5, 1.5, -1.0;
  const auto [largest, direction] = largest_principal_stress(stress);
  EXPECT_NEAR((tensor * direction - largest * direction).norm(), 0.0, 1e-12);
  EXPECT_NEAR(largest, 0.5 + std::hypot(1.5, 1.5), 1e-12);
}

TEST(TearDirection, UniaxialPullTearsExactlyAlong45DegreeFibers)
{
  // sigma_F = 10 sigma_T and alpha = 1: under a pull along x the criterion peaks on the fibers.
  const TearThresholds thresholds{1.0, 0.1, 1.0, 90.0 * kDegree};
  const Eigen::Vector3d pull(1.0, 0.0, 0.0);
  const TearDirection best = best_tear_direction(thresholds, pull, unit_at(45.0 * kDegree), {});
  EXPECT_LT(line_angle_deg(best.direction, unit_at(45.0 * kDegree)), 1e-9);
  EXPECT_NEAR(best.value, 0.5 / 0.1, 1e-9);
  // Fibers across the pull: the tear runs along them, perpendicular to the pull.
  const TearDirection across = best_tear_direction(thresholds, pull, unit_at(90.0 * kDegree), {});
  EXPECT_LT(line_angle_deg(across.direction, Vec2::UnitY()), 1e-9);
  EXPECT_NEAR(across.value, 1.0 / 0.1, 1e-9);
}

TEST(TearDirection, NeverBelowAFineExhaustiveSearch)
{
  std::mt19937 random(3);
  std::uniform_real_distribution<double> value(-2.0, 2.0), angle(-M_PI, M_PI), unit(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const TearThresholds thresholds{0.2 + 2.0 * unit(random), 0.2 + 2.0 * unit(random),
                                    0.2 + 3.0 * unit(random),
                                    (10.0 + 170.0 * unit(random)) * kDegree};
    const Eigen::Vector3d stress(value(random), value(random), value(random));
    const Vec2 fiber = unit_at(angle(random));
    const Vec2 previous = unit_at(angle(random));
    const TearDirection best = best_tear_direction(thresholds, stress, fiber, previous);
    ASSERT_TRUE(within_turn(thresholds, best.direction, previous));
    EXPECT_NEAR(best.value, criterion_value(thresholds, stress, fiber, best.direction), 1e-12);
    double fine = -1e300;
    for (int i = -20000; i <= 20000; ++i) {
      const double turn = thresholds.max_turn_rad * i / 20000.0;
      const Vec2 d = unit_at(std::atan2(previous.y(), previous.x()) + turn);
      fine = std::max(fine, criterion_value(thresholds, stress, fiber, d));
    }
    EXPECT_GE(best.value, fine - 1e-9 * (1.0 + std::abs(fine))) << "trial " << trial;
  }
}

TEST(TearDirection, StaysWithinThetaPOfThePreviousDirection)
{
  // Fibers along y favour a vertical tear, but the last advance went along x and may turn
  // by at most 30 degrees: the best admissible direction is on the cone's edge.
  const TearThresholds thresholds{1.0, 0.1, 1.0, 30.0 * kDegree};
  const Eigen::Vector3d pull(1.0, 0.0, 0.0);
  const TearDirection best =
      best_tear_direction(thresholds, pull, Vec2::UnitY(), Vec2(Vec2::UnitX()));
  EXPECT_NEAR(std::abs(std::atan2(best.direction.y(), best.direction.x())), 30.0 * kDegree, 1e-9);
}

} // namespace
} // namespace ligsim::membrane
