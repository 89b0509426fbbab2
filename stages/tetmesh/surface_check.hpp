#pragma once
/// @brief Checks that a triangle surface can bound a volume: closed, edge-manifold, consistently
/// oriented.

#include "common/mesh.hpp"

namespace ligsim::tetmesh {

/// Throws InputError, naming the count and the location of the first offending edge, when
/// `surface` is empty, has an index out of range, a repeated vertex in a triangle, a
/// non-finite coordinate, a boundary edge (open), an edge shared by more than two triangles,
/// or two triangles with opposite orientation across an edge.
void check_closed_surface(const TriangleSurface& surface);

/// Volume enclosed by a closed surface, mm^3 (positive for outward-facing triangles).
double signed_enclosed_volume_mm3(const TriangleSurface& surface);

/// Total triangle area, mm^2.
double surface_area_mm2(const TriangleSurface& surface);

} // namespace ligsim::tetmesh
