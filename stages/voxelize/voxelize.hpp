#pragma once
/// @brief Stage 1: a closed surface to a binary inside/outside image.

#include "common/mesh.hpp"
#include "stages/geometry/grid.hpp"

namespace ligsim {
class SurfaceQuery;
}

namespace ligsim::voxelize {

struct Parameters {
  double spacing_mm = 0.0;   ///< voxel edge; <= 0: default_spacing()
  int padding_voxels = 2;    ///< empty voxels around the bounding box
  double max_voxels = 3.0e7; ///< refuse grids larger than this (memory guard)
};

/// The default voxel edge: an eighth of the surface's mean thickness 2V/A (for a thin plate of
/// thickness t, V/A -> t/2; for a cylinder of radius r it gives r), so a ligament is about
/// eight voxels thick.
double default_spacing(const TriangleSurface& surface);

/// Marks the voxels whose centres lie inside `surface` (1) or outside (0). Uses one ray per
/// voxel column with parity counting, retrying a column whose crossings do not pair up.
/// Throws InputError if the grid would exceed max_voxels.
Mask voxelize(const SurfaceQuery& query, const Parameters& parameters);

} // namespace ligsim::voxelize
