#pragma once
/// @brief Stage 2: distance from each voxel centre to the surface's triangles.

#include "stages/geometry/grid.hpp"

namespace ligsim {
class SurfaceQuery;
}
namespace ligsim::vdb {
class LevelSet;
}

namespace ligsim::distance {

/// Value of the outside voxels beyond the band, in voxels (negative: outside).
inline constexpr double kFarOutsideVoxels = 2.0;

/// Signed distance to the triangles (exact closest point, not the distance to the voxel
/// boundary), positive inside, negative outside, mm, stored sparsely. The voxelize stage's
/// OpenVDB level set gives the sign (inside = its mask) and the voxels to compute: the inside
/// ones and the outside ones in its exterior band. Their distances come from `query` (CGAL's
/// AABB tree over the same triangles), exactly: OpenVDB fills the interior by passing the
/// closest triangle from voxel to voxel, which misses the closest triangle for about 1 % of
/// the voxels (by up to 1.5 voxels, near folds and corners). Outside voxels farther than
/// kFarOutsideVoxels (which covers the outside neighbours of every inside voxel, enough for
/// interpolation at the surface) hold -kFarOutsideVoxels * spacing.
ScalarGrid signed_distance(const vdb::LevelSet& level_set, const SurfaceQuery& query);

} // namespace ligsim::distance
