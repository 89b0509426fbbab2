#include "sim/contact/bone_level_set.hpp"

#include "sim/mesh/sphere_surface.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

using namespace ligsim::sim;

TEST(BoneLevelSet, DistanceOfASphereWithinTheBand)
{
  const Eigen::Vector3d centre(1.0, -2.0, 0.5);
  const double radius = 4.0;
  const BoneLevelSet grid(sphere_surface(centre, radius, 5), {0.2, 1.0});
  std::mt19937 random(1);
  std::uniform_real_distribution<double> offset(-0.9, 0.9);
  double worst = 0.0;
  double worst_normal = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d direction = Eigen::Vector3d::Random().normalized();
    const double d = offset(random);
    const DistanceSample s = grid.sample(centre + (radius + d) * direction, false);
    worst = std::max(worst, std::abs(s.distance_mm - d));
    worst_normal = std::max(worst_normal, (s.gradient - direction).norm());
  }
  // The triangulated sphere (5 subdivisions, edges about 0.14 mm) lies within 0.0015 mm of the
  // exact one, but its facets tilt the distance's gradient by up to about 0.035 rad near the
  // surface; the grid's float distances and the B-spline add the rest.
  EXPECT_LT(worst, 0.01);
  EXPECT_LT(worst_normal, 0.08);
  EXPECT_LT(grid.distance_bound(centre + (radius + 0.5) * Eigen::Vector3d::UnitX()), 0.5);
  EXPECT_LT(grid.sample(centre, false).distance_mm, 0.0); // deep inside: negative background
}

TEST(BoneLevelSet, DistanceBoundIsALowerBoundUpToItsLimit)
{
  // The contact's cull skips every pair whose bound lies beyond d_hat: the bound must never
  // exceed the sampled distance, inside, within or beyond the band.
  const Eigen::Vector3d centre(0.3, -0.2, 0.1);
  const BoneLevelSet grid(sphere_surface(centre, 3.0, 4), {0.2, 1.0});
  std::mt19937 random(2);
  std::uniform_real_distribution<double> offset(-2.0, 3.0);
  double highest = -INFINITY;
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Vector3d p =
        centre + (3.0 + offset(random)) * Eigen::Vector3d::Random().normalized();
    const double bound = grid.distance_bound(p);
    ASSERT_LE(bound, grid.sample(p, false).distance_mm) << p.transpose();
    highest = std::max(highest, bound);
  }
  EXPECT_LE(highest, grid.bound_limit_mm());
  EXPECT_GE(highest, grid.bound_limit_mm() - 1e-6); // reached beyond the band
  EXPECT_GE(grid.bound_limit_mm(), 1.0 - 1e-6);     // at least the band (float grid)
}

TEST(BoneLevelSet, CacheIsReusedForTheSameSurfaceAndRebuiltOtherwise)
{
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "ligsim_level_set_cache_test";
  std::filesystem::remove_all(dir);
  const auto sphere = sphere_surface({0, 0, 0}, 3.0, 3);
  const auto first = BoneLevelSet::cached(sphere, {0.25, 0.75}, dir / "bone.vdb");
  EXPECT_FALSE(first->figures().reused);
  const auto second = BoneLevelSet::cached(sphere, {0.25, 0.75}, dir / "bone.vdb");
  EXPECT_TRUE(second->figures().reused);
  const Eigen::Vector3d p(3.2, 0.1, 0.3);
  EXPECT_EQ(first->sample(p, false).distance_mm, second->sample(p, false).distance_mm);
  const auto other = BoneLevelSet::cached(sphere, {0.2, 0.75}, dir / "bone.vdb");
  EXPECT_FALSE(other->figures().reused);
  std::filesystem::remove_all(dir);
}

TEST(BoneLevelSet, AnOpenSurfaceGivesAnUnsignedDistance)
{
  // A sphere with a hole at the top: the sign's flood fill leaks through the hole, so both sides
  // of the sheet count as outside. The distance to the sheet stays right, so the barrier still
  // keeps nodes from crossing it (from either side), but nothing is inside any more.
  const ligsim::TriangleSurface closed = sphere_surface({0, 0, 0}, 3.0, 4);
  ligsim::TriangleSurface open;
  open.V = closed.V;
  std::vector<int> kept;
  for (Eigen::Index f = 0; f < closed.F.rows(); ++f)
    if (closed.V(closed.F(f, 0), 2) < 2.5 && closed.V(closed.F(f, 1), 2) < 2.5 &&
        closed.V(closed.F(f, 2), 2) < 2.5)
      kept.push_back(static_cast<int>(f));
  open.F.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i)
    open.F.row(static_cast<Eigen::Index>(i)) = closed.F.row(kept[i]);
  const BoneLevelSet grid(open, {0.2, 1.0});
  EXPECT_NEAR(grid.sample({0, 0, -3.2}, false).distance_mm, 0.2, 0.01); // outside
  EXPECT_NEAR(grid.sample({0, 0, -2.8}, false).distance_mm, 0.2, 0.01); // inside, yet positive
  EXPECT_NEAR(grid.sample({2.8, 0, 0}, false).distance_mm, 0.2, 0.01);  // inside, yet positive
  EXPECT_GT(grid.sample({0, 0, 0}, false).distance_mm, 1.0);            // the centre: far outside
  // The closed sphere keeps its inside.
  EXPECT_NEAR(BoneLevelSet(closed, {0.2, 1.0}).sample({0, 0, -2.8}, false).distance_mm, -0.2, 0.01);
}
