#include "common/error.hpp"
#include "stages/geometry/surface_topology.hpp"
#include "tests/stages/shape_fixture.hpp"

#include <gtest/gtest.h>

using namespace ligsim;

TEST(Voxelize, MaskVolumeMatchesTheSurfaceVolume)
{
  for (auto shape :
       {synthetic::cylinder(3.0, 30.0), synthetic::torus_tube(), synthetic::ligament_band()}) {
    const double volume = signed_volume(shape.surface);
    const auto v = test::voxelise(std::move(shape), 0.3);
    std::size_t inside = 0;
    for (auto value : v.mask.values)
      inside += value;
    const double voxel_volume = inside * std::pow(v.mask.spacing, 3);
    EXPECT_NEAR(voxel_volume, volume, 0.02 * volume);
    // The padding keeps the border outside.
    EXPECT_EQ(v.mask(0, 0, 0), 0);
  }
}

TEST(Voxelize, AgreesWithPointInsideTestsOnARotatedShape)
{
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const auto v =
      test::voxelise(test::transformed(synthetic::torus_tube(), rotation, {1, 2, 3}), 0.5);
  int disagreements = 0;
  for (std::size_t i = 0; i < v.mask.values.size(); i += 7)
    disagreements += (v.mask.values[i] != 0) != v.query.inside(v.mask.point(i));
  EXPECT_EQ(disagreements, 0);
}

TEST(Voxelize, DefaultSpacingIsAnEighthOfTheThickness)
{
  const auto band = synthetic::ligament_band(80, 12, 3);
  const double spacing = voxelize::default_spacing(band.surface);
  EXPECT_GT(spacing, 2.0 / 8);
  EXPECT_LT(spacing, 3.5 / 8);
}

TEST(Voxelize, RefusesAGridTooLargeForMemory)
{
  SurfaceQuery query(synthetic::cylinder().surface);
  voxelize::Parameters parameters;
  parameters.spacing_mm = 0.001;
  EXPECT_THROW(voxelize::voxelize(query, parameters), InputError);
}
