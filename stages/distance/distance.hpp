#pragma once
/// @brief Stage 2: distance from each voxel centre to the surface's triangles.

#include "stages/geometry/grid.hpp"

namespace ligsim {
class SurfaceQuery;
}

namespace ligsim::distance {

/// Signed distance to the triangles (exact closest point, not the distance to the voxel
/// boundary), positive inside the mask, negative outside, mm.
ScalarGrid signed_distance(const SurfaceQuery& query, const Mask& mask);

} // namespace ligsim::distance
