#include "sim/membrane/mesh/generate.hpp"

#include "common/error.hpp"
#include "sim/membrane/mesh/delaunay.hpp"
#include "sim/membrane/mesh/topology.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace ligsim::membrane {
namespace {

double total_area(const MembraneMesh& mesh)
{
  double area = 0.0;
  for (int tri = 0; tri < mesh.triangle_count(); ++tri)
    area += rest_area(mesh, tri);
  return area;
}

TEST(MembraneMeshes, RectangleIsAValidManifoldOfTheRightArea)
{
  const MembraneMesh mesh = rectangle_mesh(10.0, 10.0, 0.4, 0.15, 7);
  EXPECT_EQ(manifold_problem(mesh), "");
  EXPECT_NEAR(total_area(mesh), 100.0, 1e-10);
  EXPECT_NEAR(mesh.triangle_count(), 1500, 60);
  EXPECT_GT(min_rest_angle(mesh), 10.0 * M_PI / 180.0);
}

TEST(MembraneMeshes, DiscIsAValidManifoldCloseToTheCircle)
{
  const double radius = 5.0;
  const MembraneMesh mesh = disc_mesh(radius, 0.3, 0.1, 3);
  EXPECT_EQ(manifold_problem(mesh), "");
  const int boundary_nodes = static_cast<int>(std::lround(2.0 * M_PI * radius / 0.3));
  const double polygon =
      0.5 * boundary_nodes * radius * radius * std::sin(2.0 * M_PI / boundary_nodes);
  EXPECT_NEAR(total_area(mesh), polygon, 1e-9);
  EXPECT_GT(min_rest_angle(mesh), 20.0 * M_PI / 180.0);
}

TEST(MembraneMeshes, DelaunayTrianglesHaveEmptyCircumcircles)
{
  std::mt19937 random(2);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  std::vector<Vec2> points;
  for (int i = 0; i < 300; ++i)
    points.emplace_back(coordinate(random), coordinate(random));
  const std::vector<Triangle> triangles = delaunay_triangulation(points);
  // Euler: 2 n - 2 - h triangles for n points with h on the hull.
  EXPECT_GT(triangles.size(), 2 * points.size() - 2 - 40);
  for (const Triangle& t : triangles) {
    const Vec2 &a = points[t[0]], &b = points[t[1]], &c = points[t[2]];
    ASSERT_GT(signed_area(a, b, c), 0.0);
    for (int i = 0; i < static_cast<int>(points.size()); ++i) {
      if (i == t[0] || i == t[1] || i == t[2])
        continue;
      // In-circle determinant: positive if points[i] is inside the circumcircle of (a, b, c).
      const Vec2 pa = a - points[i], pb = b - points[i], pc = c - points[i];
      const double det = pa.squaredNorm() * cross(pb, pc) - pb.squaredNorm() * cross(pa, pc) +
                         pc.squaredNorm() * cross(pa, pb);
      EXPECT_LE(det, 1e-12);
    }
  }
}

TEST(MembraneMeshes, RejectsSizesThatMakeNoMesh)
{
  EXPECT_THROW(rectangle_mesh(10.0, 10.0, 0.0, 0.1, 1), InputError);
  EXPECT_THROW(rectangle_mesh(10.0, 10.0, 8.0, 0.1, 1), InputError);
  EXPECT_THROW(disc_mesh(-1.0, 0.3, 0.1, 1), InputError);
}

} // namespace
} // namespace ligsim::membrane
