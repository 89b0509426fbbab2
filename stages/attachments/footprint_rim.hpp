#pragma once
/// @brief The rim of an attachment area: where the footprint ends on the ligament's surface, as
/// closed polylines that the tetmesh stage draws into the mesh and the model stage binds inside.

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace ligsim::attachments {

/// The 0.5 level of the area's indicator (1 on the area's vertices, 0 elsewhere, linear on each
/// triangle) on the closed surface `surface` (#V x 3, #F x 3): one segment across each triangle
/// with one or two corners in the area, from one mixed edge's midpoint to the other's, chained
/// into closed loops. The level set of a piecewise-linear function: loops never cross or touch,
/// and they enclose the area that Area::area_mm2 measures. `area`: sorted vertex indices. Empty
/// when the area is empty or the whole surface.
std::vector<FeatureLine> footprint_rims(const TriangleSurface& surface,
                                        const std::vector<int>& area);

/// The area's indicator at `point` on triangle `face` of `surface`, linearly interpolated
/// (barycentric) from its corners: > 0.5 inside the rim. `in_area`: #V flags.
double footprint_share(const TriangleSurface& surface, const std::vector<bool>& in_area, int face,
                       const Eigen::Vector3d& point);

/// The length of a polyline, mm.
double feature_length(const FeatureLine& line);

} // namespace ligsim::attachments
