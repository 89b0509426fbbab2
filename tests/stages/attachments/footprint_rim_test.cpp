#include "common/error.hpp"
#include "stages/attachments/footprint_rim.hpp"
#include "stages/synthetic/shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace ligsim::attachments {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The heights of the cylinder's rings of vertices, sorted.
std::vector<double> ring_heights(const TriangleSurface& surface)
{
  std::set<double> heights;
  for (Eigen::Index v = 0; v < surface.V.rows(); ++v)
    heights.insert(surface.V(v, 2));
  return {heights.begin(), heights.end()};
}

std::vector<int> vertices_between(const TriangleSurface& surface, double low, double high)
{
  std::vector<int> area;
  for (Eigen::Index v = 0; v < surface.V.rows(); ++v)
    if (surface.V(v, 2) >= low && surface.V(v, 2) <= high)
      area.push_back(static_cast<int>(v));
  return area;
}

TEST(FootprintRim, AnEndOfACylinderHasOneClosedRimHalfwayToTheNextRing)
{
  const TriangleSurface surface = synthetic::cylinder(3.0, 30.0, 24).surface;
  const std::vector<double> z = ring_heights(surface);
  ASSERT_GE(z.size(), 6u);
  const std::vector<FeatureLine> rims =
      footprint_rims(surface, vertices_between(surface, -1, z[2]));
  ASSERT_EQ(rims.size(), 1u);
  const FeatureLine& rim = rims[0];
  EXPECT_EQ(rim.front(), rim.back());
  // Through the midpoints of the 24 edges along the side and the 24 diagonals between two rings.
  EXPECT_EQ(rim.size(), 49u);
  for (const Eigen::Vector3d& p : rim)
    EXPECT_NEAR(p.z(), 0.5 * (z[2] + z[3]), 1e-12);
  // Nearly the circle: the diagonals' midpoints lie cos(pi / 24) inside it.
  EXPECT_NEAR(feature_length(rim), 2 * kPi * 3.0, 0.01 * 2 * kPi * 3.0);
}

TEST(FootprintRim, ABandAroundTheMiddleHasTwoRimsAndNoneWithoutAnEdge)
{
  const TriangleSurface surface = synthetic::cylinder(3.0, 30.0, 24).surface;
  const std::vector<double> z = ring_heights(surface);
  EXPECT_EQ(footprint_rims(surface, vertices_between(surface, z[2], z[4])).size(), 2u);
  EXPECT_TRUE(footprint_rims(surface, {}).empty());
  EXPECT_TRUE(footprint_rims(surface, vertices_between(surface, -1, 100)).empty());
}

TEST(FootprintRim, TheShareIsTheIndicatorInterpolatedOnTheTriangle)
{
  const TriangleSurface surface = synthetic::cylinder(3.0, 30.0, 24).surface;
  std::vector<bool> in_area(static_cast<std::size_t>(surface.V.rows()), false);
  const int a = surface.F(0, 0), b = surface.F(0, 1), c = surface.F(0, 2);
  in_area[static_cast<std::size_t>(a)] = true;
  const auto corner = [&](int v) -> Eigen::Vector3d { return surface.V.row(v).transpose(); };
  EXPECT_NEAR(footprint_share(surface, in_area, 0, corner(a)), 1.0, 1e-12);
  EXPECT_NEAR(footprint_share(surface, in_area, 0, corner(b)), 0.0, 1e-12);
  EXPECT_NEAR(footprint_share(surface, in_area, 0, 0.5 * (corner(a) + corner(c))), 0.5, 1e-12);
  EXPECT_NEAR(footprint_share(surface, in_area, 0, (corner(a) + corner(b) + corner(c)) / 3),
              1.0 / 3, 1e-12);
}

TEST(FootprintRim, AnOpenSurfaceAtTheRimIsAClearError)
{
  TriangleSurface surface = synthetic::cylinder(3.0, 30.0, 24).surface;
  const std::vector<double> z = ring_heights(surface);
  const std::vector<int> area = vertices_between(surface, -1, z[2]);
  // Drop a triangle that the rim crosses.
  Eigen::Index crossed = -1;
  for (Eigen::Index f = 0; f < surface.F.rows() && crossed < 0; ++f) {
    int inside = 0;
    for (int k = 0; k < 3; ++k)
      inside += std::binary_search(area.begin(), area.end(), surface.F(f, k));
    if (inside == 1 || inside == 2)
      crossed = f;
  }
  ASSERT_GE(crossed, 0);
  surface.F.row(crossed) = surface.F.row(surface.F.rows() - 1);
  surface.F.conservativeResize(surface.F.rows() - 1, 3);
  try {
    footprint_rims(surface, area);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("not closed"), std::string::npos) << error.what();
  }
}

} // namespace
} // namespace ligsim::attachments
