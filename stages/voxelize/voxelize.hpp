#pragma once
/// @brief Stage 1: a closed surface to a binary inside/outside image.

#include "common/mesh.hpp"
#include "stages/geometry/grid.hpp"
#include "stages/voxelize/level_set.hpp"

#include <filesystem>

namespace ligsim::voxelize {

struct Parameters {
  double spacing_mm = 0.0; ///< voxel edge; <= 0: default_spacing()
  int padding_voxels = 2;  ///< empty voxels around the bounding box
  /// Refuse shapes with more inside voxels than this (memory guard: the grids are sparse, so
  /// memory follows the inside voxels, about 30 bytes each in the centerline stage).
  double max_voxels = 3.0e7;
};

/// The default voxel edge: an eighth of the surface's mean thickness 2V/A (for a thin plate of
/// thickness t, V/A -> t/2; for a cylinder of radius r it gives r), so a ligament is about
/// eight voxels thick.
double default_spacing(const TriangleSurface& surface);

/// The signed-distance level set of `surface` on the voxel box of `parameters` (OpenVDB: a
/// flood fill from outside decides the sign, robust to non-manifold edges, self-intersections
/// and flipped triangles, which break ray parity). Throws InputError if the shape would hold
/// more than max_voxels inside voxels.
vdb::LevelSet level_set(const TriangleSurface& surface, const Parameters& parameters);

/// Marks the voxels whose centres lie inside `surface` (1) or outside (0): the sign of
/// level_set(). If `vdb_file` is given, the level set is also written there.
Mask voxelize(const TriangleSurface& surface, const Parameters& parameters,
              const std::filesystem::path& vdb_file = {});

} // namespace ligsim::voxelize
