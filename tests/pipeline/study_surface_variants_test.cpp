/// pipeline/study/surface_variants on a sphere: offsets move the radius exactly, smoothing
/// removes bumps without shrinking, roughening has the asked rms, areas grow and shrink by
/// geodesic distance.

#include "pipeline/study/surface_variants.hpp"
#include "stages/geometry/surface_topology.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ligsim;
using namespace ligsim::study;

namespace {

/// A UV sphere of radius `r` (mm), outward triangles.
TriangleSurface sphere(double r, int rings, int segments)
{
  TriangleSurface s;
  s.V.resize(2 + (rings - 1) * segments, 3);
  s.V.row(0) << 0, 0, r;
  int v = 1;
  for (int i = 1; i < rings; ++i) {
    const double theta = M_PI * i / rings;
    for (int j = 0; j < segments; ++j, ++v) {
      const double phi = 2 * M_PI * j / segments;
      s.V.row(v) << r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi),
          r * std::cos(theta);
    }
  }
  const int south = v;
  s.V.row(south) << 0, 0, -r;
  std::vector<Eigen::Vector3i> faces;
  auto ring = [&](int i, int j) { return 1 + (i - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) {
    faces.push_back({0, ring(1, j), ring(1, j + 1)});
    faces.push_back({south, ring(rings - 1, j + 1), ring(rings - 1, j)});
  }
  for (int i = 1; i < rings - 1; ++i)
    for (int j = 0; j < segments; ++j) {
      faces.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      faces.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
  s.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    s.F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return s;
}

} // namespace

TEST(SurfaceVariants, OffsetMovesEveryVertexAlongTheOutwardNormal)
{
  const TriangleSurface s = sphere(5.0, 24, 48);
  ASSERT_GT(signed_volume(s), 0.0);
  for (double d : {-0.5, 0.25, 0.5}) {
    const TriangleSurface moved = offset_surface(s, d);
    const Eigen::VectorXd radii = moved.V.rowwise().norm();
    // Area-weighted normals of a UV sphere lean by a fraction of a degree off the radius.
    EXPECT_NEAR(radii.minCoeff(), 5.0 + d, 1e-3 * std::abs(d)) << d;
    EXPECT_NEAR(radii.maxCoeff(), 5.0 + d, 1e-3 * std::abs(d)) << d;
    EXPECT_EQ(moved.F, s.F);
  }
}

TEST(SurfaceVariants, RougheningHasTheAskedRmsAndSmoothingTakesNoiseAway)
{
  const TriangleSurface s = sphere(5.0, 32, 64);
  const TriangleSurface rough = roughen_surface(s, 0.2, 4, 7);
  const Eigen::VectorXd bumps = rough.V.rowwise().norm().array() - 5.0;
  const double rms = std::sqrt((bumps.array() - bumps.mean()).square().mean());
  EXPECT_NEAR(rms, 0.2, 0.01);
  EXPECT_EQ(roughen_surface(s, 0.2, 4, 7).V, rough.V); // seeded: reproducible

  // Taubin smoothing damps the bumps of a few edges (white noise: no averaging passes).
  const TriangleSurface noisy = roughen_surface(s, 0.2, 0, 7);
  // Compared with the clean sphere smoothed alike (the umbrella also slides vertices of the
  // uneven UV grid), half of the noise or more is gone.
  const TriangleSurface smoothed = smooth_surface(noisy, 10);
  const Eigen::VectorXd left =
      smoothed.V.rowwise().norm() - smooth_surface(s, 10).V.rowwise().norm();
  EXPECT_LT(std::sqrt(left.array().square().mean()), 0.5 * 0.2);
  // Taubin's pairs do not shrink the shape as plain Laplacian smoothing does.
  EXPECT_NEAR(signed_volume(smoothed) / signed_volume(s), 1.0, 0.03);
}

TEST(SurfaceVariants, AreasGrowAndShrinkByGeodesicDistance)
{
  const double r = 10.0;
  const TriangleSurface s = sphere(r, 90, 180);
  // The cap within 30 degrees of the north pole; 1 degree of arc is r pi / 180 = 0.1745 mm.
  auto cap = [&](double degrees) {
    std::vector<int> area;
    for (Eigen::Index v = 0; v < s.V.rows(); ++v)
      if (std::acos(std::clamp(s.V(v, 2) / r, -1.0, 1.0)) <= degrees * M_PI / 180.0 + 1e-9)
        area.push_back(static_cast<int>(v));
    return area;
  };
  const std::vector<int> area = cap(30.0);
  const double arc_mm = r * M_PI / 180.0;
  auto largest_angle = [&](const std::vector<int>& a) {
    double worst = 0.0;
    for (int v : a)
      worst = std::max(worst, std::acos(std::clamp(s.V(v, 2) / r, -1.0, 1.0)) * 180.0 / M_PI);
    return worst;
  };
  // Edge paths are at most a few percent longer than the arc on this grid: the grown cap
  // reaches 30 + 10 degrees within a grid step or two.
  const std::vector<int> grown = grow_area(s, area, 10 * arc_mm);
  EXPECT_NEAR(largest_angle(grown), 40.0, 2.1);
  EXPECT_GT(grown.size(), area.size());
  const std::vector<int> shrunk = grow_area(s, area, -10 * arc_mm);
  EXPECT_NEAR(largest_angle(shrunk), 20.0, 2.1);
  for (int v : shrunk)
    EXPECT_TRUE(std::binary_search(area.begin(), area.end(), v));
  EXPECT_TRUE(grow_area(s, area, -100.0).empty());
  EXPECT_EQ(grow_area(s, area, 0.0), area);
}
