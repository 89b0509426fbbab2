#include "tests/stages/shape_fixture.hpp"

#include <gtest/gtest.h>

using namespace ligsim;

// Analytic distance inside a cylinder of radius R from z = 0 to L: the nearer of the mantle and
// the caps. The 128-gon's sag, R (1 - cos(pi/128)) = 0.03 % of R, is far below the tolerance.
TEST(Distance, WithinTwoPercentOfTheAnalyticDistanceOnACylinder)
{
  const double R = 3.0, L = 30.0;
  const auto v = test::voxelise(synthetic::cylinder(R, L, 128), 0.25);
  int checked = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < v.mask.values.size(); ++i) {
    if (!v.mask.values[i])
      continue;
    const Eigen::Vector3d p = v.mask.point(i);
    const double exact = std::min({R - std::hypot(p.x(), p.y()), p.z(), L - p.z()});
    if (exact < v.mask.spacing) // sub-voxel accuracy is checked relative to distances >= 1 voxel
      continue;
    worst = std::max(worst, std::abs(v.distance.values[i] - exact) / exact);
    ++checked;
  }
  EXPECT_GT(checked, 10000);
  RecordProperty("worst_relative_error", std::to_string(worst));
  EXPECT_LT(worst, 0.02);
}

TEST(Distance, IsExactInABandOutsideAndClampedBeyond)
{
  const auto v = test::voxelise(synthetic::cylinder(3.0, 10.0), 0.5);
  const float far = static_cast<float>(-distance::kFarOutsideVoxels * 0.5);
  int band = 0, beyond = 0;
  for (std::size_t i = 0; i < v.mask.values.size(); ++i) {
    if (v.mask.values[i])
      continue;
    if (v.distance.values[i] == far) {
      ++beyond;
      EXPECT_GT(v.query.distance(v.mask.point(i)), 0.5 * 0.999); // at least a voxel from the inside
    } else {
      ++band;
      EXPECT_NEAR(-v.distance.values[i], v.query.distance(v.mask.point(i)), 1e-5);
    }
  }
  EXPECT_GT(band, 100);
  EXPECT_GT(beyond, 100);
}

TEST(Distance, IsSignedPositiveInside)
{
  const auto v = test::voxelise(synthetic::cylinder(3.0, 10.0), 0.5);
  for (std::size_t i = 0; i < v.mask.values.size(); ++i)
    if (std::abs(v.distance.values[i]) > 1e-6f) { // centres on the surface may fall either way
      EXPECT_EQ(v.distance.values[i] > 0.0f, v.mask.values[i] != 0) << i;
    }
}
