#pragma once
/// @brief Stage 2: distance from each voxel centre to the surface's triangles.

#include "stages/geometry/grid.hpp"

namespace ligsim {
class SurfaceQuery;
}

namespace ligsim::distance {

/// Value of the outside voxels beyond the band, in voxels (negative: outside).
inline constexpr double kFarOutsideVoxels = 2.0;

/// Signed distance to the triangles (exact closest point, not the distance to the voxel
/// boundary), positive inside the mask, negative outside, mm. Computed exactly for the inside
/// voxels and the outside voxels next to them (a one-voxel band, enough for interpolation at
/// the surface); outside voxels farther away hold -kFarOutsideVoxels * spacing.
ScalarGrid signed_distance(const SurfaceQuery& query, const Mask& mask);

} // namespace ligsim::distance
