#include "common/error.hpp"
#include "stages/geometry/surface_topology.hpp"
#include "stages/voxelize/level_set.hpp"
#include "tests/stages/shape_fixture.hpp"

#include <gtest/gtest.h>

using namespace ligsim;

TEST(Voxelize, MaskVolumeMatchesTheSurfaceVolume)
{
  for (auto shape :
       {synthetic::cylinder(3.0, 30.0), synthetic::torus_tube(), synthetic::ligament_band()}) {
    const double volume = signed_volume(shape.surface);
    const auto v = test::voxelise(std::move(shape), 0.3);
    const std::size_t inside = inside_count(v.mask);
    const double voxel_volume = inside * std::pow(v.mask.spacing, 3);
    EXPECT_NEAR(voxel_volume, volume, 0.02 * volume);
    // The padding keeps the border outside.
    EXPECT_EQ(v.mask(0, 0, 0), 0);
  }
}

TEST(Voxelize, AgreesWithPointInsideTestsOnARotatedShape)
{
  // OpenVDB decides the sign of the band voxels in single precision; on this torus two centres
  // of 0.5 mm voxels that lie 0.0013 and 0.013 mm from the surface come out on the other side.
  // Farther than 3 % of a voxel from the surface every centre must agree.
  constexpr double kSignUndecidedVoxels = 0.03;
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const auto v =
      test::voxelise(test::transformed(synthetic::torus_tube(), rotation, {1, 2, 3}), 0.5);
  int disagreements = 0;
  for (std::size_t i = 0; i < v.mask.voxel_count(); i += 7)
    if ((v.mask.at(i) != 0) != v.query.inside(v.mask.point(i)) &&
        v.query.distance(v.mask.point(i)) > kSignUndecidedVoxels * v.mask.spacing)
      ++disagreements;
  EXPECT_EQ(disagreements, 0);
}

TEST(Voxelize, DefaultSpacingIsAnEighthOfTheThickness)
{
  const auto band = synthetic::ligament_band(80, 12, 3);
  const double spacing = voxelize::default_spacing(band.surface);
  EXPECT_GT(spacing, 2.0 / 8);
  EXPECT_LT(spacing, 3.5 / 8);
}

TEST(Voxelize, KeepsTheRequestedSpacingExactlyFarFromTheOrigin)
{
  // In the MCL's frame OpenVDB's meshToVolume gave its grid a transform whose scale read back
  // as 0.0499999999999545 for 0.05, and the stages downstream inherited it.
  const synthetic::Shape shape = test::transformed(
      synthetic::cylinder(1.0, 2.0), Eigen::Matrix3d::Identity(), {578.1, 437.2, 449.3});
  voxelize::Parameters parameters;
  parameters.spacing_mm = 0.05;
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "ligsim_voxelize_spacing.vdb";
  const Mask mask = voxelize::voxelize(shape.surface, parameters, file);
  EXPECT_EQ(mask.spacing, 0.05);
  EXPECT_EQ(vdb::LevelSet::read(file).spacing_mm(), 0.05);
  std::filesystem::remove(file);
}

TEST(Voxelize, RefusesAGridTooLargeForMemory)
{
  voxelize::Parameters parameters;
  parameters.spacing_mm = 0.001;
  EXPECT_THROW(voxelize::voxelize(synthetic::cylinder().surface, parameters), InputError);
}

TEST(Voxelize, SignIsNotFooledByDefectsThatBreakRayParity)
{
  // Flipped triangles, duplicated triangles (two crossings where there is one) and an
  // overlapping inner shell: the inside is the same as the clean cylinder's.
  const TriangleSurface clean = synthetic::cylinder(3.0, 30.0).surface;
  TriangleSurface damaged = clean;
  const Eigen::Index n = damaged.F.rows();
  for (Eigen::Index f = 0; f < n; f += 9)
    damaged.F.row(f) = Eigen::RowVector3i(damaged.F(f, 0), damaged.F(f, 2), damaged.F(f, 1));
  const TriangleSurface inner = synthetic::cylinder(1.0, 10.0).surface;
  damaged.V.conservativeResize(clean.V.rows() + inner.V.rows(), 3);
  damaged.V.bottomRows(inner.V.rows()) = inner.V;
  damaged.F.conservativeResize(n + n / 5 + inner.F.rows(), 3);
  for (Eigen::Index f = 0; f < n / 5; ++f)
    damaged.F.row(n + f) = clean.F.row(5 * f);
  damaged.F.bottomRows(inner.F.rows()) = inner.F.array() + static_cast<int>(clean.V.rows());

  voxelize::Parameters parameters;
  parameters.spacing_mm = 0.3;
  const Mask expected = voxelize::voxelize(clean, parameters);
  const Mask mask = voxelize::voxelize(damaged, parameters);
  ASSERT_EQ(mask.dims, expected.dims);
  std::size_t disagreements = 0;
  for (std::size_t v = 0; v < mask.voxel_count(); ++v)
    disagreements += mask.at(v) != expected.at(v) ? 1 : 0;
  EXPECT_EQ(disagreements, 0u);
}
