#include "common/error.hpp"
#include "stages/tetmesh/surface_check.hpp"
#include "tests/stages/tetmesh/test_surfaces.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ligsim::tetmesh {
namespace {

using ::testing::HasSubstr;

/// The message of the InputError that check_closed_surface throws, or "" if none.
std::string rejection(const TriangleSurface& surface)
{
  try {
    check_closed_surface(surface);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(TetmeshSurfaceCheck, CapsuleIsClosedWithAnalyticVolumeAndArea)
{
  const double r = 3, length = 20, pi = std::acos(-1.0);
  const TriangleSurface surface = test::capsule(r, length, 64);
  EXPECT_EQ(rejection(surface), "");
  // An inscribed polyhedron: a little less than the analytic values (0.3 % at 64 segments).
  const double volume = pi * r * r * length + 4.0 / 3.0 * pi * r * r * r;
  const double area = 2 * pi * r * length + 4 * pi * r * r;
  EXPECT_NEAR(signed_enclosed_volume_mm3(surface), volume, 0.005 * volume);
  EXPECT_LT(signed_enclosed_volume_mm3(surface), volume);
  EXPECT_NEAR(surface_area_mm2(surface), area, 0.005 * area);
}

TEST(TetmeshSurfaceCheck, EmptySurfaceIsRejected)
{
  EXPECT_THAT(rejection(TriangleSurface{}), HasSubstr("empty"));
}

TEST(TetmeshSurfaceCheck, MissingTriangleIsAnOpenSurfaceWithThreeBoundaryEdges)
{
  TriangleSurface surface = test::capsule(3, 20, 32);
  surface.F.conservativeResize(surface.F.rows() - 1, 3);
  EXPECT_THAT(rejection(surface), HasSubstr("open: 3 boundary edges"));
}

TEST(TetmeshSurfaceCheck, FlippedTriangleIsInconsistentOrientation)
{
  TriangleSurface surface = test::capsule(3, 20, 32);
  std::swap(surface.F(10, 1), surface.F(10, 2));
  EXPECT_THAT(rejection(surface), HasSubstr("inconsistently oriented: 3 edges"));
}

TEST(TetmeshSurfaceCheck, DuplicatedTriangleIsNonManifold)
{
  TriangleSurface surface = test::capsule(3, 20, 32);
  surface.F.conservativeResize(surface.F.rows() + 1, 3);
  surface.F.row(surface.F.rows() - 1) = surface.F.row(5);
  EXPECT_THAT(rejection(surface), HasSubstr("non-manifold: 3 edges"));
}

TEST(TetmeshSurfaceCheck, BadCoordinatesAndIndicesAreRejected)
{
  TriangleSurface nan = test::capsule(3, 20, 32);
  nan.V(7, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(rejection(nan), HasSubstr("vertex 7 has a non-finite coordinate"));

  TriangleSurface out_of_range = test::capsule(3, 20, 32);
  out_of_range.F(4, 2) = static_cast<int>(out_of_range.V.rows());
  EXPECT_THAT(rejection(out_of_range), HasSubstr("triangle 4 has vertex index"));

  TriangleSurface repeated = test::capsule(3, 20, 32);
  repeated.F(4, 2) = repeated.F(4, 0);
  EXPECT_THAT(rejection(repeated), HasSubstr("triangle 4 repeats a vertex"));
}

} // namespace
} // namespace ligsim::tetmesh
