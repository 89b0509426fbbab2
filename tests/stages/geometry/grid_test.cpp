#include "common/error.hpp"
#include "common/vtk_files.hpp"
#include "stages/geometry/grid.hpp"
#include "stages/geometry/grid_vdb.hpp"
#include "stages/geometry/grid_vti.hpp"

#include <gtest/gtest.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>

#include <filesystem>

#include <unistd.h>

using namespace ligsim;
namespace fs = std::filesystem;

namespace {

/// A file name of this process (suites of several checkouts may run at once).
fs::path temp_file(const std::string& name)
{
  return fs::temp_directory_path() / (std::to_string(::getpid()) + "_" + name);
}

/// A sparse grid over an odd-sized box (bricks cut by its far faces) with a few values set.
ScalarGrid sample_grid()
{
  ScalarGrid grid({21, 10, 13}, {1.0, -2.0, 0.5}, 0.25, -1.5f);
  for (int k = 3; k < 13; k += 2)
    for (int j = 0; j < 10; j += 3)
      for (int i = 5; i < 21; ++i)
        grid.set(i, j, k, static_cast<float>(i + 100 * j + 10000 * k));
  return grid;
}

} // namespace

TEST(SparseGrid, StoresOnlyTheBricksWritten)
{
  ScalarGrid grid({200, 300, 400}, Eigen::Vector3d::Zero(), 0.1, 7.0f);
  EXPECT_EQ(grid.brick_count(), 0u);
  EXPECT_EQ(grid(123, 45, 67), 7.0f);
  grid.set(123, 45, 67, 1.0f);
  grid.set(120, 40, 64, 2.0f); // the same 8^3 brick
  grid.set(0, 0, 0, 3.0f);
  EXPECT_EQ(grid.brick_count(), 2u);
  EXPECT_EQ(grid(123, 45, 67), 1.0f);
  EXPECT_EQ(grid(120, 40, 64), 2.0f);
  EXPECT_EQ(grid(121, 40, 64), 7.0f); // stored brick, voxel not written
  EXPECT_EQ(grid.at(grid.index(0, 0, 0)), 3.0f);
  // 2.4e7 voxels in the box; two bricks and the brick table stored.
  EXPECT_LT(grid.memory_bytes(), 300000u);
  std::size_t visited = 0;
  grid.for_each_stored([&](const Eigen::Vector3i&, float) { ++visited; });
  EXPECT_EQ(visited, 2u * ScalarGrid::kBrickVoxels);
}

TEST(SparseGrid, VtiWrittenSlabBySlabReadsBackInVtk)
{
  const ScalarGrid grid = sample_grid();
  const fs::path file = temp_file("ligsim_sparse_grid.vti");
  write_vti(grid, "value", file);
  auto image = read_vti(file);
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(Eigen::Vector3i(dims[0], dims[1], dims[2]), grid.dims);
  EXPECT_DOUBLE_EQ(image->GetOrigin()[1], -2.0);
  EXPECT_DOUBLE_EQ(image->GetSpacing()[2], 0.25);
  vtkDataArray* values = image->GetPointData()->GetArray("value");
  ASSERT_NE(values, nullptr);
  ASSERT_EQ(static_cast<std::size_t>(values->GetNumberOfTuples()), grid.voxel_count());
  for (std::size_t i = 0; i < grid.voxel_count(); ++i)
    ASSERT_EQ(values->GetTuple1(static_cast<vtkIdType>(i)), grid.at(i)) << i;
  fs::remove(file);

  Mask mask({9, 3, 17}, Eigen::Vector3d::Zero(), 1.0);
  mask.set(8, 2, 16, 1);
  write_vti(mask, "inside", file);
  const auto mask_image = read_vti(file); // holds the array below
  vtkDataArray* inside = mask_image->GetPointData()->GetArray("inside");
  ASSERT_NE(inside, nullptr);
  EXPECT_EQ(inside->GetDataType(), VTK_UNSIGNED_CHAR);
  for (std::size_t i = 0; i < mask.voxel_count(); ++i)
    ASSERT_EQ(inside->GetTuple1(static_cast<vtkIdType>(i)), mask.at(i)) << i;
  fs::remove(file);
}

TEST(SparseGrid, VdbRoundTripKeepsGeometryValuesAndBackground)
{
  const ScalarGrid grid = sample_grid();
  const fs::path file = temp_file("ligsim_sparse_grid.vdb");
  vdb::write_grid(grid, "value", file);
  const ScalarGrid back = vdb::read_grid(file, "value");
  EXPECT_EQ(back.dims, grid.dims);
  EXPECT_EQ(back.origin, grid.origin);
  EXPECT_EQ(back.spacing, grid.spacing);
  EXPECT_EQ(back.background(), grid.background());
  for (std::size_t i = 0; i < grid.voxel_count(); ++i)
    ASSERT_EQ(back.at(i), grid.at(i)) << i;
  EXPECT_THROW(vdb::read_grid(file, "other"), InputError);
  // A spacing that is no binary fraction, far from the origin (the MCL's frame), comes back
  // exactly: measuring OpenVDB's transform (voxelSize()) gives 0.0499999999999545 for 0.05.
  ScalarGrid fine({9, 9, 9}, {578.1, 437.2, 449.3}, 0.05, 0.0f);
  fine.set(4, 4, 4, 1.0f);
  vdb::write_grid(fine, "fine", file);
  const ScalarGrid fine_back = vdb::read_grid(file, "fine");
  EXPECT_EQ(fine_back.spacing, 0.05);
  EXPECT_EQ(fine_back.origin, fine.origin);
  fs::remove(file);
  EXPECT_THROW(vdb::read_grid(file, "value"), InputError);
}
