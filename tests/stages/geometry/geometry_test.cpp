#include "stages/geometry/interpolate.hpp"
#include "stages/geometry/polyline.hpp"
#include "stages/geometry/surface_query.hpp"
#include "stages/geometry/surface_topology.hpp"
#include "stages/synthetic/shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ligsim;

TEST(SyntheticShapes, AreClosedOutwardManifoldsWithTheRightVolume)
{
  constexpr double pi = 3.14159265358979323846;
  const auto cylinder = synthetic::cylinder(3.0, 30.0, 96);
  const auto torus = synthetic::torus_tube(20.0, 3.0, 120.0, 64);
  const auto band = synthetic::ligament_band();
  for (const TriangleSurface* s :
       {&cylinder.surface, &torus.surface, &band.surface, &*band.femur, &*band.tibia}) {
    const TopologyReport report = check_topology(*s);
    EXPECT_TRUE(report.closed_manifold());
    EXPECT_EQ(report.degenerate_triangles, 0);
    EXPECT_GT(signed_volume(*s), 0.0);
  }
  // A 96-gon prism holds (96/2pi) sin(2pi/96) of the circle's area.
  const double polygon = 96.0 / (2 * pi) * std::sin(2 * pi / 96);
  EXPECT_NEAR(signed_volume(cylinder.surface), pi * 9.0 * 30.0 * polygon, 1e-6);
  EXPECT_NEAR(signed_volume(synthetic::box({0, 0, 0}, {1, 2, 3})), 6.0, 1e-12);
}

TEST(SurfaceTopology, ReportsHolesWithCountAndLocation)
{
  TriangleSurface open = synthetic::box({0, 0, 0}, {1, 1, 1});
  open.F.conservativeResize(open.F.rows() - 1, 3); // drop one triangle of the x = hi face
  const TopologyReport report = check_topology(open);
  EXPECT_EQ(report.boundary_edges, 3);
  EXPECT_FALSE(report.closed_manifold());
  EXPECT_DOUBLE_EQ(report.boundary_min.x(), 1.0);
  EXPECT_DOUBLE_EQ(report.boundary_max.x(), 1.0);
}

TEST(SurfaceQuery, DistanceInsideAndRayHitsOnABox)
{
  const SurfaceQuery query(synthetic::box({0, 0, 0}, {2, 4, 6}));
  EXPECT_NEAR(query.distance({1.0, 1.5, 3.0}), 1.0, 1e-12);
  EXPECT_NEAR(query.distance({3.0, 2.0, 3.0}), 1.0, 1e-12);
  EXPECT_TRUE(query.inside({1.0, 1.5, 3.0}));
  EXPECT_FALSE(query.inside({3.0, 2.0, 3.0}));
  const auto hit = query.first_hit({1.0, 2.0, 3.0}, {0.0, 0.0, 1.0});
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->z(), 6.0, 1e-12);
  EXPECT_EQ(query.ray_hits({1.0, 2.0, -1.0}, {1e-9, 2e-9, 1.0}).size(), 2u);
}

TEST(SurfaceQuery, InsideHoldsOnTheBoxsSymmetryPlanes)
{
  // Points with two equal coordinates in a cube whose faces' diagonals lie in the planes
  // y = z, x = y and x = z: a ray along any of them meets the box's edges.
  const SurfaceQuery query(synthetic::box({-5, -5, -5}, {20, 10, 10}));
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(0, 2, 2),
                                   Eigen::Vector3d(3, 3, 0), Eigen::Vector3d(4, 0, 4)})
    EXPECT_TRUE(query.inside(p)) << p.transpose();
  EXPECT_FALSE(query.inside({21, 1, 1}));
}

TEST(SurfaceQuery, FindsSelfIntersections)
{
  TriangleSurface two = synthetic::box({0, 0, 0}, {2, 2, 2});
  const TriangleSurface other = synthetic::box({1, 1, 1}, {3, 3, 3});
  EXPECT_TRUE(self_intersections(two).empty());
  two.V.conservativeResize(16, 3);
  two.V.bottomRows(8) = other.V;
  two.F.conservativeResize(24, 3);
  two.F.bottomRows(12) = other.F.array() + 8;
  EXPECT_FALSE(self_intersections(two).empty());
}

TEST(Polyline, ProjectsOntoSegmentsWithInterpolatedTangent)
{
  Points p(3, 3), t(3, 3);
  p << 0, 0, 0, 1, 0, 0, 1, 1, 0;
  t << 1, 0, 0, 1, 0, 0, 0, 1, 0;
  const Polyline line(p, t);
  const auto a = line.project({0.5, 0.3, 0.0});
  EXPECT_NEAR(a.distance, 0.3, 1e-12);
  EXPECT_NEAR(a.arc_length, 0.5, 1e-12);
  const auto b = line.project({2.0, 0.5, 0.0});
  EXPECT_NEAR(b.distance, 1.0, 1e-12);
  EXPECT_NEAR(b.arc_length, 1.5, 1e-12);
  EXPECT_NEAR(b.tangent.dot(Eigen::Vector3d(1, 1, 0).normalized()), 1.0, 1e-12);
}

TEST(Interpolate, IsExactForLinearFunctions)
{
  ScalarGrid grid({4, 5, 6}, {1.0, 2.0, 3.0}, 0.5);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 4; ++i) {
        const Eigen::Vector3d p = grid.point(i, j, k);
        grid.set(i, j, k, static_cast<float>(2 * p.x() - p.y() + 0.5 * p.z()));
      }
  const Eigen::Vector3d q(1.73, 3.1, 4.9);
  EXPECT_NEAR(interpolate(grid, q), 2 * q.x() - q.y() + 0.5 * q.z(), 1e-5);
}
