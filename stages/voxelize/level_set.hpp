#pragma once
/// @brief Signed-distance level sets of a triangle surface through OpenVDB (the one translation
/// unit that includes it), sampled at the voxel centres of our grids, and .vdb files of them for
/// Houdini and Blender.

#include "common/mesh.hpp"
#include "stages/geometry/grid.hpp"

#include <filesystem>

namespace ligsim::vdb {

/// Where the level set is computed: OpenVDB's meshToVolume, whose sign comes from a flood fill
/// of the outside, so it is not fooled by non-manifold edges, self-intersections, overlapping
/// shells or flipped triangles (which break ray parity).
struct LevelSetRequest {
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(); ///< centre of voxel (0, 0, 0), mm
  double spacing_mm = 1.0;
  double exterior_band_voxels = 3.0; ///< exact distances this far outside
  double interior_band_voxels = 3.0; ///< and this far inside (a huge value fills the inside)
};

/// Signed distance to `surface` at the grid's voxel centres, mm, negative inside (OpenVDB's
/// convention); beyond the bands, +-band width. If `vdb_file` is not empty the sparse grid is
/// also written there (atomically) as a level set named "surface".
ScalarGrid level_set(const TriangleSurface& surface, const LevelSetRequest& request,
                     const std::filesystem::path& vdb_file = {});

} // namespace ligsim::vdb
