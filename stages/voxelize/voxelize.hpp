#pragma once
/// @brief Stage 1: a closed surface to a binary inside/outside image.

#include "common/mesh.hpp"
#include "stages/geometry/grid.hpp"

#include <filesystem>

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

/// Marks the voxels whose centres lie inside `surface` (1) or outside (0): the sign of OpenVDB's
/// level set (a flood fill from outside, robust to non-manifold edges, self-intersections and
/// flipped triangles, which break ray parity). If `vdb_file` is given, the level set is also
/// written there. Throws InputError if the grid would exceed max_voxels.
Mask voxelize(const TriangleSurface& surface, const Parameters& parameters,
              const std::filesystem::path& vdb_file = {});

} // namespace ligsim::voxelize
